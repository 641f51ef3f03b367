//! The fibre's response to light kept as angular moments (`moments.rs`): the far-field BCSDF
//! integrated against 1, ωi and ωi ωiᵀ over the sphere, tabulated over the outgoing
//! direction's inclination θo.
//!
//! A cell's light to second order is L(ω) ≈ (M₀ + 3 M₁·ω + (15/2) ωᵀ(M₂ − M₀ I/3) ω) / 4π, with
//! M₀ = ∫ L dω, M₁ = ∫ L ω dω and M₂ = ∫ L ω ωᵀ dω (its projection on the spherical
//! harmonics of order ≤ 2: the ℓ = 2 part of ωᵀTω is T's traceless part, and
//! ∫ (ωᵀTω) ω ωᵀ dω = (8π/15) T for a traceless T). The gather's
//! ∫ S(ωi, ωo) cos θi L(ωi) dωi is then a contraction of the moments with
//! A₀ = ∫ S cos θi dωi, A₁ = ∫ S cos θi ωi dωi and A₂ = ∫ S cos θi ωi ωiᵀ dωi.
//!
//! In the fibre's frame (u the tangent, w the outgoing direction's part across the fibre, v =
//! u × w) these depend on θo alone, and S is even in the azimuth φi − φo (Marschner's and
//! Chiang's azimuthal lobes are: the offset h and −h mirror each other), so the v parts of A₁
//! and the uv, wv parts of A₂ vanish: seven RGB numbers per θo, A₀, A₁·u, A₁·w, A₂'s uu, ww,
//! vv and uw. Why tables: the gather then costs a lookup and a few dot products per point
//! instead of one BCSDF evaluation per direction bin (64 with 8 × 8 bins).

use crate::fiber::{Fiber, LightAtPoint, ShadingMode};
use glam::Vec3;
use rayon::prelude::*;
use std::f32::consts::{FRAC_PI_2, PI, TAU};

/// Inclinations tabulated over [−π/2, π/2] (both ends included).
const INCLINATIONS: usize = 91;
/// Quadrature of the sphere per inclination: midpoints uniform in sin θi and in φi.
const SINE_STEPS: usize = 160;
const AZIMUTH_STEPS: usize = 96;

/// One inclination's integrals (module doc), each RGB.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct ResponseAt {
    pub(crate) a0: Vec3,
    pub(crate) a1_u: Vec3,
    pub(crate) a1_w: Vec3,
    pub(crate) a2_uu: Vec3,
    pub(crate) a2_ww: Vec3,
    pub(crate) a2_vv: Vec3,
    pub(crate) a2_uw: Vec3,
}

impl ResponseAt {
    fn lerp(&self, o: &ResponseAt, t: f32) -> ResponseAt {
        let l = |a: Vec3, b: Vec3| a + (b - a) * t;
        ResponseAt {
            a0: l(self.a0, o.a0),
            a1_u: l(self.a1_u, o.a1_u),
            a1_w: l(self.a1_w, o.a1_w),
            a2_uu: l(self.a2_uu, o.a2_uu),
            a2_ww: l(self.a2_ww, o.a2_ww),
            a2_vv: l(self.a2_vv, o.a2_vv),
            a2_uw: l(self.a2_uw, o.a2_uw),
        }
    }
}

/// A fibre's moment integrals over θo (module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct AngularResponse {
    at: Vec<ResponseAt>,
}

impl AngularResponse {
    /// Integrates `fiber`'s single scattering of unshadowed light (S cos θi, the gather's
    /// kernel) against 1, ωi and ωi ωiᵀ at each tabulated inclination. About 1.4 M BCSDF
    /// evaluations, spread over the threads; the same bits for any thread count.
    pub fn new(fiber: &Fiber) -> AngularResponse {
        let at = (0..INCLINATIONS)
            .into_par_iter()
            .map(|k| integrate_at(fiber, inclination(k)))
            .collect();
        AngularResponse { at }
    }

    /// The integrals at inclination `theta_o` (radians, clamped to [−π/2, π/2]), linear
    /// between the tabulated ones.
    pub(crate) fn at(&self, theta_o: f32) -> ResponseAt {
        let x = ((theta_o + FRAC_PI_2) / PI * (INCLINATIONS - 1) as f32)
            .clamp(0.0, (INCLINATIONS - 1) as f32);
        let x = if x.is_finite() { x } else { 0.0 };
        let k = (x as usize).min(INCLINATIONS - 2);
        self.at[k].lerp(&self.at[k + 1], x - k as f32)
    }
}

/// Tabulated inclination `k`, radians.
fn inclination(k: usize) -> f32 {
    -FRAC_PI_2 + PI * k as f32 / (INCLINATIONS - 1) as f32
}

/// The integrals at inclination `theta_o` in the frame u = z, w = x, v = y.
fn integrate_at(fiber: &Fiber, theta_o: f32) -> ResponseAt {
    let (u, w) = (Vec3::Z, Vec3::X);
    let wo = w * theta_o.cos() + u * theta_o.sin();
    let d_omega = (2.0 / SINE_STEPS as f32) * (TAU / AZIMUTH_STEPS as f32);
    let mut r = ResponseAt::default();
    let unshadowed = LightAtPoint::UNSHADOWED;
    for i in 0..SINE_STEPS {
        let s = -1.0 + (i as f32 + 0.5) * 2.0 / SINE_STEPS as f32;
        let c = (1.0 - s * s).max(0.0).sqrt();
        for j in 0..AZIMUTH_STEPS {
            let phi = (j as f32 + 0.5) * TAU / AZIMUTH_STEPS as f32;
            let wi = Vec3::new(c * phi.cos(), c * phi.sin(), s);
            let f = fiber.shade(ShadingMode::SingleScattering, u, wi, wo, &unshadowed) * d_omega;
            r.a0 += f;
            r.a1_u += f * wi.z;
            r.a1_w += f * wi.x;
            r.a2_uu += f * (wi.z * wi.z);
            r.a2_ww += f * (wi.x * wi.x);
            r.a2_vv += f * (wi.y * wi.y);
            r.a2_uw += f * (wi.z * wi.x);
        }
    }
    r
}
