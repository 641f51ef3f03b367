//! Tables of the Chiang model's far-field azimuthal lobes N̄_p(θo, φ) = ½∫ A_p N_p dh
//! (`chiang.rs`), its front/back integrals and N^G (Zinke 2008 Eq. 25), for the shader and the
//! dual-scattering tables.
//!
//! **How.** For one lobe at one θo, γo is cut into [`N_GAMMA`] equal segments. Over a segment the
//! exit azimuth Φ_p(γo) is close to linear, so the segment's h-measure w_k = A_p cos γo Δγ/2 (at
//! its midpoint) is spread uniformly over [Φ_k, Φ_{k+1}]. Convolving that box with the trimmed
//! logistic is exact through the logistic's closed-form CDF C:
//! N̄(φ) = Σ_k w_k (C(φ − Φ_k) − C(φ − Φ_{k+1})) / (Φ_{k+1} − Φ_k). This is exact for any
//! roughness, including s far below the segment width (where N̄ tends to the box histogram) and
//! at the TRT caustics, where Φ folds and the raw N of Marschner's Eq. 8 is infinite. Errors come
//! only from Φ's curvature and w's variation inside a segment: 2.6e-5 (1/rad, R lobe, peaks 0.016
//! to 0.2) at 256 segments and β_n = 0.3, 3.3e-4 at β_n = 0.05 where s is below a segment's
//! azimuth span (`tests/lib/fiber_chiang.rs`, against `chiang::n_bar_direct` with 20 000 nodes);
//! the 2° table grid's own interpolation error is 1.7e-4.
//! - ∫ N̄ w_f dφ uses w_f ⊛ logistic in closed form (`chiang::w_forward_smoothed`) at the
//!   segment midpoints.
//! - N^G = N̄ convolved with the forward window: first the window over the segments (exact
//!   overlaps into a 2048-bin cumulative), on the table's φ grid round the circle, then the
//!   logistic as cell masses of C on that grid (the windowed function is smooth, so the cell
//!   rule errs by O(Δ²)).
//! - The p ≥ 3 residual is uniform in φ: N̄_3 = Ā_3/(2π), split ½/½, N^G_3 = N̄_3.
//!
//! Rejected: a fine histogram of the raw samples convolved with the logistic (91 × 2048 MACs per
//! row, lobe and channel, and bin aliasing for small s); sampling N_p at points (needs
//! ~s/ΔΦ more samples to resolve small roughness).

use super::azimuthal::AzimuthalSamples;
use super::chiang::{self, ChiangConstants, N_LOBES, RESIDUAL, TrimmedLogistic};
use super::tables::{Table2, TableResolution};
use glam::Vec3;
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// Segments of γo ∈ [−π/2, π/2] per (θo, lobe). Chosen by measured error at the table nodes
/// (β_n = 0.3, max abs over θo, 1/rad): 64 → 3.8e-4, 128 → 9.4e-5, 256 → 2.3e-5; 256 keeps it
/// well below the grid's interpolation error (1.7e-4) for ≈ 30 ms of build time.
pub const N_GAMMA: usize = 256;

/// One lobe at one θo: segment end azimuths (unwrapped), midpoint azimuths and weights.
#[derive(Clone, Debug)]
pub struct ChiangSamples {
    residual: bool,
    s: f64,
    logistic: TrimmedLogistic,
    nodes: Vec<f64>,
    mid: Vec<f64>,
    weight: Vec<[f64; 3]>,
    /// ∫ N̄ dφ = Ā_p (the lobe's h-averaged attenuation), RGB.
    pub total: [f64; 3],
}

