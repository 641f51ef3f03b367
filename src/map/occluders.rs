//! Opaque occluders in the light's frame: the head and body block the light that reaches the
//! hair (and each other), as the hair blocks the light that reaches them.
//!
//! What: a depth grid across the light (a shadow map): for each texel, the depth along L at
//! which a ray through the texel centre first enters an opaque solid (+∞ where it meets none).
//! A point receives the light only if it lies before that depth; [`OccluderGrid::visibility`]
//! answers with a fraction in [0, 1].
//!
//! How, and why this way:
//! - Solids are given by their geometry (the same ellipsoids the raster draws), and each texel's
//!   entry depth is computed exactly by ray casting: O(texels in the solids' shadow × solids),
//!   a few thousand texels for a head.
//! - A triangle mesh (a character's body, [`OccluderMesh`]) fills the same grid by rasterising
//!   its triangles across the light: each texel centre inside a triangle's (y, z) projection
//!   takes the depth of the triangle's plane there, and the texel keeps the smallest depth of
//!   all solids and triangles (the entry point; front and back faces alike, so the mesh need
//!   not be closed or consistently wound). O(texels covered × layers), in parallel over bands
//!   of texel rows (each band takes the triangles that reach it); the minimum does not depend
//!   on the order or the split, so the grid is the same for any thread count.
//! - The texel is a quarter of a map cell, so the head's shadow on the hair has an edge about
//!   2 mm wide at the default resolution instead of a map cell's 7 mm stair-steps.
//! - Reading: where the four texels around the point all hit a solid, the entry depth is
//!   interpolated bilinearly and compared with the point's depth, with a smooth step of a
//!   texel's width: on a smooth surface the interpolated depth follows the surface, so points on
//!   the lit side of a solid never shadow themselves ("shadow acne") and points beyond it fade
//!   over a texel. Where some texels miss (the silhouette of the shadow), each texel votes with
//!   its own comparison, weighted bilinearly: the shadow's edge is antialiased over one texel.
//! - The grid is not modulo-indexed: it covers the solids' own shadow (their bounding box across
//!   the light), capped at `MAX_TEXELS` a side (a larger scene gets coarser texels), and a point
//!   outside it is unoccluded.

use super::{LightFrame, LightMap, Projection};
use crate::tri_span;
use glam::{Affine3A, Vec2, Vec3, Vec4};
use rayon::prelude::*;

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

/// Texel rows per parallel band of the triangle raster.
const RASTER_BAND_ROWS: usize = 16;

/// A triangle across the light, ready to rasterise into a grid: its corners in texel
/// coordinates (texel centres at integers), their depths, the inverse of twice its signed
/// area, and the texel centres its box holds (rows `i0..=i1`, columns `j0..=j1`).
#[derive(Clone, Copy, Debug)]
struct TriangleSetup {
    q: [Vec2; 3],
    depth: [f32; 3],
    inv: f32,
    i0: i64,
    i1: i64,
    j0: i64,
    j1: i64,
}

impl TriangleSetup {
    /// The columns of texel row `i` within the box whose centres the triangle can cover:
    /// those inside its span at that row (`crate::tri_span::span`); an empty range
    /// (`j0 > j1`) where it has no part there.
    fn columns(&self, i: i64) -> (i64, i64) {
        match tri_span::span(self.q, (i as f32, i as f32)) {
            Some((lo, hi)) => (
                (lo.ceil() as i64).max(self.j0),
                (hi.floor() as i64).min(self.j1),
            ),
            None => (self.j0, self.j0 - 1),
        }
    }

    /// The triangle with light-frame corners `c` in a grid of `dims` texels of `texel` metres
    /// from `origin`, or `None` when it is edge-on to the light (no area to cover: its
    /// neighbours cover the silhouette) or covers no texel centre.
    fn new(c: [Vec3; 3], origin: Vec2, texel: f32, dims: [usize; 2]) -> Option<Self> {
        let q = c.map(|p| (Vec2::new(p.y, p.z) - origin) / texel - 0.5);
        let area2 = (q[1] - q[0]).perp_dot(q[2] - q[0]);
        if area2.is_nan() || area2.abs() <= 1e-9 {
            return None;
        }
        let lo = q[0].min(q[1]).min(q[2]).ceil().max(Vec2::ZERO);
        let hi = q[0].max(q[1]).max(q[2]).floor();
        let (i1, j1) = (
            (hi.x.min(dims[0] as f32 - 1.0)) as i64,
            (hi.y.min(dims[1] as f32 - 1.0)) as i64,
        );
        let (i0, j0) = (lo.x as i64, lo.y as i64);
        (i0 <= i1 && j0 <= j1).then_some(TriangleSetup {
            q,
            depth: c.map(|p| p.x),
            inv: 1.0 / area2,
            i0,
            i1,
            j0,
            j1,
        })
    }

