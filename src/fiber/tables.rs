//! Tabulated azimuthal lobes N_p(θd, φ) (Zinke 2008 §4.2: "a precomputed table for the
//! azimuthal part of single fibre scattering"), and the small lerp tables everything else uses.
//!
//! Why tables: an exact N_TT/N_TRT costs a safeguarded Newton solve per root (about 1 µs for
//! the three lobes and three channels); a bilinear lookup costs tens of nanoseconds, and the
//! shader runs 100K–200K times per frame. N depends on θd only through sin²θd and is even in φ
//! (circular model at index η or η*), so the grid covers |θd| ∈ [0, π/2], |φ| ∈ [0, π]. The
//! TRT table has a third axis, cos 2φh ∈ [−1, 1], because eccentricity enters through η*(φh)
//! (Marschner 2003 §5.2.3), which is linear in cos 2φh; with eccentricity 1 that axis has one
//! sample. Resolutions were chosen by measured error against the exact evaluation (see
//! `tests/lib/fiber_tables.rs` and [`TableResolution::DEFAULT`]).

use super::marschner::{Azimuth, COS_THETA_D_MIN, azimuth_for, eta_star};
use super::params::{Lobe, LobeConstants};
use glam::Vec3;
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// Grid sizes of the fibre's tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TableResolution {
    /// Samples of |θd| over [0, π/2] in the N and N^G tables.
    pub n_theta_d: usize,
    /// Samples of |φ| over [0, π] in the N and N^G tables.
    pub n_phi: usize,
    /// Samples of cos 2φh over [−1, 1] in the TRT table (when eccentricity ≠ 1).
    pub n_ecc: usize,
    /// Samples of θ (light inclination) over [−π/2, π/2] in the dual-scattering tables.
    pub n_theta: usize,
}

impl TableResolution {
    /// Chosen by measured error against direct evaluation (default fibre, tests/lib/fiber_tables.rs;
    /// max abs error over 3000–6000 random points, N in 1/rad):
    ///
    /// | θd × φ × ecc × θ       | N_R    | N_TT   | N_TRT  | ā_f    | ā_b    | Fiber::new |
    /// |------------------------|--------|--------|--------|--------|--------|------------|
    /// | 46 × 91 × 3 × 91       | 9.5e-4 | 2.2e-4 | —      | 7.8e-4 | 1.2e-3 | ≈ 25 ms    |
    /// | 91 × 91 × 5 × 181      | 2.5e-4 | 1.1e-4 | 5.0e-4 | 1.9e-4 | 3.0e-4 | ≈ 35 ms    |
    /// | **91 × 91 × 9 × 181**  | 2.5e-4 | 1.1e-4 | 2.8e-4 | 1.9e-4 | 3.0e-4 | ≈ 40 ms    |
    /// | 91 × 91 × 13 × 181     | 2.5e-4 | 1.1e-4 | 2.1e-4 | 1.9e-4 | 3.0e-4 | ≈ 45 ms    |
    /// | 181 × 361 × 5 × 361    | 6.7e-5 | 1.8e-5 | —      | 5.2e-5 | 8.2e-5 | ≈ 250 ms   |
    ///
    /// (peaks: N_R 0.21, N_TT 0.21, N_TRT 0.010 for brown hair; for σa = 0.1 and eccentricity
    /// 0.85 the TRT peak is 0.105 and its error 2.1e-3 at n_ecc = 9.) The cos 2φh axis sets
    /// N_TRT's error: η*(φh) moves the caustic merge (η' = 2) in θd, so layers are interpolated at
    /// equal η' rather than equal θd (see `lookup`); interpolating at equal θd gave 2.1e-3
    /// (n_ecc = 5) to 5.4e-4 (n_ecc = 13), worst inside the merge fade at θd ≈ 60°.
    pub const DEFAULT: Self = Self {
        n_theta_d: 91,
        n_phi: 91,
        n_ecc: 9,
        n_theta: 181,
    };
}

/// A 1D table of RGB values on a uniform grid over [x0, x1], linearly interpolated and clamped.
#[derive(Clone, Debug)]
pub struct Table1 {
    x0: f32,
    scale: f32,
    values: Vec<Vec3>,
}

impl Table1 {
    pub fn new(x0: f64, x1: f64, values: Vec<Vec3>) -> Self {
        let n = values.len();
        assert!(n >= 2, "a table needs two samples");
        Self {
            x0: x0 as f32,
            scale: ((n - 1) as f64 / (x1 - x0)) as f32,
            values,
        }
    }

    /// Linear interpolation at x (clamped to the range; NaN reads the first sample).
    #[inline]
    pub fn lookup(&self, x: f32) -> Vec3 {
        let n = self.values.len();
        let f = ((x - self.x0) * self.scale).clamp(0.0, (n - 1) as f32);
        let f = if f.is_nan() { 0.0 } else { f };
        let i = (f as usize).min(n - 2);
        let t = f - i as f32;
        self.values[i] * (1.0 - t) + self.values[i + 1] * t
    }