impl ChiangSamples {
    /// Lobe `lobe` (0 R, 1 TT, 2 TRT, 3 p ≥ 3) at sin θo with `n` segments of γo.
    pub fn new(c: &ChiangConstants, lobe: usize, sin_theta_o: f64, n: usize) -> Self {
        let residual = lobe == RESIDUAL;
        let dg = PI / n as f64;
        let nodes = if residual {
            Vec::new()
        } else {
            (0..=n)
                .map(|k| {
                    let g = -FRAC_PI_2 + k as f64 * dg;
                    chiang::exit_azimuth(c.eta, sin_theta_o, lobe, g)
                })
                .collect()
        };
        let mut mid = Vec::with_capacity(n);
        let mut weight = Vec::with_capacity(n);
        let mut total = [0.0; 3];
        for k in 0..n {
            let g = -FRAC_PI_2 + (k as f64 + 0.5) * dg;
            let a = chiang::attenuation(c, sin_theta_o, g.sin())[lobe];
            let w = a.map(|x| x * g.cos() * dg * 0.5);
            for ch in 0..3 {
                total[ch] += w[ch];
            }
            if !residual {
                mid.push(chiang::exit_azimuth(c.eta, sin_theta_o, lobe, g));
                weight.push(w);
            }
        }
        Self {
            residual,
            s: c.s,
            logistic: TrimmedLogistic::new(c.s),
            nodes,
            mid,
            weight,
            total,
        }
    }

    /// N̄_p(φ), RGB, 1/rad: the segments convolved with the trimmed logistic (module doc).
    pub fn n_bar(&self, phi: f64) -> [f64; 3] {
        if self.residual {
            return self.total.map(|t| t / (2.0 * PI));
        }
        let s = self.s;
        let mut acc = [0.0; 3];
        let l = &self.logistic;
        let mut prev = l.cdf(phi - self.nodes[0]);
        for k in 0..self.weight.len() {
            let next = l.cdf(phi - self.nodes[k + 1]);
            let d = self.nodes[k + 1] - self.nodes[k];
            // A segment much shorter than the logistic is a point mass (avoids 0/0).
            let density = if d.abs() > 1e-7 * s {
                (prev - next) / d
            } else {
                l.pdf(phi - self.mid[k])
            };
            for (a, w) in acc.iter_mut().zip(&self.weight[k]) {
                *a += w * density;
            }
            prev = next;
        }
        acc
    }

    /// The segments' h-measure as a cumulative over the circle: `bins` equal bins from −π, each
    /// segment spread uniformly over its azimuth range (exact overlaps), then summed.
    /// Returns cum[0..=bins] (cum[0] = 0, cum[bins] = total), RGB.
    fn cumulative(&self, bins: usize) -> Vec<[f64; 3]> {
        let db = 2.0 * PI / bins as f64;
        let mut hist = vec![[0.0f64; 3]; bins];
        for k in 0..self.weight.len() {
            let (a, b) = (
                self.nodes[k].min(self.nodes[k + 1]),
                self.nodes[k].max(self.nodes[k + 1]),
            );
            let w = self.weight[k];
            let (fa, fb) = ((a + PI) / db, (b + PI) / db);
            let (ia, ib) = (fa.floor(), fb.floor());
            let deposit = |hist: &mut Vec<[f64; 3]>, i: f64, frac: f64| {
                let j = (i as i64).rem_euclid(bins as i64) as usize;
                for ch in 0..3 {
                    hist[j][ch] += w[ch] * frac;
                }
            };
            if ib == ia || fb - fa < 1e-12 {
                deposit(&mut hist, ia, 1.0);
                continue;
            }
            let len = fb - fa;
            deposit(&mut hist, ia, (ia + 1.0 - fa) / len);
            let mut i = ia + 1.0;
            while i < ib {
                deposit(&mut hist, i, 1.0 / len);
                i += 1.0;
            }
            deposit(&mut hist, ib, (fb - ib) / len);
        }
        let mut cum = vec![[0.0f64; 3]; bins + 1];
        for j in 0..bins {
            for ch in 0..3 {
                cum[j + 1][ch] = cum[j][ch] + hist[j][ch];
            }
        }
        cum
    }
}

/// The cumulative of [`ChiangSamples::cumulative`] at any real azimuth x (periodic: it grows by
/// the total per turn), linear inside a bin.
fn cumulative_at(cum: &[[f64; 3]], x: f64) -> [f64; 3] {
    let bins = cum.len() - 1;
    let turns = ((x + PI) / (2.0 * PI)).floor();
    let f = ((x - 2.0 * PI * turns + PI) / (2.0 * PI) * bins as f64).clamp(0.0, bins as f64);
    let j = (f as usize).min(bins - 1);
    let t = f - j as f64;
    [0, 1, 2].map(|ch| turns * cum[bins][ch] + cum[j][ch] * (1.0 - t) + cum[j + 1][ch] * t)
}

