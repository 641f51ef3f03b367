//! The per-vertex shaders: the tabulated BCSDF of either fibre model, single scattering, and
//! Zinke et al. 2008 Figure 5 (dual scattering), from the hair-frame angles (`angles.rs`) and
//! the light the map reports (`arriving.rs`).
//!
//! Everything here is f32, allocation-free and branch-light: it runs 100K–200K times a frame.
//!
//! **How the map's statistics combine (Figure 5).** T_f is the map's average over light rays of
//! ∏ ā_f over their crossings, where a ray with no crossing contributes 1 (Zinke Eq. 5, n = 0),
//! so T_f ≥ directFraction and the forward-*scattered* share is T_f − directFraction. We use
//! F = directFraction·(f_s + d_b f_back) + max(T_f − directFraction, 0)·d_f·G(θi)·(f_s^G +
//! π d_b f_back^G), as Figure 5 prints it but for G: T_f is a flux along the shadow path and a
//! fibre intercepts fluence, G = w/sin w (π/2 for Zinke's window) for a light in the fibre's
//! normal plane, falling to 1 for a light along the fibre (`dual::window_fluence_inclined`;
//! d_f·G is `Fiber::scattered_gain`, tabulated over sin²θi). The alternative T_f·d_f·(…)
//! counts unobstructed light twice: a fibre in full light would receive 1 + d_f = 2 times the
//! direct light (pinned by `dual_unshadowed_is_direct_only` in tests/lib/fiber_hard_cases.rs).
//! f_back of the direct path uses σ̄_b² alone (direct light has no forward spread);
//! f_back^G uses σ̄_b² + σ̄_f² (Eq. 24). f_back = 2 Ā_b g(θi + θo − Δ̄_b, σ̄_b²)/(π cos²θd) (Eqs. 10,
//! 15 with s̃_b = 1/π in every azimuth, as Figure 5 evaluates it).
//!
//! **Two models.** The composition is the same for both; only the lobes differ. Marschner: S cos θi
//! with S = Σ M_p N_p(|θd|, φ)/cos²θd, Gaussian M_p (broadened: variance + σ̄f²). Chiang: S cos θi
//! = ḡ = Σ M_p N̄_p(|θo|, φ) directly (no cosine division, exact at θi = ±90°), d'Eon M_p
//! (broadened: v_p + σ̄f², `longitudinal`), four lobes with the p ≥ 3 residual. f_back is
//! Zinke's cluster BCSDF for both. The model is matched once per call; each branch is
//! straight-line code over its interleaved table (one bilinear fetch of 5 or 7 lobes).
//!
//! **Local density.** Both Ā_b terms are multiplied by the truncation factor of
//! `backscatter::truncation` for `LightAtPoint::crossings_behind` (skipped, factor 1, for the
//! default +∞), so an isolated fibre gets no local back-scattering.
//!
//! **Single scattering** is S cos θi · direct_fraction: hard shadows, no forward-scattered light.
//!
//! **Degenerate input.** Zero or non-finite vectors give 0. The hair frame (`angles.rs`) gives
//! a direction along ±u the other direction's azimuth (trap 9) and measures azimuths from a
//! basis built from u alone (the eccentric cross-section's orientation, Duff et al. 2017).

mod angles;
mod arriving;

pub use angles::HairAngles;
pub(crate) use angles::Trig;
use arriving::DualLight;

use super::backscatter;
use super::marschner::COS_THETA_D_MIN;
use super::params::Lobe;
use super::{ChiangShading, Fiber, LightAtPoint, MarschnerShading, ModelShading};
use glam::Vec3;
use std::f32::consts::PI;

/// Unit-area Gaussian with variance `var` (rad²) at x (radians), per channel.
#[inline]
fn gauss3(x: Vec3, var: Vec3) -> Vec3 {
    let inv_two_pi_sqrt = 1.0 / (2.0 * PI).sqrt();
    let f = |x: f32, v: f32| {
        let v = v.max(1e-10);
        (-0.5 * x * x / v).exp() * inv_two_pi_sqrt / v.sqrt()
    };
    Vec3::new(f(x.x, var.x), f(x.y, var.y), f(x.z, var.z))
}

#[inline]
fn inv_cos2(theta_d: f32) -> f32 {
    let c = theta_d.cos().max(COS_THETA_D_MIN as f32);
    1.0 / (c * c)
}

