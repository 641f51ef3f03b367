//! Chiang, Bitterli, Tappan & Burley 2016, "A Practical and Controllable Hair and Fur Model for
//! Production Path Tracing" (C16): the fibre model of pbrt-v3/v4, Mitsuba 3 and Cycles,
//! evaluated exactly in f64 (no tables). `chiang_tables.rs` tabulates its far-field azimuthal
//! lobes for the shader; the tests compare the tables against these functions.
//!
//! The paper is not in `../shared/papers`; the formulas below are C16 §4 as pbrt-v3 §9.9 prints
//! and implements them, and were checked against Mitsuba 3.9.1's `hair` BSDF
//! (`tools/reference/chiang_eval_check.py`).
//!
//! **Near field, far field, and wisp's convention.** A camera ray hits the fibre at the offset
//! h = sin γo ∈ [−1, 1]; the radiance leaving toward the camera per unit irradiance from ωi is
//!
//!   g(ωi, ωo; h) = Σ_{p<3} M_p(θi, θo') A_p(θo, h) N_p(φ − Φ_p(θo, h)) + M_3(θi, θo) A_3/(2π),
//!
//! which is pbrt's f·|cos| and Mitsuba's `eval` (both cancel the integrator's cosine). Everything
//! that depends on h lives on the camera side (θo, γo). A pixel that covers the fibre's width
//! averages h uniformly, so the far field is ḡ = Σ_p M_p N̄_p with
//! N̄_p(θo, φ) = ½∫ A_p N_p dh ([`n_bar_direct`]). In wisp's BCSDF convention (radiance =
//! S cos θi E, Marschner 2003 Eq. 1 averaged over the width) the model is S = ḡ / cos θi.
//!
//! **Energy.** With σa = 0, Σ_p A_p = 1 for every h, N_p has unit area and M_p unit area under
//! cos θi dθi, so ∫ ḡ dωi = 1 for every ωo: a white fibre in a white furnace has radiance exactly
//! 1 (measured 1 + 3e-6, `tests/lib/fiber_chiang.rs`). The forward albedo ∫ S cos θo dωo, the
//! fraction of intercepted power that leaves, is not 1: 0.991 at θi = 0, 1.40 at 80° and 11 at
//! 89° for β_R = 7.5° and no tilt (0.69 to 2.7 over ±60°…80° with the presets' α = −7.5°),
//! because S = ḡ/cos θi is not reciprocal. The dual tables divide by it where it exceeds 1, as
//! for Marschner (`dual.rs`).
//!
//! **Reciprocity.** M_p(θi, θo) = M_p(θo, θi) exactly with tilt 0. ḡ(ωi, ωo) − ḡ(ωo, ωi) =
//! Σ M_p (N̄_p(θo) − N̄_p(θi)), zero when |θi| = |θo| (the specular cone, where the lobes peak) and
//! otherwise set by the θo-dependence of A_p (Fresnel, η', chord): 12.5% of ḡ integrated over
//! random direction pairs, 5.3% within |θ| ≤ 60° (`tests/lib/fiber_chiang.rs`, `reciprocity`).
//!
//! Pieces:
//! - **M_p** (d'Eon et al. 2011, "An Energy-Conserving Hair Reflectance Model", their
//!   longitudinal function; evaluated in log space so small v does not overflow):
//!   M(v; θi, θo) = csch(1/v)/(2v) · exp(−sin θi sin θo / v) · I0(cos θi cos θo / v), a density
//!   in θo under cos θo dθo. Variances v₀ (R), v₀/4 (TT), 4v₀ (TRT and p ≥ 3). wisp sets v₀ =
//!   (2β_R)², the same R width in θo as its Marschner lobe (`FiberParams::beta_r_deg`).
//! - **Tilt α** (`alpha_r_deg`): lobe p reads θo' = θo − 2α (R), θo + α (TT), θo + 4α (TRT), θo
//!   (p ≥ 3), with cos θo' taken as |cos|; the lobes peak at θi + θo = 2α, −α, −4α.
//! - **A_p**: f = Fresnel(η; cos θo cos γo), the true 3D incidence angle (for a cylinder every
//!   internal reflection sees the same angle, `fresnel` tests); T = exp(−σa · 2cos γt / cos θt)
//!   with σa per unit radius, sin θt = sin θo/η, sin γt = h/η'(θo); A_0 = f, A_1 = (1 − f)²T,
//!   A_2 = A_1 f T, A_3 = A_2 f T/(1 − f T) (all p ≥ 3 summed).
//! - **N_p**: the logistic of scale s trimmed to [−π, π], at φ − Φ_p wrapped into [−π, π], with
//!   Φ_p = 2pγt − 2γo + pπ (Marschner 2003 Eq. 3); s from β_n by C16's fit (`logistic_scale`).