    pub fn values(&self) -> &[Vec3] {
        &self.values
    }
}

/// A 2D table of RGB values over |θd| ∈ [0, π/2] × |φ| ∈ [0, π], bilinear.
#[derive(Clone, Debug)]
pub struct Table2 {
    n_t: usize,
    n_p: usize,
    values: Vec<Vec3>,
}

impl Table2 {
    /// Fills the table with `f(θd, φ)` (radians), rows in parallel (each entry independent, so
    /// the result does not depend on the thread count).
    pub fn build(
        n_t: usize,
        n_p: usize,
        f: impl Fn(f64) -> Box<dyn Fn(f64) -> Vec3> + Sync,
    ) -> Self {
        let rows: Vec<Vec<Vec3>> = (0..n_t)
            .into_par_iter()
            .map(|i| {
                let theta_d = FRAC_PI_2 * i as f64 / (n_t - 1) as f64;
                let row = f(theta_d);
                (0..n_p)
                    .map(|j| row(PI * j as f64 / (n_p - 1) as f64))
                    .collect()
            })
            .collect();
        Self {
            n_t,
            n_p,
            values: rows.into_iter().flatten().collect(),
        }
    }

    /// A table from row-major values (`n_t` rows of |θd|, `n_p` columns of |φ|).
    pub fn from_values(n_t: usize, n_p: usize, values: Vec<Vec3>) -> Self {
        assert!(n_t >= 2 && n_p >= 2 && values.len() == n_t * n_p);
        Self { n_t, n_p, values }
    }

    /// Bilinear lookup at |θd| (radians, clamped to [0, π/2]) and |φ| (radians, clamped to
    /// [0, π]).
    #[inline]
    pub fn lookup(&self, abs_theta_d: f32, abs_phi: f32) -> Vec3 {
        let (i, j, u, v) = grid_cell(self.n_t, self.n_p, abs_theta_d, abs_phi);
        let at = |a: usize, b: usize| self.values[a * self.n_p + b];
        let top = at(i, j) * (1.0 - v) + at(i, j + 1) * v;
        let bot = at(i + 1, j) * (1.0 - v) + at(i + 1, j + 1) * v;
        top * (1.0 - u) + bot * u
    }
}

/// The cell (i, j) and the fractions (u, v) inside it of (|θd|, |φ|) on an `n_t` × `n_p` grid
/// spanning [0, π/2] × [0, π]; clamped to the grid, NaN reads the first row/column.
#[inline]
fn grid_cell(n_t: usize, n_p: usize, abs_theta_d: f32, abs_phi: f32) -> (usize, usize, f32, f32) {
    let ft = (abs_theta_d * ((n_t - 1) as f32 / std::f32::consts::FRAC_PI_2))
        .clamp(0.0, (n_t - 1) as f32);
    let fp = (abs_phi * ((n_p - 1) as f32 / std::f32::consts::PI)).clamp(0.0, (n_p - 1) as f32);
    let ft = if ft.is_nan() { 0.0 } else { ft };
    let fp = if fp.is_nan() { 0.0 } else { fp };
    let i = (ft as usize).min(n_t - 2);
    let j = (fp as usize).min(n_p - 2);
    (i, j, ft - i as f32, fp - j as f32)
}

/// Several tables on one (|θd|, |φ|) grid, interleaved per cell so that one bilinear lookup
/// fetches all of them from the same few cache lines. The shader reads N_R, N_TT and the three
/// N^G lobes this way: with seven separate tables of 100 KB each, `Table2::lookup` was 41% of
/// the dual shader's time in a profile (cache misses on random directions).
#[derive(Clone, Debug)]
pub struct Table2x<const K: usize> {
    n_t: usize,
    n_p: usize,
    values: Vec<[Vec3; K]>,
}

impl<const K: usize> Table2x<K> {
    /// Interleaves K tables built on the same grid.
    pub fn zip(tables: [&Table2; K]) -> Self {
        let (n_t, n_p) = (tables[0].n_t, tables[0].n_p);
        assert!(tables.iter().all(|t| t.n_t == n_t && t.n_p == n_p));
        let values = (0..n_t * n_p)
            .map(|i| tables.map(|t| t.values[i]))
            .collect();
        Self { n_t, n_p, values }
    }

    /// Bilinear lookup of all K values (clamped; NaN reads the first row/column).
    #[inline]
    pub fn lookup(&self, abs_theta_d: f32, abs_phi: f32) -> [Vec3; K] {
        let (i, j, u, v) = grid_cell(self.n_t, self.n_p, abs_theta_d, abs_phi);
        let w = [(1.0 - u) * (1.0 - v), (1.0 - u) * v, u * (1.0 - v), u * v];
        let cells = [
            &self.values[i * self.n_p + j],
            &self.values[i * self.n_p + j + 1],
            &self.values[(i + 1) * self.n_p + j],
            &self.values[(i + 1) * self.n_p + j + 1],
        ];
        std::array::from_fn(|k| {
            cells[0][k] * w[0] + cells[1][k] * w[1] + cells[2][k] * w[2] + cells[3][k] * w[3]
        })
    }
}

