//! Fibre scattering: Marschner 2003 BCSDF and Zinke 2008 dual-scattering quantities.
//!
//! CONTRACT (owned by the fibre work, issue #3): this module knows nothing of grids, strands
//! or pixels. The rest of the engine uses only:
//! - [`FiberParams`] (serde, from hairstyle JSON; `validate`),
//! - [`Fiber::new`] (precomputes everything, tables included),
//! - [`Fiber::forward_scatter`] (per-crossing quantities for the map fill),
//! - [`Fiber::shade`] with a [`ShadingMode`] and a [`LightAtPoint`] from the map.
//!
//! The bodies below are a temporary Kajiya-Kay stand-in so the pipeline can be built; the
//! fibre work replaces them (keeping these signatures).

use glam::Vec3;
use serde::{Deserialize, Serialize};

/// Fibre parameters as written in hairstyle JSON (`"fiber": {...}`); angles in degrees at this
/// edge only. Defaults lie inside Marschner 2003 Table 1's ranges.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FiberParams {
    /// Fibre radius in metres (default 40e-6: an 80 µm fibre).
    pub radius_m: f32,
    /// Index of refraction of the cortex (default 1.55).
    pub eta: f32,
    /// Absorption coefficient per unit fibre radius, linear RGB (brown hair by default).
    pub sigma_a: [f32; 3],
    /// Longitudinal shift of the R lobe in degrees (Table 1: −10 to −5; default −7.5).
    pub alpha_r_deg: f32,
    /// Longitudinal width (standard deviation) of the R lobe in degrees (Table 1: 5 to 10).
    pub beta_r_deg: f32,
    /// Cross-section eccentricity a/b (Table 1: 0.85 to 1; default 0.9).
    pub eccentricity: f32,
    /// Glint scale factor k_G (Table 1: 0.5 to 5).
    pub k_g: f32,
    /// Azimuthal width of the caustic w_c in degrees (Table 1: 10 to 25).
    pub w_c_deg: f32,
    /// Fade range for the caustic merge Δη' (Table 1: 0.2 to 0.4).
    pub delta_eta_prime: f32,
    /// Caustic intensity limit Δh_M (Table 1: 0.5).
    pub delta_h_m: f32,
    /// Dual scattering forward density factor d_f (Zinke 2008 §4, default 0.7).
    pub d_f: f32,
    /// Dual scattering backward density factor d_b (Zinke 2008 §4, default 0.7).
    pub d_b: f32,
}

impl Default for FiberParams {
    fn default() -> Self {
        Self {
            radius_m: 40e-6,
            eta: 1.55,
            sigma_a: [0.432, 0.612, 0.98],
            alpha_r_deg: -7.5,
            beta_r_deg: 7.5,
            eccentricity: 0.9,
            k_g: 0.5,
            w_c_deg: 15.0,
            delta_eta_prime: 0.3,
            delta_h_m: 0.5,
            d_f: 0.7,
            d_b: 0.7,
        }
    }
}

impl FiberParams {
    /// Checks every field; the error names the field (relative to `fiber.`) and the rule.
    pub fn validate(&self) -> Result<(), String> {
        let finite_pos = |name: &str, v: f32| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(format!("{name} must be finite and > 0 (got {v})"))
            }
        };
        finite_pos("radius_m", self.radius_m)?;
        if !(self.eta.is_finite() && self.eta > 1.0 && self.eta < 4.0) {
            return Err(format!("eta must be in (1, 4) (got {})", self.eta));
        }
        for (c, v) in self.sigma_a.iter().enumerate() {
            if !(v.is_finite() && *v >= 0.0 && *v <= 1.0e3) {
                return Err(format!(
                    "sigma_a[{c}] must be finite and in [0, 1000] (got {v})"
                ));
            }
        }
        Ok(())
    }
}

/// Which fibre shader to use (for comparison and benchmarks).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ShadingMode {
    /// Zinke 2008 Figure 5: Marschner BCSDF + global and local multiple scattering.
    #[default]
    DualScattering,
    /// Marschner BCSDF attenuated by the map's forward transmittance only.
    SingleScattering,
    /// Kajiya-Kay diffuse + specular scaled by transmittance (Bertails 2005 §3.3).
    KajiyaKay,
}

/// What the light-oriented map knows about the light reaching a point (all dimensionless).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightAtPoint {
    /// Fraction of rays reaching the point with no fibre crossing, in [0, 1].
    pub direct_fraction: f32,
    /// Forward-scattering transmittance T_f (Zinke 2008 Eq. 19), RGB, in [0, 1].
    pub tf: Vec3,
    /// Accumulated forward-scattering variance σ̄f² in rad² (Zinke 2008 Eq. 20), RGB, >= 0.
    pub sigma_f2: Vec3,
}

impl LightAtPoint {
    /// Light that crossed no fibre at all.
    pub const UNSHADOWED: Self = Self {
        direct_fraction: 1.0,
        tf: Vec3::ONE,
        sigma_f2: Vec3::ZERO,
    };
}

/// Per-crossing forward-scattering quantities at one fibre inclination.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForwardScatter {
    /// Mean forward attenuation ā_f (Zinke 2008 Eq. 6), RGB, in [0, 1).
    pub a_f: Vec3,
    /// Mean forward variance β̄_f² in rad² (Zinke 2008 Table 1), RGB.
    pub beta_f2: Vec3,
}

/// A fibre with everything precomputed (tables of the dual-scattering quantities).
#[derive(Clone, Debug)]
pub struct Fiber {
    params: FiberParams,
    base_color: Vec3,
}

impl Fiber {
    /// Precomputes the fibre's tables. `params` must have passed `validate`.
    pub fn new(params: &FiberParams) -> Self {
        let s = Vec3::from(params.sigma_a);
        let base_color = Vec3::new((-2.0 * s.x).exp(), (-2.0 * s.y).exp(), (-2.0 * s.z).exp());
        Self {
            params: params.clone(),
            base_color,
        }
    }

    pub fn params(&self) -> &FiberParams {
        &self.params
    }

    /// Per-crossing forward scattering for light whose direction makes `sin_theta` (= ω·u)
    /// with the fibre tangent.
    pub fn forward_scatter(&self, _sin_theta: f32) -> ForwardScatter {
        ForwardScatter {
            a_f: self.base_color * 0.8,
            beta_f2: Vec3::splat(0.01),
        }
    }

    /// Outgoing radiance toward `wo` per unit irradiance arriving from `wi` (both unit, away
    /// from the fibre), for a fibre with unit tangent `u`, given what the map says of the light.
    pub fn shade(
        &self,
        mode: ShadingMode,
        u: Vec3,
        wi: Vec3,
        wo: Vec3,
        light: &LightAtPoint,
    ) -> Vec3 {
        let _ = mode;
        let sin_i = wi.dot(u).clamp(-1.0, 1.0);
        let cos_i = (1.0 - sin_i * sin_i).max(0.0).sqrt();
        let h = (wi + wo).normalize_or_zero();
        let sin_h = h.dot(u).clamp(-1.0, 1.0);
        let cos_h = (1.0 - sin_h * sin_h).max(0.0).sqrt();
        let diffuse = self.base_color * cos_i * 0.6;
        let spec = Vec3::splat(0.25 * cos_h.powi(40));
        light.tf * (diffuse + spec)
    }
}