#[inline]
fn finite_or_zero(v: Vec3) -> Vec3 {
    if v.is_finite() { v } else { Vec3::ZERO }
}

impl Fiber {
    /// The tabulated BCSDF per lobe [R, TT, TRT, p ≥ 3] at hair-frame angles, RGB, 1/sr (radiance
    /// = S cos θi E). Marschner: M_p N_p / cos²θd (Eq. 9, M normalised in θo; the fourth lobe is
    /// 0). Chiang: M_p N̄_p / cos θi with cos θi floored at 0.01 (trap 9's floor; `shade` uses
    /// S cos θi and needs no floor).
    pub fn bcsdf_lobes(&self, a: &HairAngles) -> [Vec3; 4] {
        match &self.model {
            ModelShading::Marschner(m) => {
                let [n_r, n_tt, ..] = m.lobes.lookup(a.theta_d().abs(), a.phi.abs());
                let [r, tt, trt] = self.marschner_lobes(m, a, n_r, n_tt, inv_cos2(a.theta_d()));
                [r, tt, trt, Vec3::ZERO]
            }
            ModelShading::Chiang(c) => {
                let n = c.lobes.lookup(a.theta_o.abs(), a.phi.abs());
                let g = chiang_lobes(c, &Trig::new(a), &n);
                let inv = 1.0 / a.theta_i.cos().max(COS_THETA_D_MIN as f32);
                g.map(|x| x * inv)
            }
        }
    }

    /// The BCSDF S summed over lobes, 1/sr.
    pub fn bcsdf(&self, a: &HairAngles) -> Vec3 {
        let [r, tt, trt, rest] = self.bcsdf_lobes(a);
        r + tt + trt + rest
    }

    /// Marschner's lobes with N_R and N_TT already looked up; `inv` = 1/cos²θd.
    #[inline]
    fn marschner_lobes(
        &self,
        m: &MarschnerShading,
        a: &HairAngles,
        n_r: Vec3,
        n_tt: Vec3,
        inv: f32,
    ) -> [Vec3; 3] {
        let theta_d = a.theta_d();
        let x = a.theta_i + a.theta_o;
        let n_trt = m
            .n_tables
            .lookup(Lobe::TRT, theta_d.abs(), a.phi.abs(), a.cos_2phi_h);
        let lobe = |l: usize| {
            let dx = x - m.mean_x[l];
            (dx * dx * m.m_exp[l]).exp() * m.m_norm[l] * inv
        };
        [n_r * lobe(0), n_tt * lobe(1), n_trt * lobe(2)]
    }

    /// SingleScattering mode: S cos θi · direct_fraction (hard shadows; module doc).
    pub(crate) fn shade_single(&self, a: &HairAngles, t: &Trig, light: &LightAtPoint) -> Vec3 {
        let direct = unit_or_zero(light.direct_fraction);
        if direct == 0.0 {
            return Vec3::ZERO;
        }
        let s_cos = match &self.model {
            ModelShading::Marschner(m) => {
                let [n_r, n_tt, ..] = m.lobes.lookup(a.theta_d().abs(), a.phi.abs());
                let [r, tt, trt] = self.marschner_lobes(m, a, n_r, n_tt, inv_cos2(a.theta_d()));
                (r + tt + trt) * t.ci
            }
            ModelShading::Chiang(c) => {
                let n = c.lobes.lookup(a.theta_o.abs(), a.phi.abs());
                let [r, tt, trt, rest] = chiang_lobes(c, t, &n);
                r + tt + trt + rest
            }
        };
        finite_or_zero(s_cos * direct)
    }

    /// The local back-scattering lobe shared by both models (Zinke Eqs. 10, 15): its weight
    /// d_b Ā_b · truncation · 2/(π cos²θd), its shift Δ̄_b and variance σ̄_b² (RGB), so that
    /// f_back = weight · g(θi + θo − Δ̄_b, σ̄_b² [+ σ̄f²]). `inv` = 1/cos²θd.
    #[inline]
    fn back_lobe(&self, a: &HairAngles, light: &LightAtPoint, inv: f32) -> (Vec3, Vec3, Vec3) {
        let (a_b, delta_b, sigma_b2) = self.dual.back_at(a.theta_i);
        let mut weight = a_b;
        if light.crossings_behind != LightAtPoint::DENSE {
            let (af, ab) = self.dual.attenuations_at(a.theta_i);
            weight *= backscatter::truncation(af, ab, light.crossings_behind);
        }
        (weight * (self.d_b * 2.0 / PI * inv), delta_b, sigma_b2)
    }