/// Bins round the circle for the window integrals of N^G (0.18° each).
const N_G_BINS: usize = 2048;

impl AzimuthalSamples for ChiangSamples {
    fn split(&self) -> ([f64; 3], [f64; 3]) {
        if self.residual {
            let half = self.total.map(|t| 0.5 * t);
            return (half, half);
        }
        let mut fwd = [0.0; 3];
        for (m, w) in self.mid.iter().zip(&self.weight) {
            let f = chiang::w_forward_smoothed(*m, self.s);
            for ch in 0..3 {
                fwd[ch] += w[ch] * f;
            }
        }
        let back = [0, 1, 2].map(|ch| (self.total[ch] - fwd[ch]).max(0.0));
        (fwd, back)
    }

    fn n_g_row(&self, n_phi: usize, window: f64) -> Vec<[f64; 3]> {
        if self.residual {
            return vec![self.total.map(|t| t / (2.0 * PI)); n_phi];
        }
        // The window over the segments at the table's φ step round the whole circle
        // (φ_m = −π + mΔ), from the cumulative; then the logistic as cell masses of C.
        let m_count = 2 * (n_phi - 1);
        let dl = 2.0 * PI / m_count as f64;
        let cum = self.cumulative(N_G_BINS);
        let boxed: Vec<[f64; 3]> = (0..m_count)
            .map(|m| {
                let phi = -PI + m as f64 * dl;
                let (hi, lo) = (
                    cumulative_at(&cum, phi + window),
                    cumulative_at(&cum, phi - window),
                );
                [0, 1, 2].map(|ch| (hi[ch] - lo[ch]) / (2.0 * window))
            })
            .collect();
        // Logistic mass of the cell around each offset d·Δ, d ∈ [−M/2, M/2).
        let kernel: Vec<f64> = (0..m_count)
            .map(|i| {
                let d = i as f64 - (m_count / 2) as f64;
                self.logistic.cdf((d + 0.5) * dl) - self.logistic.cdf((d - 0.5) * dl)
            })
            .collect();
        (0..n_phi)
            .map(|j| {
                let mj = j + m_count / 2; // grid index of φ_j = jπ/(n_phi − 1)
                let mut acc = [0.0; 3];
                for (m, b) in boxed.iter().enumerate() {
                    let k = kernel[(mj + m_count + m_count / 2 - m) % m_count];
                    for ch in 0..3 {
                        acc[ch] += b[ch] * k;
                    }
                }
                acc
            })
            .collect()
    }
}

/// The shader's N̄_p tables, over |θo| ∈ [0, π/2] × |φ| ∈ [0, π] (N̄ is even in φ and depends on
/// θo through sin²θo).
#[derive(Clone, Debug)]
pub struct ChiangTables {
    /// N̄ of [R, TT, TRT, p ≥ 3].
    pub(crate) n_bar: [Table2; N_LOBES],
}

impl ChiangTables {
    pub fn build(c: &ChiangConstants, res: &TableResolution) -> Self {
        let (n_t, n_p) = (res.n_theta_d, res.n_phi);
        let rows: Vec<[Vec<Vec3>; N_LOBES]> = (0..n_t)
            .into_par_iter()
            .map(|i| {
                let theta_o = FRAC_PI_2 * i as f64 / (n_t - 1) as f64;
                std::array::from_fn(|lobe| {
                    let s = ChiangSamples::new(c, lobe, theta_o.sin(), N_GAMMA);
                    (0..n_p)
                        .map(|j| {
                            let phi = PI * j as f64 / (n_p - 1) as f64;
                            Vec3::from(s.n_bar(phi).map(|x| x as f32))
                        })
                        .collect()
                })
            })
            .collect();
        let n_bar = std::array::from_fn(|lobe| {
            Table2::from_values(
                n_t,
                n_p,
                rows.iter().flat_map(|r| r[lobe].iter().copied()).collect(),
            )
        });
        Self { n_bar }
    }

    /// Tabulated N̄_p at |θo|, |φ| (radians), RGB, 1/rad.
    pub fn lookup(&self, lobe: usize, abs_theta_o: f32, abs_phi: f32) -> Vec3 {
        self.n_bar[lobe].lookup(abs_theta_o, abs_phi)
    }
}
