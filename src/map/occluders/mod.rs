//! Opaque occluders in the light's frame: the head and body block the light that reaches the
//! hair (and each other), as the hair blocks the light that reaches them.
//!
//! What: a depth grid across the light (a shadow map): for each texel, the depth along L at
//! which a ray through the texel centre first enters an opaque solid (+∞ where it meets none).
//! A point receives the light only if it lies before that depth; [`OccluderGrid::visibility`]
//! answers with a fraction in [0, 1] (`visibility.rs`).
//!
//! How, and why this way:
//! - Solids are given by their geometry (the same ellipsoids the raster draws), and each
//!   texel's entry depth is computed exactly by ray casting (`solids.rs`): O(texels in the
//!   solids' shadow × solids), a few thousand texels for a head. For a point light they are
//!   tessellated and rasterised as a mesh.
//! - A triangle mesh (a character's body, [`OccluderMesh`]) fills the same grid by rasterising
//!   its triangles across the light (`raster.rs`); the texel keeps the smallest depth of all
//!   solids and triangles. The minimum does not depend on the order or the split, so the grid
//!   is the same for any thread count.
//! - The texel is a quarter of a map cell, so the head's shadow on the hair has an edge about
//!   2 mm wide at the default resolution instead of a map cell's 7 mm stair-steps.
//! - The grid is not modulo-indexed: it covers the solids' own shadow (their bounding box
//!   across the light), capped at [`MAX_TEXELS`] a side (a larger scene gets coarser texels),
//!   and a point outside it is unoccluded.

mod raster;
mod solids;
mod visibility;

use super::{LightFrame, LightMap, Projection};
use glam::{Affine3A, Vec2, Vec3};
use raster::{TriangleSetup, rasterise_all};
use rayon::prelude::*;
use solids::{LightSolid, tessellate};

/// Largest grid side, texels (1024² f32 = 4 MB).
pub const MAX_TEXELS: usize = 1024;

/// An opaque solid: the unit sphere under an affine map (an ellipsoid or a sphere).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solid {
    pub unit_sphere_to_world: Affine3A,
}

/// An opaque triangle mesh in world space (vertex positions, and triangles as vertex indices).
#[derive(Clone, Copy, Debug)]
pub struct OccluderMesh<'a> {
    pub positions: &'a [Vec3],
    pub triangles: &'a [[u32; 3]],
}

impl OccluderMesh<'_> {
    /// No triangles.
    pub const EMPTY: OccluderMesh<'static> = OccluderMesh {
        positions: &[],
        triangles: &[],
    };
}

/// Entry depths of the solids across the light (see the module doc).
#[derive(Clone, Debug, Default)]
pub struct OccluderGrid {
    /// Lateral (y, z) of texel (0, 0)'s corner in the light frame, metres.
    origin: Vec2,
    texel_m: f32,
    /// How far a surface point is moved along its normal before a lookup (one and a half of
    /// the texels asked for), metres.
    surface_offset_m: f32,
    dims: [usize; 2],
    /// Entry depth along L per texel (row-major in y), metres; +∞ where no solid.
    depth: Vec<f32>,
    /// Scratch: the mesh's vertices in light-frame coordinates.
    mesh_light: Vec<Vec3>,
    /// Scratch: triangles of solids tessellated for a point light (indices into `mesh_light`).
    solid_triangles: Vec<[u32; 3]>,
    /// Scratch: the triangles set up for rasterising.
    triangle_setups: Vec<TriangleSetup>,
}

/// A grid with no solids, for lookups of the hair alone: every point is visible.
pub static NO_SOLIDS: OccluderGrid = OccluderGrid::EMPTY;

impl OccluderGrid {
    /// A grid with no solids: every point is visible.
    pub const EMPTY: OccluderGrid = OccluderGrid {
        origin: Vec2::ZERO,
        texel_m: 0.0,
        surface_offset_m: 0.0,
        dims: [0, 0],
        depth: Vec::new(),
        mesh_light: Vec::new(),
        solid_triangles: Vec::new(),
        triangle_setups: Vec::new(),
    };

    /// Recomputes the grid for `solids` and `mesh` in the light frame of `map` (after its
    /// build, which sets the frame), with texels of `texel_cells` of the map's cells (coarser
    /// where the solids span more than the grid's texels).
    pub fn build_for(
        &mut self,
        map: &LightMap,
        texel_cells: f32,
        solids: &[Solid],
        mesh: OccluderMesh,
    ) {
        let texel_m = texel_cells * map.geometry().ds_m;
        self.build_with_mesh(map.projection(), texel_m, solids, mesh);
        self.surface_offset_m = 1.5 * texel_m;
    }

    /// How far a point on a solid's surface is moved along its normal before a lookup, so the
    /// solid does not shadow itself through the grid's finite resolution ("normal offset"
    /// shadow mapping): one and a half texels, metres (0 for a grid not built for a map).
    pub fn surface_offset_m(&self) -> f32 {
        self.surface_offset_m
    }

    /// Upper bound, in bytes, of what a grid holds once built: at most `MAX_TEXELS`² depths.
    pub fn estimated_bytes() -> u64 {
        (MAX_TEXELS * MAX_TEXELS * size_of::<f32>()) as u64 + size_of::<OccluderGrid>() as u64
    }

    /// Recomputes the grid for `solids` in light frame `frame`, with texels of `texel_m`.
    /// Reuses its allocation. Degenerate or non-finite solids are skipped.
    pub fn build(&mut self, frame: &LightFrame, texel_m: f32, solids: &[Solid]) {
        self.build_with_mesh(
            &Projection::Parallel { frame: *frame },
            texel_m,
            solids,
            OccluderMesh::EMPTY,
        );
    }

