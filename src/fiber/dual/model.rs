//! What the dual-scattering tables need from a fibre model ([`DualModel`]), for Marschner 2003
//! ([`LobeConstants`]) and Chiang 2016 ([`ChiangConstants`]): the lobes' azimuthal samples
//! keyed by |θd| (Marschner) or |θo| (Chiang), the longitudinal factor with S's geometric
//! factor (M_p / cos²θd, Eq. 9 of Marschner; M_p / cos θi for Chiang, S = ḡ / cos θi), and each
//! lobe's mean and variance in x = θi + θo for the moment matching of Zinke's ᾱ and β̄².

use super::super::azimuthal::{AzimuthalSamples, LobeSamples, N_H};
use super::super::chiang::{self, ChiangConstants};
use super::super::chiang_tables::{ChiangSamples, N_GAMMA};
use super::super::marschner::{COS_THETA_D_MIN, inv_cos2_theta_d, longitudinal_m};
use super::super::params::{Lobe, LobeConstants};

/// What the dual-scattering tables need from a fibre model: Marschner's [`LobeConstants`] or
/// Chiang's [`ChiangConstants`]. Only table building calls it (not the per-vertex path), so the
/// generic code is monomorphised per model and costs nothing in `shade`.
pub trait DualModel: Sync + Sized {
    type Samples: AzimuthalSamples;
    /// Number of lobes (3 for Marschner, 4 with Chiang's p ≥ 3 residual).
    fn lobes(&self) -> usize;
    /// The azimuthal table key of a direction pair, radians in [0, π/2]: |θd| for Marschner
    /// (N depends on θd), |θo| for Chiang (its A_p and η' live on the camera side).
    fn key(&self, theta_i: f64, theta_o: f64) -> f64;
    /// Lobe `lobe` sampled at `key` (radians).
    fn samples(&self, lobe: usize, key: f64) -> Self::Samples;
    /// M_p(θi, θo) times S's geometric factor, 1/rad: S = Σ_p longitudinal_p · N_p. Marschner:
    /// M_p / cos²θd (Eq. 9); Chiang: M_p / cos θi (S = ḡ/cos θi, cos θi floored at 0.01).
    fn longitudinal(&self, lobe: usize, theta_i: f64, theta_o: f64) -> f64;
    /// Lobe p's mean in x = θi + θo (radians).
    fn lobe_mean_x(&self, lobe: usize) -> f64;
    /// Lobe p's variance in x (rad²).
    fn lobe_var_x(&self, lobe: usize) -> f64;
    /// The same fibre with σa = 0 (white furnace).
    fn white(&self) -> Self;
}

impl DualModel for LobeConstants {
    type Samples = LobeSamples;
    fn lobes(&self) -> usize {
        3
    }
    fn key(&self, theta_i: f64, theta_o: f64) -> f64 {
        (0.5 * (theta_o - theta_i)).abs()
    }
    fn samples(&self, lobe: usize, key: f64) -> LobeSamples {
        LobeSamples::new(self, Lobe::ALL[lobe], key.sin(), N_H)
    }
    fn longitudinal(&self, lobe: usize, theta_i: f64, theta_o: f64) -> f64 {
        longitudinal_m(self, Lobe::ALL[lobe], theta_i, theta_o)
            * inv_cos2_theta_d(0.5 * (theta_o - theta_i))
    }
    fn lobe_mean_x(&self, lobe: usize) -> f64 {
        self.mean_x(Lobe::ALL[lobe])
    }
    fn lobe_var_x(&self, lobe: usize) -> f64 {
        self.std_x(Lobe::ALL[lobe]).powi(2)
    }
    fn white(&self) -> Self {
        Self {
            sigma_a: [0.0; 3],
            ..*self
        }
    }
}

impl DualModel for ChiangConstants {
    type Samples = ChiangSamples;
    fn lobes(&self) -> usize {
        chiang::N_LOBES
    }
    fn key(&self, _theta_i: f64, theta_o: f64) -> f64 {
        theta_o.abs()
    }
    fn samples(&self, lobe: usize, key: f64) -> Self::Samples {
        ChiangSamples::new(self, lobe, key.sin(), N_GAMMA)
    }
    fn longitudinal(&self, lobe: usize, theta_i: f64, theta_o: f64) -> f64 {
        self.m(lobe, theta_i, theta_o) / theta_i.cos().max(COS_THETA_D_MIN)
    }
    fn lobe_mean_x(&self, lobe: usize) -> f64 {
        self.mean_x(lobe)
    }
    fn lobe_var_x(&self, lobe: usize) -> f64 {
        self.v[lobe]
    }
    fn white(&self) -> Self {
        ChiangConstants::white(self)
    }
}
