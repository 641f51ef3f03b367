//! Marschner et al. 2003 BCSDF, evaluated exactly (no tables): longitudinal lobes M_p,
//! azimuthal lobes N_p (Eq. 8) from the exact roots of Eq. 3, attenuation A(p, h), the TRT
//! caustic smoothing (§5.2.2) and eccentricity through η*(φh) (§5.2.3).
//!
//! Everything here is f64 and radians. The renderer does not call these per pixel: `Fiber::new`
//! tabulates N_p from them (see `tables.rs`), and tests compare the tables against them.
//!
//! **Roots (Eq. 3 vs Eq. 10).** φ(p, h) = 2pγt − 2γi + pπ is solved exactly, in the variable γi
//! (smooth up to γi = ±π/2, where dφ/dh is infinite), by safeguarded Newton inside brackets.
//! φ is monotone between its folds, so each monotone piece holds at most one root: R and TT
//! have one piece; TRT has three pieces split at ±γc (Descartes, Eq. 4) while η' < 2, and one
//! after the caustic merge. **Trap 7 (roots coalesce)**: near the merge two roots approach the
//! fold from both sides; bracketing each piece separately finds both, where a single Newton
//! start would converge to one and drop the other (pinned by `trp_finds_three_roots_near_merge`).
//! Marschner's cubic (Eq. 10) is not used: its 0.75° error in γt moves TT's φ-range edges and the
//! TRT caustic (measured in `cubic_eq10_error_is_measurable`: N_TT differs by up to 7.4% of its
//! peak, near the range edge), while the exact solve runs only while tables are built (the
//! renderer reads tables), so its cost does not reach the frame.
//!
//! **Trap 8 (no path).** Where φ lies outside a lobe's range (TT: |φ| < 2c with c = asin(1/η');
//! TRT beyond its outermost extremum) there is no root, and N_p is exactly 0 there, never the
//! value of the nearest path.
//!
//! **Trap 9 (grazing).** 1/cos²θd is unbounded as |θd| → π/2; cos θd is floored at
//! [`COS_THETA_D_MIN`] (|θd| ≤ 89.43°), which bounds the factor at 10⁴. Only the corner θi = −θo =
//! ±90° (light and view along the fibre, opposite ways) reaches the floor; the alternative (no
//! floor) gives +∞ there, and any smaller floor only raises the bound.

mod caustic;

pub use caustic::{Caustic, smoothstep_paper};

use super::fresnel::{eta_double_prime, eta_prime, fresnel_generalized};
use super::params::{Lobe, LobeConstants};
use std::f64::consts::PI;

/// Floor of cos θd in 1/cos²θd (trap 9): |θd| ≤ acos(0.01) = 89.43°.
pub const COS_THETA_D_MIN: f64 = 0.01;

/// Unit-area Gaussian of standard deviation `std` (radians) at `x` (radians), in 1/rad.
pub fn gaussian(x: f64, std: f64) -> f64 {
    (-0.5 * (x / std) * (x / std)).exp() / (std * (2.0 * PI).sqrt())
}

/// Wraps an angle into [−π, π].
pub fn wrap_pi(a: f64) -> f64 {
    let mut x = (a + PI).rem_euclid(2.0 * PI) - PI;
    if x < -PI {
        x += 2.0 * PI;
    }
    x
}

/// Longitudinal lobe M_p (Marschner 2003 §5.1) normalised in θo: a unit-area Gaussian in
/// x = θi + θo (= 2θh) with mean 2α_p and standard deviation 2β_p, i.e. g(β_p; θh − α_p)/2.
/// Units 1/rad; θi, θo in radians.
///
/// **Trap 1.** Marschner's g(β; θh − α) has unit area in θh and therefore area 2 over θo; fed
/// into Zinke's Eq. 6 it makes ā_f > 1 and A_b < 0. We keep Marschner's widths (β in θh) and
/// halve the value, so the lobe has unit area in the variable every integral here runs over (θo
/// at fixed θi). The alternative (unit area in θh) doubles every energy integral (pinned by
/// `m_has_unit_area_in_theta_o`). `wisp fiber eval` reports this as "theta_o".
pub fn longitudinal_m(c: &LobeConstants, lobe: Lobe, theta_i: f64, theta_o: f64) -> f64 {
    gaussian(theta_i + theta_o - c.mean_x(lobe), c.std_x(lobe))
}