    /// [`OccluderGrid::build`] with a triangle mesh as well (see the module doc). Triangles
    /// with an index out of range or a non-finite corner are skipped. For a point light (a
    /// central projection) the solids are tessellated and rasterised with the mesh
    /// (`solids.rs`).
    pub fn build_with_mesh(
        &mut self,
        proj: &Projection,
        texel_m: f32,
        solids: &[Solid],
        mesh: OccluderMesh,
    ) {
        let (frame, analytic) = self.project_mesh(proj, solids, mesh);
        let solids = LightSolid::in_frame(&frame, analytic);
        self.depth.clear();
        let extra = std::mem::take(&mut self.solid_triangles);
        let (mut lo, mut hi) = LightSolid::bounds(&solids);
        let mut any_triangle = false;
        for t in mesh.triangles.iter().chain(&extra) {
            let Some(c) = self.corners(t) else { continue };
            for p in c {
                lo = lo.min(Vec2::new(p.y, p.z));
                hi = hi.max(Vec2::new(p.y, p.z));
            }
            any_triangle = true;
        }
        if (solids.is_empty() && !any_triangle)
            || texel_m.is_nan()
            || texel_m <= 0.0
            || !texel_m.is_finite()
        {
            self.dims = [0, 0];
            self.solid_triangles = extra;
            return;
        }
        self.lay_out(lo, hi, texel_m);
        self.cast(&solids);
        self.rasterise(mesh.triangles, &extra);
        self.solid_triangles = extra;
    }

    /// The mesh's vertices in light-frame coordinates (`mesh_light`), and for a point light
    /// the solids tessellated after them (`solid_triangles`). Returns the light frame and the
    /// solids left to cast analytically (all of them for parallel light, none for a point
    /// light).
    fn project_mesh<'s>(
        &mut self,
        proj: &Projection,
        solids: &'s [Solid],
        mesh: OccluderMesh,
    ) -> (LightFrame, &'s [Solid]) {
        self.solid_triangles.clear();
        self.mesh_light.clear();
        self.mesh_light
            .extend(mesh.positions.iter().map(|p| proj.point(*p)));
        match *proj {
            Projection::Parallel { frame } => (frame, solids),
            Projection::Central { frame, .. } => {
                for s in solids {
                    tessellate(proj, s, &mut self.mesh_light, &mut self.solid_triangles);
                }
                (frame, &[][..])
            }
        }
    }

    /// Sizes the grid over the lateral box `lo..hi` with a texel of `texel_m` (coarser when
    /// the box would need over [`MAX_TEXELS`] a side), a texel of margin each side, every
    /// texel +∞.
    fn lay_out(&mut self, lo: Vec2, hi: Vec2, texel_m: f32) {
        let extent = hi - lo;
        let texel = texel_m.max(extent.max_element() / (MAX_TEXELS as f32 - 2.0));
        let dims = [
            ((extent.x / texel).ceil() as usize + 2).min(MAX_TEXELS),
            ((extent.y / texel).ceil() as usize + 2).min(MAX_TEXELS),
        ];
        self.origin = lo - Vec2::splat(texel);
        self.texel_m = texel;
        self.dims = dims;
        self.depth.resize(dims[0] * dims[1], f32::INFINITY);
    }

    /// Each texel's entry depth into the analytic `solids`, cast through its centre, in
    /// parallel over rows.
    fn cast(&mut self, solids: &[LightSolid]) {
        let (origin, texel) = (self.origin, self.texel_m);
        self.depth
            .par_chunks_mut(self.dims[1])
            .enumerate()
            .for_each(|(iy, row)| {
                for (iz, d) in row.iter_mut().enumerate() {
                    let yz = origin + (Vec2::new(iy as f32, iz as f32) + 0.5) * texel;
                    *d = LightSolid::first_entry(solids, yz);
                }
            });
    }

    /// Lowers the texels under the mesh's `triangles` and the tessellated solids' `extra` to
    /// their depth: the triangles set up once, then rasterised in parallel over bands of
    /// texel rows (`raster.rs`).
    fn rasterise(&mut self, triangles: &[[u32; 3]], extra: &[[u32; 3]]) {
        let mut setups = std::mem::take(&mut self.triangle_setups);
        setups.clear();
        for t in triangles.iter().chain(extra) {
            if let Some(c) = self.corners(t) {
                setups.extend(TriangleSetup::new(c, self.origin, self.texel_m, self.dims));
            }
        }
        rasterise_all(&mut self.depth, self.dims[1], &setups);
        self.triangle_setups = setups;
    }

    /// A triangle's corners in light-frame coordinates, if its indices are in range and its
    /// corners finite.
    fn corners(&self, t: &[u32; 3]) -> Option<[Vec3; 3]> {
        let c = [
            *self.mesh_light.get(t[0] as usize)?,
            *self.mesh_light.get(t[1] as usize)?,
            *self.mesh_light.get(t[2] as usize)?,
        ];
        c.iter().all(|p| p.is_finite()).then_some(c)
    }

    /// Whether any solid is in the grid.
    pub fn is_empty(&self) -> bool {
        self.depth.is_empty()
    }

    /// The grid as [`super::entry_depths::EntryDepths`] reads it: entry depths (row-major),
    /// dims, texel (0, 0)'s corner and the texel's width, metres.
    pub(super) fn depth_grid(&self) -> (&[f32], [usize; 2], Vec2, f32) {
        (&self.depth, self.dims, self.origin, self.texel_m)
    }

    /// The texel's width, metres.
    pub fn texel_m(&self) -> f32 {
        self.texel_m
    }
}

#[cfg(test)]
mod tests;
