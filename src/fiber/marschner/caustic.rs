//! The TRT caustic of Marschner 2003 §5.2.2: where dφ/dh = 0 the raw N_TRT of Eq. 8 is
//! infinite, so the paper notches it out and adds two glint lobes of finite power instead:
//!
//!   N_TRT(φ) = N_raw(φ) · (1 − t g(φ − φc)/g(0)) (1 − t g(φ + φc)/g(0))
//!            + t k_G A(2, h_c) Δh (g(φ − φc, w_c) + g(φ + φc, w_c)).
//!
//! Before the merge (η' < 2) the caustic sits at h_c² = (4 − η'²)/3 (Descartes, Eq. 4),
//! φc = |φ(2, asin h_c)|, the glints carry the power of Δh = min(Δh_M, 2√(2 w_c / |φ''(h_c)|))
//! around it, and t = 1. Past the merge φc = 0, Δh = Δh_M and t fades from 1 to 0 over
//! η' ∈ [2, 2 + Δη'] with the paper's reversed smoothstep.
//!
//! **Trap 7.** Where the notch is exactly 0 (φ = ±φc before the merge) the raw term is
//! skipped: raw ∝ |φ − φc|^{−1/2} while the notch vanishes like (φ − φc)², so the product's
//! limit is 0, where evaluating it would give ∞ · 0. GLSL's smoothstep would fade the caustic
//! *in* past the merge instead of out, hence [`smoothstep_paper`].

use super::super::params::LobeConstants;
use super::{Azimuth, gaussian, wrap_pi};

/// Marschner 2003 §5.2.2's smoothstep, reversed relative to GLSL's: 1 for x ≤ a, 0 for x ≥ b,
/// and 1 − (3s² − 2s³) with s = (x − a)/(b − a) in between (trap 7: GLSL's would fade the
/// caustic *in* past the merge instead of out).
pub fn smoothstep_paper(a: f64, b: f64, x: f64) -> f64 {
    let s = ((x - a) / (b - a)).clamp(0.0, 1.0);
    1.0 - s * s * (3.0 - 2.0 * s)
}

/// The caustic of the TRT lobe (Marschner 2003 §5.2.2 procedure).
#[derive(Clone, Copy, Debug)]
pub struct Caustic {
    /// Fade factor t in [0, 1] (1 before the merge).
    pub t: f64,
    /// Azimuth of the caustic φc ≥ 0 (radians); 0 past the merge.
    pub phi_c: f64,
    /// Width Δh of the interval of h whose power the glint lobes carry.
    pub delta_h: f64,
    /// γi of the caustic ray (asin h_c); 0 past the merge.
    pub gamma_c: f64,
}

impl Azimuth {
    /// The caustic of the TRT lobe with this geometry (Marschner 2003 §5.2.2): before the merge
    /// (η' < 2) from Descartes's h_c² = (4 − η'²)/3 (Eq. 4), Δh = min(Δh_M, 2√(2w_c/|φ''(h_c)|));
    /// after it φc = 0, Δh = Δh_M and t fades from 1 to 0 over η' ∈ [2, 2 + Δη'].
    pub fn caustic(&self, c: &LobeConstants) -> Caustic {
        if self.eta_prime < 2.0 {
            let h_c = ((4.0 - self.eta_prime * self.eta_prime) / 3.0).sqrt();
            let gamma_c = h_c.asin();
            let phi_c = wrap_pi(self.phi(2, gamma_c)).abs();
            let d2 = self.d2phi_dh2(2, h_c).abs();
            let delta_h = if d2 > 1e-300 {
                c.delta_h_m.min(2.0 * (2.0 * c.w_c / d2).sqrt())
            } else {
                c.delta_h_m
            };
            Caustic {
                t: 1.0,
                phi_c,
                delta_h,
                gamma_c,
            }
        } else {
            Caustic {
                t: smoothstep_paper(2.0, 2.0 + c.delta_eta_prime, self.eta_prime),
                phi_c: 0.0,
                delta_h: c.delta_h_m,
                gamma_c: 0.0,
            }
        }
    }

    /// The notch factor (1 − t g(φ − φc)/g(0)) (1 − t g(φ + φc)/g(0)) of §5.2.2.
    pub fn notch(caustic: &Caustic, w_c: f64, phi: f64) -> f64 {
        let bump = |x: f64| (-0.5 * (x / w_c) * (x / w_c)).exp();
        (1.0 - caustic.t * bump(phi - caustic.phi_c))
            * (1.0 - caustic.t * bump(phi + caustic.phi_c))
    }

    /// The two glint lobes t k_G A(2, h_c) Δh (g(φ − φc, w_c) + g(φ + φc, w_c)), RGB.
    pub fn glints(&self, caustic: &Caustic, c: &LobeConstants, phi: f64) -> [f64; 3] {
        let a = self.attenuation(2, caustic.gamma_c);
        let g = gaussian(phi - caustic.phi_c, c.w_c) + gaussian(phi + caustic.phi_c, c.w_c);
        let k = caustic.t * c.k_g * caustic.delta_h * g;
        a.map(|x| x * k)
    }

    /// Smoothed N_TRT(φ) of §5.2.2. Trap 7 (∞·0): where the notch is exactly 0 (φ = ±φc before
    /// the merge) the raw term is skipped, since raw ∝ |φ − φc|^{−1/2} while the notch vanishes
    /// like (φ − φc)², so the product's limit is 0.
    pub fn n_trt_smoothed(&self, c: &LobeConstants, phi: f64) -> [f64; 3] {
        self.n_trt_smoothed_with(c, &self.caustic(c), phi)
    }

    /// [`Self::n_trt_smoothed`] with the caustic computed once by the caller.
    pub fn n_trt_smoothed_with(&self, c: &LobeConstants, caustic: &Caustic, phi: f64) -> [f64; 3] {
        let caustic = *caustic;
        let phi = wrap_pi(phi);
        let notch = Self::notch(&caustic, c.w_c, phi);
        let mut out = if notch > 0.0 {
            self.n_raw(2, phi).map(|x| x * notch)
        } else {
            [0.0; 3]
        };
        let gl = self.glints(&caustic, c, phi);
        for k in 0..3 {
            out[k] += gl[k];
        }
        out
    }
}
