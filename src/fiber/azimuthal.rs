//! Azimuthal integrals of the lobes N_p (Marschner 2003 Eq. 8) for the dual-scattering tables,
//! done in h rather than φ: ∫ N_p(φ) w(φ) dφ = ∫ A(p, h) w(φ(p, h)) dh / 2, since each h maps to
//! one exit azimuth and Eq. 8 divides by |dφ/dh|. This needs no root solving and has a smooth
//! integrand (the caustics, infinite in φ, are harmless in h); only the TRT glints, which are
//! defined in φ, are integrated in φ. Also the front/back weights of Eqs. 6 and 12, N^G of
//! Eq. 25, and the direct references the tests compare against. Circular fibre (index η).

use super::marschner::{Azimuth, gaussian, wrap_pi};
use super::params::{Lobe, LobeConstants};
use std::f64::consts::{FRAC_PI_2, PI};

/// Samples of γi in the h-space quadratures (midpoint rule).
pub const N_H: usize = 1024;

/// Histogram bins over the circle for N^G (Eq. 25).
pub const N_G_BINS: usize = 2048;

/// Forward weight of a relative azimuth φ: share of incident azimuths in the light-facing half
/// circle whose outgoing azimuth lands in the front half (|φ|/π).
pub fn w_forward(phi: f64) -> f64 {
    wrap_pi(phi).abs() / PI
}

/// Backward weight, 1 − |φ|/π.
pub fn w_backward(phi: f64) -> f64 {
    1.0 - w_forward(phi)
}

/// Error function (Abramowitz & Stegun 7.1.26, |error| ≤ 1.5·10⁻⁷).
pub fn erf(x: f64) -> f64 {
    let s = x.signum();
    let x = x.abs();
    let t = 1.0 / (1.0 + 0.327_591_1 * x);
    let y = 1.0
        - (((((1.061_405_429 * t - 1.453_152_027) * t) + 1.421_413_741) * t - 0.284_496_736) * t
            + 0.254_829_592)
            * t
            * (-x * x).exp();
    s * y
}

fn normal_cdf(x: f64, std: f64) -> f64 {
    0.5 * (1.0 + erf(x / (std * std::f64::consts::SQRT_2)))
}

/// One lobe at one θd, sampled in h (midpoint rule in γi, h = sin γi): exit azimuths φ(p, h)
/// and weights A(p, h) · notch(φ) · dh/2, plus the TRT glints (amplitude, φc, w_c). Every
/// azimuthal integral of N_p is a sum over these samples (Eq. 8 bookkeeping).
pub struct LobeSamples {
    phi: Vec<f64>,
    weight: Vec<[f64; 3]>,
    glint: Option<([f64; 3], f64, f64)>,
}

impl LobeSamples {
    /// Samples for the circular fibre (index η) at sin θd, with `n_h` samples of γi.
    pub fn new(c: &LobeConstants, lobe: Lobe, sin_theta_d: f64, n_h: usize) -> Self {
        let az = Azimuth::new(c.eta, sin_theta_d, c.sigma_a);
        let p = lobe.p();
        let caustic = (lobe == Lobe::TRT).then(|| az.caustic(c));
        let dg = PI / n_h as f64;
        let mut phi = Vec::with_capacity(n_h);
        let mut weight = Vec::with_capacity(n_h);
        for k in 0..n_h {
            let g = -FRAC_PI_2 + (k as f64 + 0.5) * dg;
            let ph = wrap_pi(az.phi(p, g));
            let mut wt = g.cos() * dg * 0.5;
            if let Some(ca) = &caustic {
                wt *= Azimuth::notch(ca, c.w_c, ph);
            }
            phi.push(ph);
            weight.push(az.attenuation(p, g).map(|a| a * wt));
        }
        let glint = caustic.map(|ca| {
            let a = az.attenuation(2, ca.gamma_c);
            let k = ca.t * c.k_g * ca.delta_h;
            (a.map(|x| x * k), ca.phi_c, c.w_c)
        });
        Self { phi, weight, glint }
    }

    /// ∫ N_p(φ) w(φ) dφ over the circle, RGB (glints by midpoint quadrature in φ at w_c/8).
    pub fn integral(&self, w: impl Fn(f64) -> f64) -> [f64; 3] {
        let mut acc = [0.0; 3];
        for (ph, wt) in self.phi.iter().zip(&self.weight) {
            let f = w(*ph);
            for ch in 0..3 {
                acc[ch] += wt[ch] * f;
            }
        }
        if let Some((amp, phi_c, w_c)) = self.glint {
            let n = ((16.0 * PI / w_c).ceil() as usize).max(256);
            let d = 2.0 * PI / n as f64;
            let mut sum = 0.0;
            for k in 0..n {
                let ph = -PI + (k as f64 + 0.5) * d;
                sum += (gaussian(ph - phi_c, w_c) + gaussian(ph + phi_c, w_c)) * w(ph) * d;
            }
            for ch in 0..3 {
                acc[ch] += amp[ch] * sum;
            }
        }
        acc
    }

