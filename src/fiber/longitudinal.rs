//! d'Eon et al. 2011's longitudinal lobes M_p in f32 for the per-vertex shader (the Chiang
//! model; the f64 reference is `chiang::deon_m`, and Marschner's Gaussians are in `shader`).
//!
//! M(v; θi, θo) = exp(−sin θi sin θo / v) I0(cos θi cos θo / v) / (2v sinh(1/v)). With
//! a = cos θi cos θo / v and x = θi + θo, the exponent of the large-a form is
//! a − sin θi sin θo / v − 1/v = −(1 − cos x)/v ≤ 0, so:
//! - a ≥ 3.75: M = N_v · e^{−(1 − cos x)/v} · P(3.75/a)/√a, with e^{a}P/√a = I0(a)
//!   (Abramowitz & Stegun 9.8.2, relative error < 1.9e-7);
//! - a < 3.75: M = N_v · e^{−(1 − cos x)/v − a} · I0(a) (A&S 9.8.1, error < 1.6e-7),
//!
//! with N_v = 1/(v (1 − e^{−2/v})). Neither exponent can overflow for any v. 1 − cos x is formed
//! as sin²x/(1 + cos x) from the products of sines and cosines, so the exponent keeps its
//! relative precision near the peak even when 1/v is 10⁴ (a direct a − b − 1/v in f32 would lose
//! 1e-3 of it to cancellation there).
//!
//! The tilt is a rotation of θo per lobe with |cos| (as pbrt and Mitsuba): θo' = θo + t_p.

use super::chiang::{ChiangConstants, N_LOBES};
use glam::Vec3;

/// I0(a) e^{−a} √a for a ≥ 3.75 (Abramowitz & Stegun 9.8.2), r = 3.75/a.
#[inline]
fn i0_scaled_large(r: f32) -> f32 {
    0.398_942_3
        + r * (0.013_285_92
            + r * (0.002_253_19
                + r * (-0.001_575_65
                    + r * (0.009_162_81
                        + r * (-0.020_577_06
                            + r * (0.026_355_37 + r * (-0.016_476_33 + r * 0.003_923_77)))))))
}

/// I0(a) for 0 ≤ a ≤ 3.75 (Abramowitz & Stegun 9.8.1), t² = (a/3.75)².
#[inline]
fn i0_small(t2: f32) -> f32 {
    1.0 + t2
        * (3.515_622_9
            + t2 * (3.089_942_4
                + t2 * (1.206_749_2 + t2 * (0.265_973_2 + t2 * (0.036_076_8 + t2 * 0.004_581_3)))))
}

/// The variance-independent part of d'Eon's lobe at one direction pair: 1 − cos(θi + θo)
/// (without cancellation near 0) and cos θi cos θo.
#[derive(Clone, Copy, Debug)]
pub struct DeonGeometry {
    one_minus_cos: f32,
    cos_cos: f32,
}

impl DeonGeometry {
    /// From sin and (non-negative) cos of θi and θo.
    #[inline]
    pub fn new(si: f32, ci: f32, so: f32, co: f32) -> Self {
        let cos_x = ci * co - si * so;
        let sin_x = si * co + ci * so;
        let one_minus_cos = if cos_x > 0.0 {
            sin_x * sin_x / (1.0 + cos_x)
        } else {
            1.0 - cos_x
        };
        Self {
            one_minus_cos,
            cos_cos: ci * co,
        }
    }

    /// M at 1/v = `inv_v` with normalisation `norm` = 1/(v(1 − e^{−2/v})). 1/rad.
    #[inline]
    pub fn m(&self, inv_v: f32, norm: f32) -> f32 {
        let e = self.one_minus_cos * inv_v;
        let a = self.cos_cos * inv_v;
        if a >= 3.75 {
            norm * (-e).exp() * i0_scaled_large(3.75 / a) / a.sqrt()
        } else {
            let t = a * (1.0 / 3.75);
            norm * (-e - a).exp() * i0_small(t * t)
        }
    }
}

/// d'Eon's M at 1/v = `inv_v` with normalisation `norm` = 1/(v(1 − e^{−2/v})), from sin and
/// (non-negative) cos of θi and θo. 1/rad.
#[inline]
pub fn deon_m_f32(inv_v: f32, norm: f32, si: f32, ci: f32, so: f32, co: f32) -> f32 {
    DeonGeometry::new(si, ci, so, co).m(inv_v, norm)
}