    /// Lowers each texel of rows `band` (`rows`: those rows, `cols` texels each) whose centre
    /// lies inside the triangle to the depth of the triangle's plane there. A row visits only
    /// the columns its part of the triangle can reach (`crate::tri_span`), the same texels
    /// the whole box gave.
    fn rasterise(&self, band: std::ops::Range<usize>, cols: usize, rows: &mut [f32]) {
        let (i0, i1) = (
            self.i0.max(band.start as i64),
            self.i1.min(band.end as i64 - 1),
        );
        let q = &self.q;
        let narrow = i0 <= i1 && tri_span::narrowable(*q);
        let (inv, lanes) = (Vec4::splat(self.inv), Vec4::new(0.0, 1.0, 2.0, 3.0));
        for i in i0..=i1 {
            let (j0, j1) = if narrow {
                self.columns(i)
            } else {
                (self.j0, self.j1)
            };
            // Four centres of the row side by side, each lane the arithmetic of one centre
            // p = (i, j) in the order the scalar test had: (qₐ − p).perp_dot(q_b − p) × inv,
            // then the depth as Σ lₖ·depthₖ left to right: the same bits.
            let fi = i as f32;
            let ax = [q[0].x - fi, q[1].x - fi, q[2].x - fi].map(Vec4::splat);
            let mut j = j0;
            while j <= j1 {
                let pj = Vec4::splat(j as f32) + lanes;
                let ay = [
                    Vec4::splat(q[0].y) - pj,
                    Vec4::splat(q[1].y) - pj,
                    Vec4::splat(q[2].y) - pj,
                ];
                let l0 = (ax[1] * ay[2] - ay[1] * ax[2]) * inv;
                let l1 = (ax[2] * ay[0] - ay[2] * ax[0]) * inv;
                let l2 = (ax[0] * ay[1] - ay[0] * ax[1]) * inv;
                let inside =
                    (l0.cmpge(Vec4::ZERO) & l1.cmpge(Vec4::ZERO) & l2.cmpge(Vec4::ZERO)).bitmask();
                if inside != 0 {
                    let d =
                        (l0 * self.depth[0] + l1 * self.depth[1] + l2 * self.depth[2]).to_array();
                    let row = (i as usize - band.start) * cols;
                    for (k, d) in d.iter().enumerate() {
                        let jk = j + k as i64;
                        if inside & (1 << k) != 0 && jk <= j1 {
                            let texel = &mut rows[row + jk as usize];
                            *texel = texel.min(*d);
                        }
                    }
                }
                j += 4;
            }
        }
    }
}

/// Tessellation of a solid for a point light's map: latitude bands and longitude slices of
/// the unit sphere. With 32 slices a chord lies within 1 − cos(π/32) = 0.5% of the radius
/// inside the surface (0.4 mm on a 9 cm head, a tenth of an occluder texel).
const SPHERE_STACKS: u32 = 16;
const SPHERE_SLICES: u32 = 32;

/// A grid with no solids, for lookups of the hair alone: every point is visible.
pub static NO_SOLIDS: OccluderGrid = OccluderGrid::EMPTY;

impl OccluderGrid {
    /// A grid with no solids: every point is visible.
    pub const EMPTY: OccluderGrid = OccluderGrid {
        origin: Vec2::ZERO,
        texel_m: 0.0,
        dims: [0, 0],
        depth: Vec::new(),
        mesh_light: Vec::new(),
        solid_triangles: Vec::new(),
        triangle_setups: Vec::new(),
    };

