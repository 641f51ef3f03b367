//! The gather (`light_paths` module doc, step 4): the multiply scattered light a seen point
//! receives from the light kept in one cell near it.
//!
//! L_o(ωo) = Σ_k S(ωk, ωo) cos θk · Φ_k over the cell's bins k, Φ_k the bin's share of
//! ∫ L dω (W/m²) and ωk its mean direction: the fibre's far-field BCSDF integrated against the
//! light by direction (Moon, Walter & Marschner 2008's gather, with direction bins in place of
//! their spherical harmonics). S cos θi is the shader's single scattering of unshadowed light, so the
//! units are the shader's (radiance per irradiance); a white-furnace test pins them (isotropic
//! light of share Φ gives a white Chiang fibre Φ/4π).
//!
//! One cell of the 2 × 2 × 2 around the point (between cell centres) is drawn with trilinear
//! probabilities from a hash of the point's index: the expectation is the trilinear blend of
//! the cells' light, at the cost of one cell, and the same point picks the same cell every run.

use super::LightPaths;
use super::moments::Moment;
use super::response::AngularResponse;
use crate::fiber::{Fiber, LightAtPoint, ShadingMode};
use glam::Vec3;

/// Light that crossed no fibre: the gather takes the shader's S cos θi per unit irradiance.
const UNSHADOWED: LightAtPoint = LightAtPoint::UNSHADOWED;

impl LightPaths {
    /// The multiply scattered radiance toward unit `wo` of a fibre of unit tangent `u` at `p`
    /// (W/(m²·sr), RGB): Σ S(ωi, ωo) cos θi × the record's share of ∫ L dω, over the records
    /// of one cell near `p`, chosen with trilinear probabilities by `pick` ∈ [0, 1)³.
    /// With [`super::Directions::Strongest`], `response` gathers the cell's other bins from
    /// their moments (`moments.rs`).
    pub fn indirect(
        &self,
        fiber: &Fiber,
        response: Option<&AngularResponse>,
        p: Vec3,
        u: Vec3,
        wo: Vec3,
        pick: Vec3,
    ) -> Vec3 {
        let Some(c) = self.pick_cell(p, pick) else {
            return Vec3::ZERO;
        };
        let slot = self.cells.slot[c] as usize;
        let (Some(&a), Some(&b)) = (self.starts.get(slot), self.starts.get(slot + 1)) else {
            return Vec3::ZERO;
        };
        let (a, b) = (a as usize, b as usize);
        let mut sum = Vec3::ZERO;
        for (wi, e) in self.from[a..b].iter().zip(&self.fluence[a..b]) {
            // S cos θi: single scattering of unshadowed light from ωi.
            sum += fiber.shade(ShadingMode::SingleScattering, u, *wi, wo, &UNSHADOWED) * *e;
        }
        if let (Some(rest), Some(response)) = (self.moments.get(slot), response) {
            sum += rest_of(rest, response, u, wo);
        }
        if sum.is_finite() {
            sum.max(Vec3::ZERO)
        } else {
            Vec3::ZERO
        }
    }

    /// The cell of the 2×2×2 around `p` (between cell centres) that `pick` draws with
    /// trilinear probabilities: its expectation is the trilinear blend of the cells' values.
    fn pick_cell(&self, p: Vec3, pick: Vec3) -> Option<usize> {
        let cells = &self.cells;
        let q = (p - cells.origin) / cells.cell_m - Vec3::splat(0.5);
        if !q.is_finite() {
            return None;
        }
        let f = q.floor();
        let t = q - f;
        let step = |t: f32, r: f32| if r < t { 1.0 } else { 0.0 };
        let c = f + Vec3::new(step(t.x, pick.x), step(t.y, pick.y), step(t.z, pick.z));
        let d = cells.dims.as_vec3();
        if c.x < 0.0 || c.y < 0.0 || c.z < 0.0 || c.x >= d.x || c.y >= d.y || c.z >= d.z {
            return None;
        }
        Some(cells.index(c.as_uvec3()))
    }
}

/// ∫ S cos θi L dωi for the light `rest` keeps as moments, toward unit `wo` from a fibre of
/// unit tangent `u`, through `response`'s tables.
pub(super) fn rest_of(rest: &Moment, response: &AngularResponse, u: Vec3, wo: Vec3) -> Vec3 {
    let sin_o = u.dot(wo).clamp(-1.0, 1.0);
    let w = (wo - u * sin_o).normalize_or_zero();
    // Along the fibre, every direction across it is ωo's: any pair will do (the tables' ww and
    // vv agree there).
    let (w, v) = if w == Vec3::ZERO {
        u.any_orthonormal_pair()
    } else {
        (w, u.cross(w))
    };
    rest.gather(&response.at(sin_o.asin()), (u, w, v))
}

/// Three numbers in [0, 1) from a hash of `i` (SplitMix64's finaliser), for
/// [`LightPaths::indirect`]'s cell choice: the same point picks the same cell every run.
pub fn pick_of(i: usize) -> Vec3 {
    let mut rng = crate::rng::SplitMix64::new(i as u64 ^ 0xC0FF_EE00_D15C_0BA1);
    Vec3::new(rng.unit(), rng.unit(), rng.unit())
}