use super::fresnel::fresnel_dielectric;
use super::params::FiberParams;
use std::f64::consts::{FRAC_PI_2, PI};

/// Lobes of the model: R, TT, TRT and the p ≥ 3 residual (index [`RESIDUAL`]).
pub const N_LOBES: usize = 4;
/// Index of the p ≥ 3 residual lobe.
pub const RESIDUAL: usize = 3;

/// C16's azimuthal logistic scale s (radians) for azimuthal roughness β_n ∈ [0, 1]:
/// s = √(π/8)(0.265β_n + 1.194β_n² + 5.372β_n²²).
pub fn logistic_scale(beta_n: f64) -> f64 {
    (PI / 8.0).sqrt() * (0.265 * beta_n + 1.194 * beta_n * beta_n + 5.372 * beta_n.powi(22))
}

/// The model's constants, derived once from [`FiberParams`] (radians, rad²).
#[derive(Clone, Copy, Debug)]
pub struct ChiangConstants {
    pub eta: f64,
    /// Absorption per unit radius, RGB.
    pub sigma_a: [f64; 3],
    /// Longitudinal variances v_p of [R, TT, TRT, p ≥ 3], rad² (variance in θo).
    pub v: [f64; N_LOBES],
    /// Logistic scale s, radians.
    pub s: f64,
    /// Angle added to θo before M_p, per lobe (radians): [−2α, α, 4α, 0].
    pub tilt: [f64; N_LOBES],
}

impl ChiangConstants {
    pub fn from_params(p: &FiberParams) -> Self {
        let v0 = (2.0 * (p.beta_r_deg as f64).to_radians()).powi(2);
        let a = (p.alpha_r_deg as f64).to_radians();
        Self {
            eta: p.eta as f64,
            sigma_a: p.sigma_a.map(|x| x as f64),
            v: [v0, v0 / 4.0, 4.0 * v0, 4.0 * v0],
            s: logistic_scale(p.azimuthal_roughness as f64),
            tilt: [-2.0 * a, a, 4.0 * a, 0.0],
        }
    }

    /// The same fibre with no absorption (white furnace, normalisation of the dual tables).
    pub fn white(&self) -> Self {
        Self {
            sigma_a: [0.0; 3],
            ..*self
        }
    }

    /// Where lobe p peaks in x = θi + θo (radians): −tilt_p.
    pub fn mean_x(&self, lobe: usize) -> f64 {
        -self.tilt[lobe]
    }

    /// M_p(θi, θo) with the lobe's tilt and variance (1/rad; unit area under cos θo dθo).
    pub fn m(&self, lobe: usize, theta_i: f64, theta_o: f64) -> f64 {
        deon_m(self.v[lobe], theta_i, theta_o + self.tilt[lobe])
    }
}

/// ln I0(x) for x ≥ 0 (modified Bessel function of the first kind, order 0): the power series
/// Σ (x²/4)^k/(k!)² up to x = 30 (relative error < 1e-15), the asymptotic series
/// e^x/√(2πx) (1 + 1/(8x) + 9/(128x²) + 225/(3072x³) + 11025/(98304x⁴)) above (error < 1e-10).
pub fn ln_i0(x: f64) -> f64 {
    let x = x.abs();
    if x <= 30.0 {
        let q = 0.25 * x * x;
        let (mut term, mut sum) = (1.0f64, 1.0f64);
        for k in 1..200 {
            term *= q / (k as f64 * k as f64);
            sum += term;
            if term < 1e-17 * sum {
                break;
            }
        }
        sum.ln()
    } else {
        let r = 1.0 / x;
        let series = 1.0
            + r * (1.0 / 8.0 + r * (9.0 / 128.0 + r * (225.0 / 3072.0 + r * 11025.0 / 98304.0)));
        x - 0.5 * (2.0 * PI * x).ln() + series.ln()
    }
}

/// d'Eon et al. 2011's longitudinal lobe M(v; θi, θo) = exp(−sin θi sin θo / v) I0(cos θi cos θo
/// / v) / (2v sinh(1/v)), evaluated in log space (no overflow for v down to 1e-6). Units 1/rad;
/// unit area under cos θo dθo over [−π/2, π/2] for every θi. cos θo is taken as |cos θo| (so a
/// tilted θo beyond ±π/2 reflects, as in pbrt and Mitsuba).
pub fn deon_m(v: f64, theta_i: f64, theta_o: f64) -> f64 {
    let (si, ci) = theta_i.sin_cos();
    let (so, co) = theta_o.sin_cos();
    let a = ci.abs() * co.abs() / v;
    let b = si * so / v;
    // 1/(2v sinh(1/v)) = e^{−1/v} / (v (1 − e^{−2/v})).
    let norm = -(v * -(-2.0 / v).exp_m1()).ln();
    (ln_i0(a) - b - 1.0 / v + norm).exp()
}