    /// Recomputes the grid for `solids` and `mesh` in the light frame of `map` (after its
    /// build, which sets the frame), with texels of [`LightMap::occluder_texel_m`].
    pub fn build_for(&mut self, map: &LightMap, solids: &[Solid], mesh: OccluderMesh) {
        self.build_with_mesh(map.projection(), map.occluder_texel_m(), solids, mesh);
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
    /// with an index out of range or a non-finite corner are skipped.
    ///
    /// For a point light (a central projection) the solids are tessellated
    /// ([`SPHERE_STACKS`] × [`SPHERE_SLICES`]) and rasterised with the mesh, corners projected:
    /// the projection keeps straight lines straight, so a flat triangle stays flat across the
    /// light and its depth is interpolated linearly between corners (exact at the corners,
    /// within the depth change of a triangle elsewhere).
    pub fn build_with_mesh(
        &mut self,
        proj: &Projection,
        texel_m: f32,
        solids: &[Solid],
        mesh: OccluderMesh,
    ) {
        self.solid_triangles.clear();
        self.mesh_light.clear();
        self.mesh_light
            .extend(mesh.positions.iter().map(|p| proj.point(*p)));
        let (frame, analytic) = match *proj {
            Projection::Parallel { frame } => (frame, solids),
            Projection::Central { frame, .. } => {
                for s in solids {
                    self.tessellate(proj, s);
                }
                (frame, &[][..])
            }
        };
        // Each solid in light-frame coordinates, with its lateral bounding box.
        let solids: Vec<(Affine3A, Vec2, Vec2)> = analytic
            .iter()
            .filter_map(|s| {
                let world_to_light = Affine3A::from_mat3(
                    glam::Mat3::from_cols(frame.x, frame.y, frame.z).transpose(),
                );
                let to_light = world_to_light * s.unit_sphere_to_world;
                let m = glam::Mat3::from(to_light.matrix3);
                let det = m.determinant();
                if !(det.abs() > 1e-30 && det.is_finite() && to_light.translation.is_finite()) {
                    return None;
                }
                // Half-extent of an ellipsoid along axis a is |row a of M|.
                let c = Vec3::from(to_light.translation);
                let half = Vec2::new(m.row(1).length(), m.row(2).length());
                let centre = Vec2::new(c.y, c.z);
                Some((to_light, centre - half, centre + half))
            })
            .collect();
        self.depth.clear();
        let extra = std::mem::take(&mut self.solid_triangles);
        let (mut lo, mut hi) = solids.iter().fold(
            (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN)),
            |(lo, hi), s| (lo.min(s.1), hi.max(s.2)),
        );
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
        let origin = self.origin;
        self.depth
            .par_chunks_mut(dims[1])
            .enumerate()
            .for_each(|(iy, row)| {
                for (iz, d) in row.iter_mut().enumerate() {
                    let yz = origin + (Vec2::new(iy as f32, iz as f32) + 0.5) * texel;
                    *d = solids
                        .iter()
                        .filter(|s| yz.cmpge(s.1).all() && yz.cmple(s.2).all())
                        .filter_map(|s| entry_depth(&s.0, yz))
                        .fold(f32::INFINITY, f32::min);
                }
            });
        // Triangles set up once, then rasterised in parallel over bands of texel rows, each
        // band taking the triangles that reach it. A texel keeps the minimum depth, which does
        // not depend on the order or the split: the same bits for any thread count.
        let mut setups = std::mem::take(&mut self.triangle_setups);
        setups.clear();
        for t in mesh.triangles.iter().chain(&extra) {
            if let Some(c) = self.corners(t) {
                setups.extend(TriangleSetup::new(c, origin, texel, dims));
            }
        }
        let cols = dims[1];
        self.depth
            .par_chunks_mut(RASTER_BAND_ROWS * cols)
            .enumerate()
            // One job per band, as the solids cover few of them (`raster::lines` says why).
            .with_max_len(1)
            .for_each(|(b, rows)| {
                let band = b * RASTER_BAND_ROWS..(b * RASTER_BAND_ROWS + rows.len() / cols);
                for t in &setups {
                    t.rasterise(band.clone(), cols, rows);
                }
            });
        self.triangle_setups = setups;
        self.solid_triangles = extra;
    }

