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
use glam::Vec3;

/// One light's shadows: its hair map, its solids' grid and its skin texture (if any).
#[derive(Clone, Copy, Debug)]
pub struct Shadow<'a> {
    pub hair: &'a LightMap,
    pub solids: &'a OccluderGrid,
    pub skin: Option<&'a SurfaceShadow>,
}

impl<'a> Shadow<'a> {
    /// The hair map alone: no solids, no skin texture.
    pub fn hair_only(hair: &'a LightMap) -> Self {
        Self {
            hair,
            solids: &NO_SOLIDS,
            skin: None,
        }
    }

    /// Light reaching world point `p` through the hair and past the solids
    /// ([`LightMap::light_at`]).
    pub fn light_at(&self, p: Vec3) -> LightAtPoint {
        self.hair.light_past(self.solids, p)
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
        self.hair
            .light_at_vertex_seen_past(self.solids, vertex, p, to_eye, tangent, fiber_radius_m)
    }

    /// Forward transmittance T_f (R, G, B) reaching a point of a surface (skin, clothes) at
    /// world point `p` facing the light, past the hair and the solids. With the skin texture:
    /// exp(−L)·V, L the texture's optical depth of the hair in front of the first solid along
    /// the ray (`super::surface`), V the solids' visibility. Without it: [`Self::light_at`].
    pub fn light_at_surface(&self, p: Vec3) -> Vec3 {
        let Some(surface) = self.skin else {
            return self.light_at(p).tf;
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
}

impl<'a> Shadows<'a> {
    /// The hair maps alone.
    pub fn hair_only(maps: &'a [LightMap]) -> Self {
        Self {
            maps,
            solids: &[],
            skin: &[],
        }
    }

    /// Light `k`'s shadows, or `None` past the last light.
    pub fn light(&self, k: usize) -> Option<Shadow<'a>> {
        Some(Shadow {
            hair: self.maps.get(k)?,
            solids: self.solids.get(k).unwrap_or(&NO_SOLIDS),
            skin: self.skin.get(k).and_then(Option::as_ref),
        })
    }

    /// The first light's map, which orders the shading's lookups.
    pub fn first_map(&self) -> Option<&'a LightMap> {
        self.maps.first()
    }
}