/// Attenuations [A_0, A_1, A_2, A_3 (all p ≥ 3)] per channel at sin θo and offset h ∈ [−1, 1]
/// (module doc). σa per unit radius.
pub fn attenuation(c: &ChiangConstants, sin_theta_o: f64, h: f64) -> [[f64; 3]; N_LOBES] {
    let s = sin_theta_o.clamp(-1.0, 1.0);
    let cos_o = (1.0 - s * s).max(0.0).sqrt();
    let h = h.clamp(-1.0, 1.0);
    let cos_gamma_o = (1.0 - h * h).max(0.0).sqrt();
    let f = fresnel_dielectric(c.eta, cos_o * cos_gamma_o);
    let (_, cos_gt) = refracted_gamma(c.eta, s, h);
    let sin_tt = s / c.eta;
    let cos_tt = (1.0 - sin_tt * sin_tt).sqrt();
    let chord = 2.0 * cos_gt / cos_tt;
    let per_channel = c.sigma_a.map(|sigma| {
        let t = (-sigma * chord).exp();
        let a1 = (1.0 - f) * (1.0 - f) * t;
        let a2 = a1 * f * t;
        let ft = f * t;
        // f T < 1 unless f = 1 (grazing, where A_2 = 0 anyway).
        let a3 = if ft < 1.0 { a2 * ft / (1.0 - ft) } else { 0.0 };
        [f, a1, a2, a3]
    });
    std::array::from_fn(|p| per_channel.map(|a| a[p]))
}

/// (sin γt, cos γt) of the refracted ray in the normal plane: sin γt = h / η'(θo), with Bravais's
/// η' = √(η² − sin²θo) / cos θo (cos θo floored at 1e-6).
pub fn refracted_gamma(eta: f64, sin_theta_o: f64, h: f64) -> (f64, f64) {
    let s2 = sin_theta_o * sin_theta_o;
    let cos_o = (1.0 - s2).max(1e-12).sqrt();
    let eta_p = (eta * eta - s2).max(0.0).sqrt() / cos_o;
    let sin_gt = (h / eta_p).clamp(-1.0, 1.0);
    (sin_gt, (1.0 - sin_gt * sin_gt).sqrt())
}

/// Exit azimuth Φ_p(γo) = 2pγt − 2γo + pπ (radians, unwrapped, continuous in γo).
pub fn exit_azimuth(eta: f64, sin_theta_o: f64, p: usize, gamma_o: f64) -> f64 {
    let (sin_gt, _) = refracted_gamma(eta, sin_theta_o, gamma_o.sin());
    2.0 * p as f64 * sin_gt.asin() - 2.0 * gamma_o + p as f64 * PI
}

/// The logistic sigmoid 1/(1 + e^{−t}), without overflow.
fn sigmoid(t: f64) -> f64 {
    if t >= 0.0 {
        1.0 / (1.0 + (-t).exp())
    } else {
        let e = t.exp();
        e / (1.0 + e)
    }
}

/// The logistic of scale s trimmed to [−π, π] (C16's azimuthal roughness), with its trimming
/// constants computed once (the table builder evaluates its CDF millions of times).
#[derive(Clone, Copy, Debug)]
pub struct TrimmedLogistic {
    s: f64,
    /// σ(−π/s), the untrimmed CDF at −π.
    lo: f64,
    /// 1/(σ(π/s) − σ(−π/s)).
    inv_z: f64,
}

impl TrimmedLogistic {
    pub fn new(s: f64) -> Self {
        let lo = sigmoid(-PI / s);
        Self {
            s,
            lo,
            inv_z: 1.0 / (1.0 - 2.0 * lo),
        }
    }

    /// The density in x (1/rad), x wrapped into [−π, π] first, so it is 2π-periodic with unit
    /// area per period.
    #[inline]
    pub fn pdf(&self, x: f64) -> f64 {
        let y = super::marschner::wrap_pi(x).abs();
        let e = (-y / self.s).exp();
        e / (self.s * (1.0 + e) * (1.0 + e)) * self.inv_z
    }

    /// The cumulative of the periodic density from −π to x, for any real x: it grows by 1 per
    /// period, so C(x + 2π) = C(x) + 1, C(−π) = 0, C(0) = ½.
    #[inline]
    pub fn cdf(&self, x: f64) -> f64 {
        let k = ((x + PI) / (2.0 * PI)).floor();
        let y = x - 2.0 * PI * k;
        k + ((sigmoid(y / self.s) - self.lo) * self.inv_z).clamp(0.0, 1.0)
    }