    /// N^G_p(φ) = (1/2w) ∫_{φ−w}^{φ+w} N_p(ψ) dψ (Eq. 25 read as a convolution, trap 5; w =
    /// `window` radians, Zinke's π/2 by default, `FiberParams::forward_spread_deg`), for φ at the
    /// `n_phi` grid points over [0, π]. The sampled (notched) part is deposited into a
    /// `bins`-bin histogram over the circle (linear split between the two nearest bins) and
    /// integrated through its cumulative sum; the glints use the Gaussian's closed-form CDF.
    pub fn n_g(&self, n_phi: usize, bins: usize, window: f64) -> Vec<[f64; 3]> {
        let dw = 2.0 * PI / bins as f64;
        let mut hist = vec![[0.0f64; 3]; bins];
        for (ph, wt) in self.phi.iter().zip(&self.weight) {
            let u = (ph + PI) / dw - 0.5;
            let i0 = u.floor();
            let frac = u - i0;
            let i0 = (i0 as i64).rem_euclid(bins as i64) as usize;
            let i1 = (i0 + 1) % bins;
            for ch in 0..3 {
                hist[i0][ch] += wt[ch] * (1.0 - frac);
                hist[i1][ch] += wt[ch] * frac;
            }
        }
        let mut cum = vec![[0.0f64; 3]; bins + 1];
        for j in 0..bins {
            for ch in 0..3 {
                cum[j + 1][ch] = cum[j][ch] + hist[j][ch];
            }
        }
        let total = cum[bins];
        // Cumulative mass from −π to x (any real x, wrapping); bin j spans [−π + j dw, +dw).
        let cum_at = |x: f64| -> [f64; 3] {
            let wraps = ((x + PI) / (2.0 * PI)).floor();
            let xr = x - 2.0 * PI * wraps;
            let f = ((xr + PI) / dw).clamp(0.0, bins as f64);
            let j = (f as usize).min(bins - 1);
            let t = f - j as f64;
            [0, 1, 2].map(|ch| wraps * total[ch] + cum[j][ch] * (1.0 - t) + cum[j + 1][ch] * t)
        };
        (0..n_phi)
            .map(|k| {
                let phi = PI * k as f64 / (n_phi - 1) as f64;
                let (lo, hi) = (phi - window, phi + window);
                let (c_hi, c_lo) = (cum_at(hi), cum_at(lo));
                let mut out = [0, 1, 2].map(|ch| (c_hi[ch] - c_lo[ch]) / (2.0 * window));
                if let Some((amp, phi_c, w_c)) = self.glint {
                    let mut mass = 0.0;
                    for mu in [phi_c, -phi_c] {
                        for k in [-1.0, 0.0, 1.0] {
                            let s = 2.0 * PI * k;
                            mass += normal_cdf(hi - mu + s, w_c) - normal_cdf(lo - mu + s, w_c);
                        }
                    }
                    for ch in 0..3 {
                        out[ch] += amp[ch] * mass / (2.0 * window);
                    }
                }
                out
            })
            .collect()
    }
}

/// ∫ N_p(θd, φ) w(φ) dφ over the circle for the circular fibre, RGB, computed in h (Eq. 8
/// bookkeeping) plus, for TRT, the glints integrated in φ.
pub fn lobe_integral(
    c: &LobeConstants,
    lobe: Lobe,
    sin_theta_d: f64,
    w: impl Fn(f64) -> f64,
) -> [f64; 3] {
    LobeSamples::new(c, lobe, sin_theta_d, N_H).integral(w)
}

/// Direct N^G_p(θd, φ) by midpoint quadrature of the exact N_p over ψ ∈ [φ − w, φ + w] with
/// weight 1/(2w) (reference for the tests), circular fibre; `window` = w in radians.
pub fn n_g_direct(
    c: &LobeConstants,
    lobe: Lobe,
    theta_d: f64,
    phi: f64,
    window: f64,
    n: usize,
) -> [f64; 3] {
    let az = Azimuth::new(c.eta, theta_d.sin(), c.sigma_a);
    let d = 2.0 * window / n as f64;
    let mut acc = [0.0; 3];
    for k in 0..n {
        let psi = phi - window + (k as f64 + 0.5) * d;
        let v = match lobe {
            Lobe::TRT => az.n_trt_smoothed(c, psi),
            _ => az.n_raw(lobe.p(), psi),
        };
        for ch in 0..3 {
            acc[ch] += v[ch] * d / (2.0 * window);
        }
    }
    acc
}

/// What the dual-scattering tables need from one lobe at one value of the azimuthal table's key
/// (|θd| for Marschner, |θo| for Chiang): its integrals against the front/back weights (Eqs. 6,
/// 12) and N^G (Eq. 25).
pub trait AzimuthalSamples {
    /// (∫ N_p w_f dφ, ∫ N_p w_b dφ) over the circle, RGB.
    fn split(&self) -> ([f64; 3], [f64; 3]);
    /// N^G_p at `n_phi` grid points over |φ| ∈ [0, π], for a forward window of half-width
    /// `window` radians.
    fn n_g_row(&self, n_phi: usize, window: f64) -> Vec<[f64; 3]>;
}

impl AzimuthalSamples for LobeSamples {
    fn split(&self) -> ([f64; 3], [f64; 3]) {
        (self.integral(w_forward), self.integral(w_backward))
    }

    fn n_g_row(&self, n_phi: usize, window: f64) -> Vec<[f64; 3]> {
        self.n_g(n_phi, N_G_BINS, window)
    }
}

#[cfg(test)]
mod tests;
