//! Kajiya-Kay shading as Bertails et al. 2005 §3.3 uses it: I = T_f (diffuse + specular), kept
//! for comparison with the physically based modes.
//!
//! The colours are derived from the fibre, not tuned:
//! - diffuse: K_d cos θi with K_d = E_d / π², where E_d is the fibre's TT + TRT (+ Chiang's
//!   p ≥ 3) energy at normal incidence (ā_f + ā_b of those lobes at θ = 0, from the dual
//!   tables). Derivation: a radiance K_d cos θi leaving uniformly over the sphere carries
//!   ∫ K_d cos θo dωo = K_d ∫cos²θo dθo ∫dφ = K_d π² per unit irradiance, so this diffuse lobe
//!   holds exactly the energy that the absorbing interior passes on;
//! - specular: K_s cos^n(θi + θo) (peak on the mirror cone θo = −θi), white, with n = 1/(2β_R)²
//!   so that cosⁿ ≈ a Gaussian of the R lobe's width 2β_R in θo, and K_s = E_R / (2π √(2π) 2β_R)
//!   so that at θi = 0 it holds the R lobe's energy E_R.

use super::LightAtPoint;
use super::dual::DualTables;
use super::params::LobeConstants;
use super::shader::HairAngles;
use glam::Vec3;

/// Precomputed Kajiya-Kay constants.
#[derive(Clone, Copy, Debug)]
pub struct KajiyaKay {
    pub k_d: Vec3,
    pub k_s: f32,
    pub exponent: f32,
}

impl KajiyaKay {
    pub fn new(c: &LobeConstants, dual: &DualTables) -> Self {
        let mid = dual.theta.len() / 2; // θ = 0 (odd-sized uniform grid over [−π/2, π/2])
        let s = &dual.shares[mid];
        let e = |p: usize, ch: usize| s.forward[p][ch] + s.backward[p][ch];
        let pi2 = std::f64::consts::PI.powi(2);
        // TT + TRT (+ Chiang's p ≥ 3 residual; 0 for Marschner).
        let inner = |ch: usize| ((e(1, ch) + e(2, ch) + e(3, ch)) / pi2) as f32;
        let k_d = Vec3::new(inner(0), inner(1), inner(2));
        let w = 2.0 * c.beta[0];
        let e_r = e(0, 0);
        Self {
            k_d,
            k_s: (e_r / (2.0 * std::f64::consts::PI * (2.0 * std::f64::consts::PI).sqrt() * w))
                as f32,
            exponent: (1.0 / (w * w)) as f32,
        }
    }

    /// T_f (K_d cos θi + K_s cosⁿ(θi + θo)), RGB, finite for any angles.
    pub fn shade(&self, a: &HairAngles, light: &LightAtPoint) -> Vec3 {
        let tf = if light.tf.is_finite() {
            light.tf.clamp(Vec3::ZERO, Vec3::ONE)
        } else {
            Vec3::ZERO
        };
        let diffuse = self.k_d * a.theta_i.cos().max(0.0);
        let spec = (a.theta_i + a.theta_o).cos().max(0.0).powf(self.exponent) * self.k_s;
        tf * (diffuse + Vec3::splat(spec))
    }
}