    /// The x in [−π, π] where the CDF is `xi` ∈ [0, 1]: its inverse, for sampling
    /// (`chiang_sample.rs`). σ(x/s) = lo + ξ(1 − 2 lo), so x = s · logit(lo + ξ(1 − 2 lo)).
    pub fn sample(&self, xi: f64) -> f64 {
        let q = (self.lo + xi.clamp(0.0, 1.0) * (1.0 - 2.0 * self.lo)).clamp(1e-300, 1.0 - 1e-16);
        (self.s * (q / (1.0 - q)).ln()).clamp(-PI, PI)
    }
}

/// [`TrimmedLogistic::pdf`] of scale s.
pub fn trimmed_logistic(x: f64, s: f64) -> f64 {
    TrimmedLogistic::new(s).pdf(x)
}

/// [`TrimmedLogistic::cdf`] of scale s.
pub fn trimmed_logistic_cdf(x: f64, s: f64) -> f64 {
    TrimmedLogistic::new(s).cdf(x)
}

/// The paper's N_p(φ) at one offset h, p < 3 (1/rad): the trimmed logistic at φ − Φ_p.
pub fn n_near(c: &ChiangConstants, p: usize, phi: f64, sin_theta_o: f64, h: f64) -> f64 {
    let gamma_o = h.clamp(-1.0, 1.0).asin();
    trimmed_logistic(phi - exit_azimuth(c.eta, sin_theta_o, p, gamma_o), c.s)
}

/// (w_f ⊛ ℓ)(y): the forward weight w_f(φ) = |φ|/π (`azimuthal::w_forward`) averaged over an
/// azimuth y + X with X drawn from the trimmed logistic of scale s, in closed form from the
/// logistic's partial moments (∫ x ℓ dx has the antiderivative x σ(x/s) − s ln(1 + e^{x/s})).
/// Used to integrate N̄_p against w_f from h-samples without resolving the logistic in φ.
pub fn w_forward_smoothed(y: f64, s: f64) -> f64 {
    let y = super::marschner::wrap_pi(y).abs();
    let z = 1.0 - 2.0 * sigmoid(-PI / s);
    let p0 = |a: f64, b: f64| (sigmoid(b / s) - sigmoid(a / s)) / z;
    // Antiderivative of x·L(x), bounded for every x.
    let q = |x: f64| {
        let t = x / s;
        if t >= 0.0 {
            -x * sigmoid(-t) - s * (-t).exp().ln_1p()
        } else {
            x * sigmoid(t) - s * t.exp().ln_1p()
        }
    };
    let p1 = |a: f64, b: f64| (q(b) - q(a)) / z;
    // |wrap(y + x)| is −(y + x) on [−π, −y], y + x on [−y, π − y], 2π − y − x on [π − y, π].
    let e = -y * p0(-PI, -y) - p1(-PI, -y)
        + y * p0(-y, PI - y)
        + p1(-y, PI - y)
        + (2.0 * PI - y) * p0(PI - y, PI)
        - p1(PI - y, PI);
    (e / PI).clamp(0.0, 1.0)
}

/// Far-field N̄_p(θo, φ) = ½∫ A_p N_p dh by midpoint quadrature in γo (h = sin γo, `n` nodes),
/// RGB, 1/rad; p = 3 gives Ā_3/(2π). Slow; the reference for the tables.
pub fn n_bar_direct(c: &ChiangConstants, p: usize, theta_o: f64, phi: f64, n: usize) -> [f64; 3] {
    let so = theta_o.sin();
    let dg = PI / n as f64;
    let mut acc = [0.0; 3];
    for k in 0..n {
        let g = -FRAC_PI_2 + (k as f64 + 0.5) * dg;
        let a = attenuation(c, so, g.sin())[p];
        let np = if p == RESIDUAL {
            1.0 / (2.0 * PI)
        } else {
            n_near(c, p, phi, so, g.sin())
        };
        let w = np * g.cos() * dg * 0.5;
        for ch in 0..3 {
            acc[ch] += a[ch] * w;
        }
    }
    acc
}

/// The far-field ḡ_p(ωi, ωo) = M_p N̄_p per lobe (radiance toward ωo per unit irradiance from ωi,
/// 1/sr), RGB, by direct quadrature with `n` nodes in γo. S = Σ ḡ_p / cos θi.
pub fn g_direct(
    c: &ChiangConstants,
    theta_i: f64,
    theta_o: f64,
    phi: f64,
    n: usize,
) -> [[f64; 3]; N_LOBES] {
    std::array::from_fn(|p| {
        let m = c.m(p, theta_i, theta_o);
        n_bar_direct(c, p, theta_o, phi, n).map(|x| x * m)
    })
}

#[cfg(test)]
mod tests;