    /// Appends solid `s` as triangles (corners projected by `proj`) to the scratch mesh.
    fn tessellate(&mut self, proj: &Projection, s: &Solid) {
        let base = self.mesh_light.len() as u32;
        let ring = SPHERE_SLICES + 1;
        for i in 0..=SPHERE_STACKS {
            let polar = std::f32::consts::PI * i as f32 / SPHERE_STACKS as f32;
            for j in 0..ring {
                let azimuth = std::f32::consts::TAU * j as f32 / SPHERE_SLICES as f32;
                let unit = Vec3::new(
                    polar.sin() * azimuth.cos(),
                    polar.cos(),
                    polar.sin() * azimuth.sin(),
                );
                let world = s.unit_sphere_to_world.transform_point3(unit);
                self.mesh_light.push(proj.point(world));
            }
        }
        for i in 0..SPHERE_STACKS {
            for j in 0..SPHERE_SLICES {
                let a = base + i * ring + j;
                let b = a + ring;
                self.solid_triangles.push([a, b, a + 1]);
                self.solid_triangles.push([a + 1, b, b + 1]);
            }
        }
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

    /// The depth along the light (light-frame metres) at which a ray near light-frame point
    /// `m` first enters a solid: the shallowest of the 5 × 5 texels around `m`'s texel (+∞
    /// where none of them meets a solid). Nothing beyond it can shadow a lit point on the
    /// first surface that rays there meet; taking the neighbours' too keeps hair behind a
    /// solid's silhouette off the surface points at the silhouette, which read across it.
    #[inline]
    pub fn entry_depth(&self, m: Vec3) -> f32 {
        if self.depth.is_empty() || !m.is_finite() {
            return f32::INFINITY;
        }
        let t = (Vec2::new(m.y, m.z) - self.origin) / self.texel_m;
        let (ic, jc) = (t.x.floor() as i64, t.y.floor() as i64);
        let mut shallowest = f32::INFINITY;
        for i in ic - 2..=ic + 2 {
            for j in jc - 2..=jc + 2 {
                if i >= 0 && j >= 0 && (i as usize) < self.dims[0] && (j as usize) < self.dims[1] {
                    shallowest = shallowest.min(self.depth[i as usize * self.dims[1] + j as usize]);
                }
            }
        }
        shallowest
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

    /// Fraction of the light reaching light-frame point `m` (metres) past the solids, in [0, 1].
    /// The shadow begins at the entry depth and is complete one texel further along the light,
    /// so a point on the lit surface of a solid (or just outside it, as hair roots are) is lit.
    #[inline]
    pub fn visibility(&self, m: Vec3) -> f32 {
        if self.depth.is_empty() || !m.is_finite() {
            return 1.0;
        }
        let t = (Vec2::new(m.y, m.z) - self.origin) / self.texel_m - 0.5;
        let f = t.floor();
        let (w, (i0, j0)) = (t - f, (f.x as i64, f.y as i64));
        let at = |i: i64, j: i64| -> f32 {
            if i < 0 || j < 0 || i as usize >= self.dims[0] || j as usize >= self.dims[1] {
                f32::INFINITY
            } else {
                self.depth[i as usize * self.dims[1] + j as usize]
            }
        };
        let d = [
            at(i0, j0),
            at(i0, j0 + 1),
            at(i0 + 1, j0),
            at(i0 + 1, j0 + 1),
        ];
        let wts = [
            (1.0 - w.x) * (1.0 - w.y),
            (1.0 - w.x) * w.y,
            w.x * (1.0 - w.y),
            w.x * w.y,
        ];
        let shadowed = |depth: f32| ((m.x - depth) / self.texel_m).clamp(0.0, 1.0);
        if d.iter().all(|v| v.is_finite()) {
            let depth = d.iter().zip(&wts).map(|(d, w)| d * w).sum::<f32>();
            1.0 - shadowed(depth)
        } else {
            1.0 - d
                .iter()
                .zip(&wts)
                .filter(|(d, _)| d.is_finite())
                .map(|(d, w)| w * shadowed(*d))
                .sum::<f32>()
        }
    }
}

/// Depth along the light frame's X at which the line {(x, yz)} enters the ellipsoid
/// `m(unit sphere)` (m maps to light-frame coordinates), or None when it misses.
fn entry_depth(m: &Affine3A, yz: Vec2) -> Option<f32> {
    let inv = m.inverse();
    let o = inv.transform_point3(Vec3::new(0.0, yz.x, yz.y));
    let d = inv.transform_vector3(Vec3::X);
    // |o + t d|² = 1.
    let a = d.length_squared();
    let b = o.dot(d);
    let c = o.length_squared() - 1.0;
    let disc = b * b - a * c;
    (disc >= 0.0 && a > 0.0).then(|| (-b - disc.sqrt()) / a)
}

#[cfg(test)]
mod tests;
