//! Sampling the Chiang 2016 fibre model (`chiang.rs`): where light arriving from one direction
//! leaves, for tracing light through hair (`crate::light_paths`).
//!
//! The near-field model at offset h (`chiang.rs`, module doc) is a sum of lobes, each a product
//! of densities: g = Σ_p A_p(θ, h) M_p(θ', θ) N_p(φ − Φ_p(θ, h)) (p ≥ 3: N uniform). Drawing
//! h uniform in [−1, 1], a lobe p with probability P_p (the mean of A_p's channels over their
//! sum), θ' from M_p and φ from N_p gives a direction whose weight A_p / P_p has, per channel,
//! the expectation of ∫ ḡ over any set of directions: the far-field model averaged over the
//! fibre's width, which is what a fibre a light path meets at a random offset does. pbrt-v3
//! §9.9.6 samples the same densities; the inversions below are the densities' own:
//!
//! - d'Eon's M with variance v about −θ (tilted per lobe): with ξ ∈ (0, 1],
//!   cos ϑ = 1 + v ln(ξ + (1 − ξ)e^{−2/v}) is the cosine of the angle from the lobe's peak
//!   direction of a von Mises–Fisher-like density in 3-D, and the azimuth ψ about it is uniform;
//!   the sampled sin θ' = −cos ϑ sin θ + sin ϑ cos ψ cos θ, ψ = 2πξ (the rotation of a
//!   direction at angle ϑ from the peak, d'Eon et al. 2011; pbrt-v3 §9.9.6 samples it so).
//! - The trimmed logistic of scale s: the inverse of its CDF on [−π, π]
//!   ([`TrimmedLogistic::sample`]).
//!
//! Light paths use the model with the given direction in the role of ωo: the model is not
//! exactly reciprocal (`chiang.rs`, "Reciprocity": 5% within |θ| ≤ 60°), and a path tracer
//! (Mitsuba's `hair` BSDF) samples from the camera's side.

// `!(a < b)` on floats is meant: it is true for NaN, which must take the safe branch.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::chiang::{
    ChiangConstants, N_LOBES, RESIDUAL, TrimmedLogistic, attenuation, refracted_gamma,
};
use glam::DVec3;
use std::f64::consts::PI;

/// A direction leaving the fibre and its weight per channel (A_p / P_p).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scattered {
    /// Unit, away from the fibre.
    pub dir: DVec3,
    /// What the arriving power is multiplied by, RGB (≥ 0).
    pub weight: [f64; 3],
    /// The lobe drawn (0 R, 1 TT, 2 TRT, 3 the p ≥ 3 residual).
    pub lobe: usize,
}

/// Draws where light leaves a fibre of one [`ChiangConstants`] (module doc), with what every
/// draw shares computed once: the logistic, and per lobe the sine and cosine of its tilt and
/// e^{−2/v} (a light path draws about 1.6 times; four of its transcendentals were these).
pub struct ScatterSampler<'a> {
    c: &'a ChiangConstants,
    logistic: TrimmedLogistic,
    /// Per lobe, (sin, cos) of its tilt.
    tilt: [(f64, f64); N_LOBES],
    /// Per lobe, e^{−2/v}: the floor of d'Eon's inversion.
    tail: [f64; N_LOBES],
}

impl<'a> ScatterSampler<'a> {
    pub fn new(c: &'a ChiangConstants) -> Self {
        Self {
            c,
            logistic: TrimmedLogistic::new(c.s),
            tilt: c.tilt.map(f64::sin_cos),
            tail: c.v.map(|v| (-2.0 / v).exp()),
        }
    }

    /// Where light arriving at a fibre of unit tangent `u` from unit direction `from`
    /// (pointing away from the fibre, toward where the light came from) leaves, drawn with the
    /// four uniform numbers `xi` (offset, lobe, longitudinal pair; a fifth for the azimuth).
    /// `None` for a degenerate frame or a lobe of no weight.
    pub fn sample(&self, u: DVec3, from: DVec3, xi: [f64; 5]) -> Option<Scattered> {
        let c = self.c;
        let sin_o = from.dot(u).clamp(-1.0, 1.0);
        let cos_o = (1.0 - sin_o * sin_o).max(0.0).sqrt();
        // The normal plane's frame: e1 toward `from`'s projection (its azimuth is 0), e2 = u × e1.
        let perp = from - u * sin_o;
        let e1 = if perp.length_squared() > 1e-20 {
            perp.normalize()
        } else {
            u.any_orthonormal_vector()
        };
        let e2 = u.cross(e1);
        let h = (2.0 * xi[0] - 1.0).clamp(-1.0, 1.0);
        let (lobe, prob, a) = pick_lobe(c, sin_o, h, xi[1])?;
        // θ' from d'Eon's lobe about −(θ + tilt): sin and cos of θ + tilt by angle addition.
        let v = c.v[lobe];
        let (sin_tilt, cos_tilt) = self.tilt[lobe];
        let sin_t = sin_o * cos_tilt + cos_o * sin_tilt;
        let cos_t = cos_o * cos_tilt - sin_o * sin_tilt;
        let x = xi[2].max(1e-12);
        let cos_k = (1.0 + v * (x + (1.0 - x) * self.tail[lobe]).ln()).clamp(-1.0, 1.0);
        let sin_k = (1.0 - cos_k * cos_k).max(0.0).sqrt();
        let sin_i =
            (-cos_k * sin_t + sin_k * (2.0 * PI * xi[3]).cos() * cos_t.abs()).clamp(-1.0, 1.0);
        let cos_i = (1.0 - sin_i * sin_i).max(0.0).sqrt();
        // φ about the lobe's exit azimuth Φ_p = 2pγt − 2γo + pπ (uniform for the residual).
        let phi = if lobe == RESIDUAL {
            PI * (2.0 * xi[4] - 1.0)
        } else {
            let (sin_gt, _) = refracted_gamma(c.eta, sin_o, h);
            let p = lobe as f64;
            2.0 * p * sin_gt.asin() - 2.0 * h.asin() + p * PI + self.logistic.sample(xi[4])
        };
        let dir = u * sin_i + (e1 * phi.cos() + e2 * phi.sin()) * cos_i;
        let weight = a[lobe].map(|w| w / prob);
        Some(Scattered { dir, weight, lobe })
    }
}

/// The lobe drawn by `xi` with probability its share of the mean attenuation at offset `h`,
/// that probability, and every lobe's attenuation; `None` when no lobe has any weight.
fn pick_lobe(
    c: &ChiangConstants,
    sin_o: f64,
    h: f64,
    xi: f64,
) -> Option<(usize, f64, [[f64; 3]; N_LOBES])> {
    let a = attenuation(c, sin_o, h);
    let mean = a.map(|ch| (ch[0] + ch[1] + ch[2]) / 3.0);
    let total: f64 = mean.iter().sum();
    if !(total > 0.0) {
        return None;
    }
    let mut lobe = N_LOBES - 1;
    let mut acc = 0.0;
    for (p, m) in mean.iter().enumerate() {
        acc += m / total;
        if xi < acc {
            lobe = p;
            break;
        }
    }
    let prob = mean[lobe] / total;
    (prob > 0.0).then_some((lobe, prob, a))
}

#[cfg(test)]
mod tests;
