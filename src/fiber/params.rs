//! Fibre parameters as written in hairstyle JSON, their validation, and the per-lobe constants
//! derived from them (Marschner 2003 Table 1), converted to radians once.
//!
//! Degrees exist only in [`FiberParams`] (the JSON edge); [`LobeConstants`] holds radians.

use serde::{Deserialize, Serialize};

/// Which fibre scattering model a fibre uses (JSON `"model"`, lower case).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FiberModel {
    /// Marschner et al. 2003 (`marschner.rs`): Gaussian M_p in θh over cos²θd, N_p from the exact
    /// roots of Eq. 3 with the §5.2.2 caustic smoothing and eccentricity. Not energy conserving
    /// (white albedo 0.93–1.8, `tests/lib/fiber_energy.rs`).
    #[default]
    Marschner,
    /// Chiang et al. 2016 (`chiang.rs`), the model of pbrt-v3/v4, Mitsuba 3 and Cycles: d'Eon
    /// et al. 2011 lobes M_p, trimmed-logistic azimuthal roughness, energy-conserving A_p with the
    /// p ≥ 3 residual. A white fibre in a white furnace has radiance exactly 1.
    Chiang,
}

/// Fibre parameters as written in hairstyle JSON (`"fiber": {...}`); angles in degrees at this
/// edge only. Defaults lie inside Marschner 2003 Table 1's ranges.
///
/// One set of physical parameters drives both models (`model`): η, σa per unit radius, the
/// longitudinal roughness (`beta_r_deg`), the azimuthal roughness (`azimuthal_roughness`, Chiang
/// only; Marschner has none) and the cuticle tilt (`alpha_r_deg`). The Marschner-only caustic
/// parameters (`eccentricity`, `k_g`, `w_c_deg`, `delta_eta_prime`, `delta_h_m`) are ignored by
/// "chiang".
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FiberParams {
    /// Scattering model, "marschner" (default) or "chiang".
    pub model: FiberModel,
    /// Fibre radius in metres (default 40e-6: an 80 µm fibre). Not used by the BCSDF (which is
    /// per unit radius, Marschner 2003 footnote 2); the map uses it for crossing counts.
    pub radius_m: f32,
    /// Index of refraction of the cortex, in (1, 4) (default 1.55, Table 1).
    pub eta: f32,
    /// Absorption coefficient per unit fibre radius, linear RGB, each in [0, 1000] (default:
    /// brown hair [0.545, 0.906, 1.78], pbrt-v4's eumelanin concentration 1.3).
    pub sigma_a: [f32; 3],
    /// Longitudinal shift of the R lobe in degrees, in [−20, 20] (Table 1: −10 to −5; default
    /// −7.5). Negative shifts the R lobe toward the root. For "chiang" this is the cuticle tilt α
    /// (Mitsuba's `scale_tilt`, same sign): R peaks at θi + θo = 2α, TT at −α, TRT at −4α
    /// (Marschner: 2α_R, −α_R, −3α_R, `LobeConstants`).
    pub alpha_r_deg: f32,
    /// Longitudinal width (standard deviation in θh) of the R lobe in degrees, in [0.5, 45]
    /// (Table 1: 5 to 10; default 7.5). Both models take the R lobe's standard deviation in θo
    /// from it, 2β_R: "chiang" sets d'Eon's v₀ = (2β_R)² rad², i.e. Chiang's longitudinal
    /// roughness b solves 0.726b + 0.812b² + 3.7b²⁰ = 2β_R (β_R = 2.5/5/7.5/10° gives b =
    /// 0.107/0.197/0.276/0.347; [`FiberParams::chiang_longitudinal_roughness`]).
    pub beta_r_deg: f32,
    /// Azimuthal roughness β_n of "chiang" (dimensionless, in [0.01, 1]; default 0.3 as pbrt and
    /// Mitsuba). The trimmed logistic's scale is s = √(π/8)(0.265β_n + 1.194β_n² + 5.372β_n²²)
    /// radians (0.117 rad at 0.3). Below 0.01 (s < 0.1°) N_p tends to a delta that no table
    /// resolves. Ignored by "marschner".
    pub azimuthal_roughness: f32,
    /// Cross-section eccentricity a/b, in [0.75, 1/0.75] (Table 1: 0.85 to 1; default 0.9).
    /// Below 1/√2 Marschner's η* (§5.2.3) would fall below 1.
    pub eccentricity: f32,
    /// Glint scale factor k_G, in [0, 10] (Table 1: 0.5 to 5; default 0.5).
    pub k_g: f32,
    /// Azimuthal width (standard deviation) of the caustic w_c in degrees, in [1, 45]
    /// (Table 1: 10 to 25; default 15).
    pub w_c_deg: f32,
    /// Range of η' over which the caustic fades after the merge, Δη', in [0.01, 1]
    /// (Table 1: 0.2 to 0.4; default 0.3).
    pub delta_eta_prime: f32,
    /// Caustic intensity limit Δh_M, in [0, 2] (Table 1: 0.5; default 0.5).
    pub delta_h_m: f32,
    /// Dual scattering forward density factor d_f, dimensionless in [0, 1] (Zinke 2008 Eq. 5):
    /// the share of the forward-scattered light T_f − direct that reaches a shadowed fibre.
    /// Default 1, not Zinke's 0.7: wisp's map reads T_f as the Poisson average over the real
    /// crossing counts, so the gaps Zinke's constant stands for are already in T_f; measured
    /// against the path tracer (ACCURACY.md §2), 1 halves the side- and back-lit deficit
    /// (dense blond side 0.68 → 0.87, curly side 0.79 → 0.90) for +6–12% front-lit.
    pub d_f: f32,
    /// Dual scattering backward density factor d_b, dimensionless in [0, 1] (Zinke 2008 Eq. 9):
    /// the weight of the local back-scattering f_back in dense hair. The local density
    /// (`LightAtPoint::crossings_behind`) scales it further, to 0 for an isolated fibre
    /// (`backscatter::truncation`). Default 0.5, measured, not Zinke's 0.7: on a front-lit slab
    /// of parallel fibres (`tools/reference/slab.py`, 8 crossings deep) the multiply scattered
    /// light reads 0.69 / 1.30 of the path tracer's (R) at d_b = 0.35 / 0.7 and 0.95 at 0.5
    /// (ACCURACY.md §2, "The slab"). A reading that agrees, not a derivation: Figure 5
    /// evaluates f_back with s̃_b = 1/π at every azimuth, twice the energy of Eq. 14's backward
    /// half circle, so 0.5 is an energy-preserving 1/(2π) with no density loss (d_b = 1).
    pub d_b: f32,
    /// Forward spread: half-width in degrees, in [1, 180], of the azimuthal window from which
    /// forward-scattered light reaches a fibre (Zinke 2008 Eq. 7: s̃_f = 1/(2w) inside the
    /// window, 0 outside; N^G of Eq. 25 is N convolved with it). Default 90 = Zinke's s̃_f = 1/π
    /// over the front half circle; 180 = isotropic in azimuth; small = still along the light.
    pub forward_spread_deg: f32,
}