/// Marschner 2003 §5.2.3: index η*(φh) that mimics an elliptical cross section of eccentricity a
/// in the circular TRT model; η₁* = 2(η − 1)a² − η + 2, η₂* = 2(η − 1)a⁻² − η + 2 and
/// η* = ½(η₁* + η₂*) + ½ cos(2φh)(η₁* − η₂*). Takes cos 2φh (in [−1, 1]); returns η* > 1
/// (guaranteed for a² > ½, see `FiberParams::eccentricity`).
pub fn eta_star(eta: f64, eccentricity: f64, cos_2phi_h: f64) -> f64 {
    let a2 = eccentricity * eccentricity;
    let e1 = 2.0 * (eta - 1.0) * a2 - eta + 2.0;
    let e2 = 2.0 * (eta - 1.0) / a2 - eta + 2.0;
    (0.5 * (e1 + e2) + 0.5 * cos_2phi_h.clamp(-1.0, 1.0) * (e1 - e2)).max(1.0 + 1e-6)
}

/// The 2D (normal-plane) scattering problem at one difference angle θd for one index η:
/// Bravais indices η', η'' and the absorption σa' = σa / cos θt (Marschner 2003 §4.3, App. B).
///
/// θt here is the refracted inclination for θd (sin θt = sin θd / η), like η'(θd): both depend
/// on θd only through sin²θd, which keeps S reciprocal.
#[derive(Clone, Copy, Debug)]
pub struct Azimuth {
    pub eta_prime: f64,
    pub eta_dprime: f64,
    /// σa / cos θt per unit radius, RGB.
    pub sigma_a_prime: [f64; 3],
}

impl Azimuth {
    pub fn new(eta: f64, sin_theta_d: f64, sigma_a: [f64; 3]) -> Self {
        let s = sin_theta_d.clamp(-1.0, 1.0);
        // Trap 9: keep η' finite at |θd| = 90° with the same floor as 1/cos²θd.
        let s = s.clamp(
            -(1.0 - COS_THETA_D_MIN * COS_THETA_D_MIN).sqrt(),
            (1.0 - COS_THETA_D_MIN * COS_THETA_D_MIN).sqrt(),
        );
        let sin_t = s / eta;
        let cos_t = (1.0 - sin_t * sin_t).sqrt();
        Self {
            eta_prime: eta_prime(eta, s),
            eta_dprime: eta_double_prime(eta, s),
            sigma_a_prime: sigma_a.map(|x| x / cos_t),
        }
    }

    /// Eq. 3: exit azimuth φ(p, γi) = 2pγt − 2γi + pπ, unwrapped, with sin γi = η' sin γt.
    pub fn phi(&self, p: u32, gamma_i: f64) -> f64 {
        let gamma_t = (gamma_i.sin() / self.eta_prime).clamp(-1.0, 1.0).asin();
        2.0 * p as f64 * gamma_t - 2.0 * gamma_i + p as f64 * PI
    }

    /// dφ/dγi = 2p cos γi / (η' cos γt) − 2 (finite on the closed interval).
    pub fn dphi_dgamma_i(&self, p: u32, gamma_i: f64) -> f64 {
        let sin_t = gamma_i.sin() / self.eta_prime;
        let cos_t = (1.0 - sin_t * sin_t).max(0.0).sqrt();
        2.0 * p as f64 * gamma_i.cos() / (self.eta_prime * cos_t) - 2.0
    }