/// 1/(v (1 − e^{−2/v})) from 1/v. e^{−2/v} is below half an f32 ulp of 1 once 1/v > 9; below
/// that 1 − e^{−2/v} ≥ 0.18 for every accepted v (≤ 4·(2·45°)² = 9.9 rad²), so the plain
/// exponential loses nothing to cancellation (and costs half of `exp_m1` in f32).
#[inline]
fn norm_from_inv_v(inv_v: f32) -> f32 {
    if inv_v > 9.0 {
        inv_v
    } else {
        inv_v / (1.0 - (-2.0 * inv_v).exp())
    }
}

/// 1/v and the normalisation of the d'Eon lobe of variance v + extra, per channel.
#[inline]
fn broadened_constants(v: f32, extra: Vec3) -> (Vec3, Vec3) {
    let inv = Vec3::ONE / (Vec3::splat(v) + extra.max(Vec3::ZERO));
    (
        inv,
        Vec3::new(
            norm_from_inv_v(inv.x),
            norm_from_inv_v(inv.y),
            norm_from_inv_v(inv.z),
        ),
    )
}

/// The four Chiang lobes' constants [R, TT, TRT, p ≥ 3] in f32. TRT and p ≥ 3 have the same
/// variance (4v₀, C16); `m_broadened_all` relies on it.
#[derive(Clone, Copy, Debug)]
pub struct DeonLobes {
    /// Variance v_p (rad²).
    pub(crate) v: [f32; N_LOBES],
    inv_v: [f32; N_LOBES],
    norm: [f32; N_LOBES],
    tilt_sin: [f32; N_LOBES],
    tilt_cos: [f32; N_LOBES],
}

impl DeonLobes {
    pub fn new(c: &ChiangConstants) -> Self {
        debug_assert_eq!(c.v[2], c.v[3], "TRT and p ≥ 3 share 4v₀");
        let v = c.v.map(|v| v as f32);
        let inv_v = c.v.map(|v| (1.0 / v) as f32);
        Self {
            v,
            inv_v,
            norm: c.v.map(|v| (1.0 / (v * -(-2.0 / v).exp_m1())) as f32),
            tilt_sin: c.tilt.map(|t| t.sin() as f32),
            tilt_cos: c.tilt.map(|t| t.cos() as f32),
        }
    }

    /// (sin θo', |cos θo'|) of lobe p's tilted outgoing inclination.
    #[inline]
    pub fn tilted(&self, p: usize, so: f32, co: f32) -> (f32, f32) {
        let (ts, tc) = (self.tilt_sin[p], self.tilt_cos[p]);
        (so * tc + co * ts, (co * tc - so * ts).abs())
    }

    /// M_p at sin/cos θi and the *tilted* sin/cos θo' ([`Self::tilted`]). 1/rad.
    #[inline]
    pub fn m(&self, p: usize, si: f32, ci: f32, so_p: f32, co_p: f32) -> f32 {
        deon_m_f32(self.inv_v[p], self.norm[p], si, ci, so_p, co_p)
    }

    /// All four lobes [R, TT, TRT, p ≥ 3] broadened by a longitudinal variance `extra` (rad², per
    /// channel): d'Eon lobes of variance v_p + extra (Zinke 2008 Eq. 23: variances of narrow
    /// lobes add), at sin/cos θi and (untilted) sin/cos θo.
    /// TRT and p ≥ 3 share their variance 4v₀ (C16), so their 1/v and normalisation are computed
    /// once.
    #[inline]
    pub fn m_broadened_all(&self, extra: Vec3, si: f32, ci: f32, so: f32, co: f32) -> [Vec3; 4] {
        let consts = [
            broadened_constants(self.v[0], extra),
            broadened_constants(self.v[1], extra),
            broadened_constants(self.v[2], extra),
        ];
        std::array::from_fn(|p| {
            let (so_p, co_p) = self.tilted(p, so, co);
            let g = DeonGeometry::new(si, ci, so_p, co_p);
            let (inv, norm) = consts[p.min(2)];
            Vec3::new(g.m(inv.x, norm.x), g.m(inv.y, norm.y), g.m(inv.z, norm.z))
        })
    }
}

#[cfg(test)]
mod tests;