impl Default for FiberParams {
    fn default() -> Self {
        Self {
            model: FiberModel::Marschner,
            azimuthal_roughness: 0.3,
            forward_spread_deg: 90.0,
            radius_m: 40e-6,
            eta: 1.55,
            sigma_a: [0.545, 0.906, 1.78],
            alpha_r_deg: -7.5,
            beta_r_deg: 7.5,
            eccentricity: 0.9,
            k_g: 0.5,
            w_c_deg: 15.0,
            delta_eta_prime: 0.3,
            delta_h_m: 0.5,
            d_f: 1.0,
            d_b: 0.5,
        }
    }
}

/// Lowest accepted eccentricity; its inverse is the highest.
pub const ECCENTRICITY_MIN: f32 = 0.75;

impl FiberParams {
    /// Checks every field; the error names the field (relative to `fiber.`) and the rule.
    pub fn validate(&self) -> Result<(), String> {
        let in_range = |name: &str, v: f32, lo: f32, hi: f32, open_lo: bool, open_hi: bool| {
            let lo_ok = if open_lo { v > lo } else { v >= lo };
            let hi_ok = if open_hi { v < hi } else { v <= hi };
            if v.is_finite() && lo_ok && hi_ok {
                Ok(())
            } else {
                let l = if open_lo { '(' } else { '[' };
                let r = if open_hi { ')' } else { ']' };
                Err(format!("{name} must be in {l}{lo}, {hi}{r} (got {v})"))
            }
        };
        if !(self.radius_m.is_finite() && self.radius_m > 0.0) {
            return Err(format!(
                "radius_m must be finite and > 0 (got {})",
                self.radius_m
            ));
        }
        in_range("eta", self.eta, 1.0, 4.0, true, true)?;
        for (c, v) in self.sigma_a.iter().enumerate() {
            if !(v.is_finite() && *v >= 0.0 && *v <= 1.0e3) {
                return Err(format!(
                    "sigma_a[{c}] must be finite and in [0, 1000] (got {v})"
                ));
            }
        }
        in_range("alpha_r_deg", self.alpha_r_deg, -20.0, 20.0, false, false)?;
        in_range("beta_r_deg", self.beta_r_deg, 0.5, 45.0, false, false)?;
        in_range(
            "eccentricity",
            self.eccentricity,
            ECCENTRICITY_MIN,
            1.0 / ECCENTRICITY_MIN,
            false,
            false,
        )?;
        in_range("k_g", self.k_g, 0.0, 10.0, false, false)?;
        in_range("w_c_deg", self.w_c_deg, 1.0, 45.0, false, false)?;
        in_range(
            "delta_eta_prime",
            self.delta_eta_prime,
            0.01,
            1.0,
            false,
            false,
        )?;
        in_range("delta_h_m", self.delta_h_m, 0.0, 2.0, false, false)?;
        in_range("d_f", self.d_f, 0.0, 1.0, false, false)?;
        in_range("d_b", self.d_b, 0.0, 1.0, false, false)?;
        in_range(
            "azimuthal_roughness",
            self.azimuthal_roughness,
            0.01,
            1.0,
            false,
            false,
        )?;
        in_range(
            "forward_spread_deg",
            self.forward_spread_deg,
            1.0,
            180.0,
            false,
            false,
        )?;
        Ok(())
    }