    /// d²φ/dh² = 2ph/(η'² − h²)^{3/2} − 2h/(1 − h²)^{3/2}, for |h| < 1.
    pub fn d2phi_dh2(&self, p: u32, h: f64) -> f64 {
        let e2 = self.eta_prime * self.eta_prime;
        2.0 * p as f64 * h / (e2 - h * h).powf(1.5) - 2.0 * h / (1.0 - h * h).max(1e-300).powf(1.5)
    }

    /// Attenuation A(p, h) of Marschner 2003 §4.3 generalised to 3D, RGB, with h = sin γi:
    /// A(0) = F(η', η'', γi); A(p) = (1 − F(η', η'', γi))² F(1/η', 1/η'', γt)^{p−1} T^p, with
    /// T = exp(−σa' · 2 cos γt): the internal chord of a unit circle is 2 cos γt radii (the
    /// printed 2 + 2 cos 2γt is its square; blog notes, Zinke 2007). In [0, 1].
    pub fn attenuation(&self, p: u32, gamma_i: f64) -> [f64; 3] {
        let f_i = fresnel_generalized(self.eta_prime, self.eta_dprime, gamma_i.cos());
        if p == 0 {
            return [f_i; 3];
        }
        let sin_t = gamma_i.sin() / self.eta_prime;
        let cos_t = (1.0 - sin_t * sin_t).max(0.0).sqrt();
        let f_t = fresnel_generalized(1.0 / self.eta_prime, 1.0 / self.eta_dprime, cos_t);
        let base = (1.0 - f_i) * (1.0 - f_i) * f_t.powi(p as i32 - 1);
        let chord = 2.0 * cos_t;
        self.sigma_a_prime
            .map(|s| base * (-(s * chord) * p as f64).exp())
    }

    /// Monotone pieces of φ(p, ·) over γi ∈ [−π/2, π/2] (see module doc).
    pub fn pieces(&self, p: u32) -> ([(f64, f64); 3], usize) {
        let h = PI / 2.0;
        if p == 2 && self.eta_prime < 2.0 {
            let gc = ((4.0 - self.eta_prime * self.eta_prime) / 3.0)
                .sqrt()
                .asin();
            ([(-h, -gc), (-gc, gc), (gc, h)], 3)
        } else {
            ([(-h, h), (0.0, 0.0), (0.0, 0.0)], 1)
        }
    }

    /// All roots γi of φ(p, γi) ≡ φ (mod 2π), at most three.
    pub fn roots(&self, p: u32, phi: f64) -> ([f64; 3], usize) {
        let mut out = [0.0; 3];
        if p == 0 {
            out[0] = -wrap_pi(phi) / 2.0;
            return (out, 1);
        }
        let (pieces, n) = self.pieces(p);
        let mut count = 0;
        for &(g0, g1) in &pieces[..n] {
            let (f0, f1) = (self.phi(p, g0), self.phi(p, g1));
            let (lo, hi) = (f0.min(f1), f0.max(f1));
            let k = ((lo - phi) / (2.0 * PI)).ceil();
            let target = phi + 2.0 * PI * k;
            if target > hi {
                continue; // trap 8: no path through this piece
            }
            out[count] = self.solve_piece(p, target, g0, g1, f0);
            count += 1;
        }
        (out, count)
    }

    /// Safeguarded Newton for φ(p, γ) = target on a monotone bracket [g0, g1].
    fn solve_piece(&self, p: u32, target: f64, g0: f64, g1: f64, f0: f64) -> f64 {
        let (mut a, mut b) = (g0, g1);
        let fa0 = f0 - target;
        if fa0 == 0.0 {
            return g0;
        }
        let sign_a = fa0 > 0.0;
        let mut g = 0.5 * (a + b);
        for _ in 0..100 {
            let fg = self.phi(p, g) - target;
            if fg == 0.0 {
                return g;
            }
            if (fg > 0.0) == sign_a {
                a = g;
            } else {
                b = g;
            }
            let d = self.dphi_dgamma_i(p, g);
            let mut next = g - fg / d;
            let (lo, hi) = (a.min(b), a.max(b));
            if !(next > lo && next < hi) {
                next = 0.5 * (a + b);
            }
            if (next - g).abs() < 1e-15 || (hi - lo) < 1e-15 {
                return next;
            }
            g = next;
        }
        g
    }