/// The renderer's N_p tables.
#[derive(Clone, Debug)]
pub struct NTables {
    pub(crate) r: Table2,
    pub(crate) tt: Table2,
    /// One TRT table per sample of cos 2φh over [−1, 1].
    trt: Vec<Table2>,
    /// η* of each TRT layer, and η*(cos 2φh) = mid + half · cos 2φh (Marschner 2003 §5.2.3).
    trt_eta_star: Vec<f32>,
    eta_star_mid: f32,
    eta_star_half: f32,
}

impl NTables {
    pub fn build(c: &LobeConstants, res: &TableResolution) -> Self {
        let simple = |lobe: Lobe| {
            Table2::build(res.n_theta_d, res.n_phi, move |theta_d| {
                let az = azimuth_for(c, lobe, theta_d.sin(), 1.0);
                Box::new(move |phi| Vec3::from(az.n_raw(lobe.p(), phi).map(|x| x as f32)))
            })
        };
        let n_ecc = if c.eccentricity == 1.0 {
            1
        } else {
            res.n_ecc.max(2)
        };
        let trt = (0..n_ecc)
            .map(|k| {
                let cos_2phi_h = if n_ecc == 1 {
                    1.0
                } else {
                    -1.0 + 2.0 * k as f64 / (n_ecc - 1) as f64
                };
                Table2::build(res.n_theta_d, res.n_phi, move |theta_d| {
                    let az: Azimuth = azimuth_for(c, Lobe::TRT, theta_d.sin(), cos_2phi_h);
                    let caustic = az.caustic(c);
                    let c = *c;
                    Box::new(move |phi| {
                        Vec3::from(az.n_trt_smoothed_with(&c, &caustic, phi).map(|x| x as f32))
                    })
                })
            })
            .collect();
        let trt_eta_star = (0..n_ecc)
            .map(|k| {
                let c2 = if n_ecc == 1 {
                    1.0
                } else {
                    -1.0 + 2.0 * k as f64 / (n_ecc - 1) as f64
                };
                eta_star(c.eta, c.eccentricity, c2) as f32
            })
            .collect();
        let (e1, e2) = (
            eta_star(c.eta, c.eccentricity, 1.0),
            eta_star(c.eta, c.eccentricity, -1.0),
        );
        Self {
            r: simple(Lobe::R),
            tt: simple(Lobe::TT),
            trt,
            trt_eta_star,
            eta_star_mid: (0.5 * (e1 + e2)) as f32,
            eta_star_half: (0.5 * (e1 - e2)) as f32,
        }
    }

    /// N_p at |θd|, |φ| (radians) and cos 2φh, bilinear (trilinear for TRT). RGB, 1/rad.
    #[inline]
    pub fn lookup(&self, lobe: Lobe, abs_theta_d: f32, abs_phi: f32, cos_2phi_h: f32) -> Vec3 {
        match lobe {
            Lobe::R => self.r.lookup(abs_theta_d, abs_phi),
            Lobe::TT => self.tt.lookup(abs_theta_d, abs_phi),
            Lobe::TRT => {
                let n = self.trt.len();
                if n == 1 {
                    return self.trt[0].lookup(abs_theta_d, abs_phi);
                }
                let c2 = if cos_2phi_h.is_nan() {
                    0.0
                } else {
                    cos_2phi_h.clamp(-1.0, 1.0)
                };
                let f = (c2 + 1.0) * 0.5 * (n - 1) as f32;
                let k = (f as usize).min(n - 2);
                let t = f - k as f32;
                // Feature-aligned interpolation across layers: each layer is read where *its*
                // η* reaches the actual η'(η*, θd), so the caustic merge (η' = 2) and its fade
                // line up between layers (the caustic structure depends on η' alone).
                let es = self.eta_star_mid + self.eta_star_half * c2;
                let (sin_d, cos_d) = abs_theta_d.sin_cos();
                let cos_d = cos_d.max(COS_THETA_D_MIN as f32);
                let ep2 = (es * es - sin_d * sin_d) / (cos_d * cos_d);
                let max_s2 = 1.0 - (COS_THETA_D_MIN * COS_THETA_D_MIN) as f32;
                let at = |j: usize| {
                    let e = self.trt_eta_star[j];
                    let s2 = ((ep2 - e * e) / (ep2 - 1.0)).clamp(0.0, max_s2);
                    let s2 = if s2.is_nan() { 0.0 } else { s2 };
                    self.trt[j].lookup(s2.sqrt().asin(), abs_phi)
                };
                at(k) * (1.0 - t) + at(k + 1) * t
            }
        }
    }
}