    /// Chiang et al. 2016's longitudinal roughness b (Mitsuba's `longitudinal_roughness`, pbrt's
    /// β_m) that gives this fibre's R lobe: the root in [0, 1] of 0.726b + 0.812b² + 3.7b²⁰ = 2β_R
    /// (radians; the fit of d'Eon's √v₀ used by pbrt and Mitsuba), by bisection. For the
    /// reference exporter; the model itself uses v₀ = (2β_R)² directly.
    pub fn chiang_longitudinal_roughness(&self) -> f64 {
        roughness_for_std((2.0 * self.beta_r_deg as f64).to_radians())
    }
}

/// The three scattering modes of Marschner 2003 (p = number of internal path segments).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lobe {
    /// Surface reflection, p = 0.
    R = 0,
    /// Transmission-transmission, p = 1.
    TT = 1,
    /// Transmission-reflection-transmission, p = 2.
    TRT = 2,
}

impl Lobe {
    pub const ALL: [Lobe; 3] = [Lobe::R, Lobe::TT, Lobe::TRT];
    /// Number of internal path segments p.
    pub fn p(self) -> u32 {
        self as u32
    }
}

/// Per-lobe longitudinal constants and the other parameters in radians (computed once).
#[derive(Clone, Copy, Debug)]
pub struct LobeConstants {
    /// Lobe shifts α_p in radians (Table 1: α_TT = −α_R/2, α_TRT = −3α_R/2).
    pub alpha: [f64; 3],
    /// Lobe widths β_p (standard deviation in θh) in radians (β_TT = β_R/2, β_TRT = 2β_R).
    pub beta: [f64; 3],
    pub eta: f64,
    pub sigma_a: [f64; 3],
    pub eccentricity: f64,
    pub k_g: f64,
    /// w_c in radians.
    pub w_c: f64,
    pub delta_eta_prime: f64,
    pub delta_h_m: f64,
}

impl LobeConstants {
    pub fn from_params(p: &FiberParams) -> Self {
        let a_r = (p.alpha_r_deg as f64).to_radians();
        let b_r = (p.beta_r_deg as f64).to_radians();
        Self {
            alpha: [a_r, -a_r / 2.0, -3.0 * a_r / 2.0],
            beta: [b_r, b_r / 2.0, 2.0 * b_r],
            eta: p.eta as f64,
            sigma_a: p.sigma_a.map(|s| s as f64),
            eccentricity: p.eccentricity as f64,
            k_g: p.k_g as f64,
            w_c: (p.w_c_deg as f64).to_radians(),
            delta_eta_prime: p.delta_eta_prime as f64,
            delta_h_m: p.delta_h_m as f64,
        }
    }

    /// Mean of lobe p's longitudinal Gaussian in the variable θi + θo (= 2θh), radians.
    pub fn mean_x(&self, lobe: Lobe) -> f64 {
        2.0 * self.alpha[lobe as usize]
    }

    /// Standard deviation of lobe p's longitudinal Gaussian in θi + θo (= 2θh), radians.
    pub fn std_x(&self, lobe: Lobe) -> f64 {
        2.0 * self.beta[lobe as usize]
    }
}

/// C16's fit of d'Eon's R-lobe standard deviation √v₀ (radians) to the longitudinal roughness
/// b ∈ [0, 1]: 0.726b + 0.812b² + 3.7b²⁰.
pub fn std_for_roughness(b: f64) -> f64 {
    0.726 * b + 0.812 * b * b + 3.7 * b.powi(20)
}

/// The inverse of [`std_for_roughness`] on [0, 1] by bisection (the fit is increasing); clamped
/// to [0, 1] for standard deviations outside the fit's range (0 to 5.24 rad); 0 for NaN or ≤ 0.
pub fn roughness_for_std(std_rad: f64) -> f64 {
    if std_rad.is_nan() || std_rad <= 0.0 {
        return 0.0;
    }
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if std_for_roughness(mid) < std_rad {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests;