    /// Eq. 8 for one root: A(p, h) / |2 dφ/dh| = A cos γi / (2|dφ/dγi|), RGB.
    fn root_term(&self, p: u32, gamma_i: f64) -> [f64; 3] {
        let d = self.dphi_dgamma_i(p, gamma_i).abs().max(1e-12);
        let w = gamma_i.cos().max(0.0) / (2.0 * d);
        self.attenuation(p, gamma_i).map(|a| a * w)
    }

    /// Raw N_p(φ) of Eq. 8: sum over the roots of Eq. 3 (0 where there is none). RGB, 1/rad.
    /// Infinite only at a fold (the TRT caustic), where the caller multiplies by zero.
    pub fn n_raw(&self, p: u32, phi: f64) -> [f64; 3] {
        let (roots, n) = self.roots(p, phi);
        let mut out = [0.0; 3];
        for &g in &roots[..n] {
            let t = self.root_term(p, g);
            for c in 0..3 {
                out[c] += t[c];
            }
        }
        out
    }
}

/// The azimuthal geometry lobe `lobe` uses at difference angle θd (radians) and cos 2φh: R and
/// TT use η; TRT uses η*(φh) (§5.2.3).
pub fn azimuth_for(c: &LobeConstants, lobe: Lobe, sin_theta_d: f64, cos_2phi_h: f64) -> Azimuth {
    let eta = if lobe == Lobe::TRT {
        eta_star(c.eta, c.eccentricity, cos_2phi_h)
    } else {
        c.eta
    };
    Azimuth::new(eta, sin_theta_d, c.sigma_a)
}

/// N_p(θd, φ) as the model uses it: raw Eq. 8 for R and TT, smoothed for TRT. RGB, 1/rad.
pub fn n_lobe(
    c: &LobeConstants,
    lobe: Lobe,
    sin_theta_d: f64,
    phi: f64,
    cos_2phi_h: f64,
) -> [f64; 3] {
    let az = azimuth_for(c, lobe, sin_theta_d, cos_2phi_h);
    match lobe {
        Lobe::TRT => az.n_trt_smoothed(c, phi),
        _ => az.n_raw(lobe.p(), phi),
    }
}

/// 1 / cos²θd with the trap-9 floor.
pub fn inv_cos2_theta_d(theta_d: f64) -> f64 {
    let c = theta_d.cos().max(COS_THETA_D_MIN);
    1.0 / (c * c)
}

/// The full BCSDF S = Σ_p M_p(θh) N_p(θd, φ) / cos²θd (Marschner 2003 Eq. 9), per lobe, RGB,
/// evaluated exactly. Angles in radians: θi, θo ∈ [−π/2, π/2], φ = φo − φi, cos 2φh =
/// cos(φi + φo). Units 1/sr.
pub fn bcsdf_exact(
    c: &LobeConstants,
    theta_i: f64,
    theta_o: f64,
    phi: f64,
    cos_2phi_h: f64,
) -> [[f64; 3]; 3] {
    let theta_d = 0.5 * (theta_o - theta_i);
    let inv = inv_cos2_theta_d(theta_d);
    let mut out = [[0.0; 3]; 3];
    for lobe in Lobe::ALL {
        let m = longitudinal_m(c, lobe, theta_i, theta_o);
        let n = n_lobe(c, lobe, theta_d.sin(), phi, cos_2phi_h);
        out[lobe as usize] = n.map(|x| m * x * inv);
    }
    out
}

#[cfg(test)]
mod tests;
