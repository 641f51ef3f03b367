//! The lobe shares of one light inclination (Zinke 2008 Eq. 6 and §3's ā_b, per lobe):
//! ā_f,p(θi) = (1/π) ∫∫ f_s,p w_f(φ) cos θo dωo and ā_b,p the same with w_b, by one
//! longitudinal quadrature over θo of the azimuthal integrals ∫ N_p w(φ) dφ (done in h,
//! `azimuthal.rs`). The azimuthal integrals are tabulated over the model's key and
//! interpolated ([`SplitTable`]), or recomputed at every node for the reference
//! ([`shares_direct`]). The cosine is the outgoing one ([`CosineReading`], trap 4 in the
//! `dual` module doc).

use super::super::azimuthal::AzimuthalSamples;
use super::super::tables::Table2;
use super::{DualModel, MAX_LOBES};
use glam::Vec3;
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// Which cosine weights Eq. 6 (trap 4); the tables use `Outgoing`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CosineReading {
    /// cos θ of the incident direction, as printed.
    Incident,
    /// cos θ of the outgoing direction (hemispherical albedo reading; the tables' reading).
    Outgoing,
}

/// Per-lobe forward and backward shares at one light inclination, before combination.
#[derive(Clone, Copy, Debug, Default)]
pub struct LobeShares {
    /// ā_f contribution of each lobe [R, TT, TRT, p ≥ 3 (Chiang only; 0 for Marschner)], RGB.
    pub forward: [[f64; 3]; MAX_LOBES],
    /// ā_b contribution of each lobe, RGB.
    pub backward: [[f64; 3]; MAX_LOBES],
}

impl LobeShares {
    /// ā_f + ā_b of channel 0 (for σa = 0: the hemispherical albedo, all channels equal).
    pub fn albedo(&self) -> f64 {
        (0..MAX_LOBES)
            .map(|l| self.forward[l][0] + self.backward[l][0])
            .sum()
    }
}

/// σa = 0 albedo ρ_w(θ) of the fibre `c` (direct quadrature; the tables use the same integral).
pub fn white_albedo<M: DualModel>(c: &M, theta: f64) -> f64 {
    shares_direct(&c.white(), theta, CosineReading::Outgoing).albedo()
}

type Split = ([f64; 3], [f64; 3]);

/// One key row of `SplitTable::build_with_n_g`: per-lobe splits and N^G rows.
type SplitRow = ([Split; MAX_LOBES], Vec<Vec<[f64; 3]>>);

/// The azimuthal integrals of each lobe against w_f and w_b, tabulated over the model's key.
pub(super) struct SplitTable {
    n: usize,
    /// [key index][lobe] -> (forward RGB, backward RGB)
    values: Vec<[Split; MAX_LOBES]>,
}

impl SplitTable {
    /// The split integrals alone.
    pub(super) fn build<M: DualModel>(c: &M, n: usize) -> Self {
        let values = (0..n)
            .into_par_iter()
            .map(|i| {
                let key = FRAC_PI_2 * i as f64 / (n - 1) as f64;
                std::array::from_fn(|l| {
                    if l < c.lobes() {
                        c.samples(l, key).split()
                    } else {
                        ([0.0; 3], [0.0; 3])
                    }
                })
            })
            .collect();
        Self { n, values }
    }

    /// The split integrals and the N^G rows (φ over [0, π], `n_phi` samples, forward window of
    /// half-width `window`) on the same `n` samples of the key, from one set of samples per
    /// (key, lobe).
    pub(super) fn build_with_n_g<M: DualModel>(
        c: &M,
        n: usize,
        n_phi: usize,
        window: f64,
    ) -> (Self, Vec<Table2>) {
        let lobes = c.lobes();
        let rows: Vec<SplitRow> = (0..n)
            .into_par_iter()
            .map(|i| {
                let key = FRAC_PI_2 * i as f64 / (n - 1) as f64;
                let samples: Vec<M::Samples> = (0..lobes).map(|l| c.samples(l, key)).collect();
                let split = std::array::from_fn(|l| {
                    samples.get(l).map_or(([0.0; 3], [0.0; 3]), |s| s.split())
                });
                let n_g = samples.iter().map(|s| s.n_g_row(n_phi, window)).collect();
                (split, n_g)
            })
            .collect();
        let values = rows.iter().map(|r| r.0).collect();
        let n_g = (0..lobes)
            .map(|l| {
                Table2::from_values(
                    n,
                    n_phi,
                    rows.iter()
                        .flat_map(|r| r.1[l].iter().map(|v| Vec3::from(v.map(|x| x as f32))))
                        .collect(),
                )
            })
            .collect();
        (Self { n, values }, n_g)
    }

    fn lookup(&self, key: f64, lobe: usize) -> Split {
        let f = (key / FRAC_PI_2 * (self.n - 1) as f64).clamp(0.0, (self.n - 1) as f64);
        let i = (f as usize).min(self.n - 2);
        let t = f - i as f64;
        let (a, b) = (self.values[i][lobe], self.values[i + 1][lobe]);
        let mix = |x: [f64; 3], y: [f64; 3]| [0, 1, 2].map(|k| x[k] * (1.0 - t) + y[k] * t);
        (mix(a.0, b.0), mix(a.1, b.1))
    }
}

/// Lobe shares at θi by one longitudinal quadrature over θo, with azimuthal integrals from
/// `split` (or recomputed at every node when `split` is None: the reference).
pub(super) fn shares_at<M: DualModel>(
    c: &M,
    theta_i: f64,
    split: Option<&SplitTable>,
    reading: CosineReading,
) -> LobeShares {
    let min_std = (0..c.lobes())
        .map(|l| c.lobe_var_x(l).sqrt())
        .fold(f64::MAX, f64::min);
    let n_o = ((PI / (min_std / 4.0)).ceil() as usize).clamp(256, 8192);
    let d_o = PI / n_o as f64;
    let mut out = LobeShares::default();
    for k in 0..n_o {
        let theta_o = -FRAC_PI_2 + (k as f64 + 0.5) * d_o;
        let cos_w = match reading {
            CosineReading::Incident => theta_i.cos(),
            CosineReading::Outgoing => theta_o.cos(),
        };
        let geom = cos_w * theta_o.cos() * d_o;
        let key = c.key(theta_i, theta_o);
        for lobe in 0..c.lobes() {
            let m = c.longitudinal(lobe, theta_i, theta_o);
            if m * geom < 1e-300 {
                continue;
            }
            let (f, b) = match split {
                Some(s) => s.lookup(key, lobe),
                None => c.samples(lobe, key).split(),
            };
            for ch in 0..3 {
                out.forward[lobe][ch] += m * geom * f[ch];
                out.backward[lobe][ch] += m * geom * b[ch];
            }
        }
    }
    out
}

/// Direct (untabulated) lobe shares at θi, for checking the tables: azimuthal integrals are
/// recomputed at every θo node instead of interpolated. Slow (≈ 0.1 s).
pub fn shares_direct<M: DualModel>(c: &M, theta_i: f64, reading: CosineReading) -> LobeShares {
    shares_at(c, theta_i, None, reading)
}
