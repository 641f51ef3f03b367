//! What a light's shadows are made of, read together: the hair's light map ([`LightMap`]),
//! the opaque solids' entry depths in the same light frame ([`OccluderGrid`]) and, for skin
//! and clothes, the hair's finer shadow texture ([`SurfaceShadow`]). Each is built by its own
//! pass and owned there; a [`Shadow`] borrows one light's three, a [`Shadows`] every light's.
//!
//! Hair reads the map past the solids (the head shadows the hair behind it); a surface reads
//! the texture's optical depth of the hair in front of it times the solids' visibility, or the
//! map where there is no texture.

use super::occluders::NO_SOLIDS;
use super::surface::SurfaceShadow;
use super::{LightMap, OccluderGrid};
use crate::fiber::LightAtPoint;
use glam::{Affine3A, Vec3};

/// Where the hair and the head were when a hair map built for an earlier frame was made (the
/// hair maps at a lower rate than the frames, `engine::map_rate`): a frame lit by it reads
/// each render-strand point where it was then, and any other point of hair carried back with
/// the head, so the shadows move with the hair instead of staying where it was. Points of the
/// solids (skin, clothes) are read where they are, in the solids' grid and the skin texture,
/// which are built for every frame (in the old map's frame).
#[derive(Clone, Copy, Debug)]
pub struct BuiltEarlier<'a> {
    /// The render-strand points the maps were built from, indexed as now.
    pub positions: &'a [Vec3],
    /// World now → world then: the head's motion since, undone (rigid).
    pub head_back: Affine3A,
}

/// One light's shadows: its hair map, its solids' grid and its skin texture (if any).
#[derive(Clone, Copy, Debug)]
pub struct Shadow<'a> {
    pub hair: &'a LightMap,
    pub solids: &'a OccluderGrid,
    pub skin: Option<&'a SurfaceShadow>,
    /// `None` when the shadows were built for this frame.
    pub earlier: Option<BuiltEarlier<'a>>,
}

impl<'a> Shadow<'a> {
    /// The hair map alone: no solids, no skin texture.
    pub fn hair_only(hair: &'a LightMap) -> Self {
        Self {
            hair,
            solids: &NO_SOLIDS,
            skin: None,
            earlier: None,
        }
    }

    /// World point `p` of now where the shadows were built.
    #[inline]
    fn back(&self, p: Vec3) -> Vec3 {
        match &self.earlier {
            None => p,
            Some(e) => e.head_back.transform_point3(p),
        }
    }

    /// Direction `d` of now where the shadows were built.
    #[inline]
    fn back_dir(&self, d: Vec3) -> Vec3 {
        match &self.earlier {
            None => d,
            Some(e) => e.head_back.transform_vector3(d),
        }
    }

    /// Light reaching world point `p` through the hair and past the solids
    /// ([`LightMap::light_at`]).
    pub fn light_at(&self, p: Vec3) -> LightAtPoint {
        self.hair.light_past(self.solids, self.back(p))
    }

    /// The light reaching a point of a fibre the camera sees from `to_eye`
    /// ([`LightMap::light_at_seen`]), past the solids.
    pub fn light_at_seen(
        &self,
        p: Vec3,
        to_eye: Vec3,
        tangent: Vec3,
        fiber_radius_m: f32,
    ) -> LightAtPoint {
        let (p, to_eye, tangent) = (self.back(p), self.back_dir(to_eye), self.back_dir(tangent));
        self.hair
            .light_at_seen_past(self.solids, p, to_eye, tangent, fiber_radius_m)
    }

    /// [`Self::light_at_seen`] for render-strand point `vertex`, with its contact shadows
    /// when the map has them ([`LightMap::light_at_vertex_seen`]), past the solids.
    pub fn light_at_vertex_seen(
        &self,
        vertex: usize,
        p: Vec3,
        to_eye: Vec3,
        tangent: Vec3,
        fiber_radius_m: f32,
    ) -> LightAtPoint {
        let p = match &self.earlier {
            None => p,
            Some(e) => e
                .positions
                .get(vertex)
                .copied()
                .unwrap_or_else(|| e.head_back.transform_point3(p)),
        };
        let (to_eye, tangent) = (self.back_dir(to_eye), self.back_dir(tangent));
        self.hair
            .light_at_vertex_seen_past(self.solids, vertex, p, to_eye, tangent, fiber_radius_m)
    }

    /// Forward transmittance T_f (R, G, B) reaching a point of a surface (skin, clothes) at
    /// world point `p` facing the light, past the hair and the solids. With the skin texture:
    /// exp(−L)·V, L the texture's optical depth of the hair in front of the first solid along
    /// the ray (`super::surface`), V the solids' visibility. Without it: the map's
    /// [`LightMap::light_at`]. Read where `p` is (see [`BuiltEarlier`]).
    pub fn light_at_surface(&self, p: Vec3) -> Vec3 {
        let Some(surface) = self.skin else {
            return self.hair.light_past(self.solids, p).tf;
        };
        let m = self.hair.projection().point(p);
        if !m.is_finite() {
            return Vec3::ONE;
        }
        // No hair in front (most of the body): exp(−0) is exactly 1, without three `exp`s.
        let depth = surface.optical_depth(m);
        let hair = if depth == Vec3::ZERO {
            Vec3::ONE
        } else {
            (-depth).exp()
        };
        let tf = hair * self.solids.visibility(m);
        tf.clamp(Vec3::ZERO, Vec3::ONE)
    }

    /// Fraction of the light reaching world point `p` past the opaque solids alone (head,
    /// body; not the hair), in [0, 1].
    pub fn solid_visibility(&self, p: Vec3) -> f32 {
        self.solids.visibility(self.hair.projection().point(p))
    }

    /// How far a surface point is moved along its normal before a lookup, so the solid does
    /// not shadow itself ([`OccluderGrid::surface_offset_m`]).
    pub fn surface_offset_m(&self) -> f32 {
        self.solids.surface_offset_m()
    }
}

/// Every light's shadows, in the lights' order: `maps[k]`, `solids[k]` and `skin[k]` are light
/// k's. `solids` and `skin` may be shorter (no solids drawn): a light without them reads the
/// hair alone.
#[derive(Clone, Copy, Debug)]
pub struct Shadows<'a> {
    pub maps: &'a [LightMap],
    pub solids: &'a [OccluderGrid],
    pub skin: &'a [Option<SurfaceShadow>],
    /// `None` when the shadows were built for this frame.
    pub earlier: Option<BuiltEarlier<'a>>,
}

impl<'a> Shadows<'a> {
    /// The hair maps alone.
    pub fn hair_only(maps: &'a [LightMap]) -> Self {
        Self {
            maps,
            solids: &[],
            skin: &[],
            earlier: None,
        }
    }

    /// Light `k`'s shadows, or `None` past the last light.
    pub fn light(&self, k: usize) -> Option<Shadow<'a>> {
        Some(Shadow {
            hair: self.maps.get(k)?,
            solids: self.solids.get(k).unwrap_or(&NO_SOLIDS),
            skin: self.skin.get(k).and_then(Option::as_ref),
            earlier: self.earlier,
        })
    }

    /// The first light's map, which orders the shading's lookups.
    pub fn first_map(&self) -> Option<&'a LightMap> {
        self.maps.first()
    }
}