    /// DualScattering mode: Zinke 2008 Figure 5 (module doc for the combination). One branch
    /// per model, each straight-line code.
    pub(crate) fn shade_dual(&self, a: &HairAngles, t: &Trig, light: &LightAtPoint) -> Vec3 {
        let l = DualLight::new(light);
        let inv = inv_cos2(a.theta_d());
        let (back_w, delta_b, sigma_b2) = self.back_lobe(a, light, inv);
        let dx = Vec3::splat(a.theta_i + a.theta_o) - delta_b;
        let cos_i = t.ci;
        match &self.model {
            ModelShading::Marschner(m) => {
                // F = direct (f_s + f_back) + scattered gain (f_s^G + π f_back^G), times cos θi.
                let [n_r, n_tt, ng_r, ng_tt, ng_trt] =
                    m.lobes.lookup(a.theta_d().abs(), a.phi.abs());
                let mut out = Vec3::ZERO;
                if l.direct > 0.0 {
                    let [r, tt, trt] = self.marschner_lobes(m, a, n_r, n_tt, inv);
                    out += l.direct * (r + tt + trt + back_w * gauss3(dx, sigma_b2));
                }
                if l.any_scattered {
                    let x = a.theta_i + a.theta_o;
                    let mut f_s_g = Vec3::ZERO;
                    for (p, n_g) in [ng_r, ng_tt, ng_trt].into_iter().enumerate() {
                        let mp = gauss3(
                            Vec3::splat(x - m.mean_x[p]),
                            Vec3::splat(m.var_x[p]) + l.sigma_f2,
                        );
                        f_s_g += mp * n_g;
                    }
                    f_s_g *= inv;
                    let f_back_g = back_w * gauss3(dx, sigma_b2 + l.sigma_f2);
                    let gain = self.scattered_gain.at(t.si);
                    out += l.scattered * gain * (f_s_g + PI * f_back_g);
                }
                finite_or_zero(out * cos_i)
            }
            ModelShading::Chiang(c) => {
                // The lobes give ḡ = f_s cos θi directly; only f_back needs the cosine.
                let n = c.lobes.lookup(a.theta_o.abs(), a.phi.abs());
                let mut out = Vec3::ZERO;
                if l.direct > 0.0 {
                    let [r, tt, trt, rest] = chiang_lobes(c, t, &n);
                    out += l.direct * (r + tt + trt + rest + back_w * gauss3(dx, sigma_b2) * cos_i);
                }
                if l.any_scattered {
                    // N^G of the residual is N̄_3 (uniform in φ).
                    let [m_r, m_tt, m_trt, m_rest] =
                        c.deon.m_broadened_all(l.sigma_f2, t.si, t.ci, t.so, t.co);
                    let g_s_g = m_r * n[4] + m_tt * n[5] + m_trt * n[6] + m_rest * n[3];
                    let f_back_g = back_w * gauss3(dx, sigma_b2 + l.sigma_f2);
                    let gain = self.scattered_gain.at(t.si);
                    out += l.scattered * gain * (g_s_g + PI * cos_i * f_back_g);
                }
                finite_or_zero(out)
            }
        }
    }
}

/// Chiang's ḡ_p = M_p N̄_p per lobe [R, TT, TRT, p ≥ 3] (= S_p cos θi), from the interleaved
/// lookup `n` ([N̄_0..3, N^G_0..2]).
#[inline]
fn chiang_lobes(c: &ChiangShading, t: &Trig, n: &[Vec3; 7]) -> [Vec3; 4] {
    std::array::from_fn(|p| {
        let (so, co) = c.deon.tilted(p, t.so, t.co);
        n[p] * c.deon.m(p, t.si, t.ci, so, co)
    })
}

/// A fraction in [0, 1]; NaN and infinities read as 0.
#[inline]
pub(crate) fn unit_or_zero(x: f32) -> f32 {
    if x.is_finite() {
        x.clamp(0.0, 1.0)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests;
