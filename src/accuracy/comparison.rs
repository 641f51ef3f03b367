//! How far the map is from the exact reference: the figures ACCURACY.md reports and the tests
//! assert, computed one way everywhere (`wisp accuracy`, `wisp bench`, `tests/lib/map_accuracy.rs`).
//!
//! For a set of vertices, the map's T_f (mean of the three channels) is compared with the exact
//! reference's:
//! - **MAE**: mean |ΔT_f| over all vertices.
//! - **Bias binned by the true T_f** (0–0.2, 0.2–0.5, 0.5–0.8, 0.8–1): the mean signed error of
//!   the vertices whose *reference* value falls in the bin. Any estimator that cannot see the
//!   variation of the truth below its resolution reads too dark in the top bin and too bright in
//!   the bottom one even when it is right on average (the vertices that happen to be lit are
//!   selected by the bin: regression dilution).
//! - **Bias binned by the estimate**: the same, binned by the *map's* value. This is calibration:
//!   where the map says 0.6, does the hair receive 0.6 on average? It is not diluted by
//!   variation the map cannot resolve, so it measures the map's own bias.
//! - **Overall bias**: the mean signed error over all vertices (image brightness).

use crate::fiber::LightAtPoint;
use glam::Vec3;

/// Bin edges of T_f.
pub const BIN_EDGES: [f32; 5] = [0.0, 0.2, 0.5, 0.8, 1.0];

/// One bin's figures.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Bin {
    pub count: usize,
    /// Mean |ΔT_f| in the bin.
    pub mae: f64,
    /// Mean signed ΔT_f (map − reference).
    pub bias: f64,
    /// Mean signed Δ of the direct fraction.
    pub direct_bias: f64,
}

/// The map against the reference over a set of vertices.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Comparison {
    pub vertices: usize,
    pub mae: f64,
    pub overall_bias: f64,
    /// Binned by the reference's T_f.
    pub by_truth: [Bin; 4],
    /// Binned by the map's T_f.
    pub by_estimate: [Bin; 4],
}

fn mean3(v: Vec3) -> f32 {
    (v.x + v.y + v.z) / 3.0
}

fn bin_of(v: f32) -> usize {
    BIN_EDGES[1..4].iter().filter(|e| v >= **e).count()
}

impl Comparison {
    /// Compares `estimate[i]` with `truth[i]`.
    pub fn new(truth: &[LightAtPoint], estimate: &[LightAtPoint]) -> Self {
        let mut c = Comparison {
            vertices: truth.len().min(estimate.len()),
            ..Default::default()
        };
        let add = |bins: &mut [Bin; 4], key: f32, e: &LightAtPoint, t: &LightAtPoint| {
            let b = &mut bins[bin_of(key)];
            let d = e.tf - t.tf;
            b.count += 1;
            b.mae += mean3(d.abs()) as f64;
            b.bias += mean3(d) as f64;
            b.direct_bias += (e.direct_fraction - t.direct_fraction) as f64;
        };
        for (t, e) in truth.iter().zip(estimate) {
            let d = e.tf - t.tf;
            c.mae += mean3(d.abs()) as f64;
            c.overall_bias += mean3(d) as f64;
            add(&mut c.by_truth, mean3(t.tf), e, t);
            add(&mut c.by_estimate, mean3(e.tf), e, t);
        }
        let n = c.vertices.max(1) as f64;
        c.mae /= n;
        c.overall_bias /= n;
        for b in c.by_truth.iter_mut().chain(c.by_estimate.iter_mut()) {
            let k = b.count.max(1) as f64;
            b.mae /= k;
            b.bias /= k;
            b.direct_bias /= k;
        }
        c
    }

    /// The largest |bias| among bins with at least `min_count` vertices, binned by truth
    /// (`by_truth = true`) or by the estimate.
    pub fn worst_bin_bias(&self, by_truth: bool, min_count: usize) -> f64 {
        let bins = if by_truth {
            &self.by_truth
        } else {
            &self.by_estimate
        };
        bins.iter()
            .filter(|b| b.count >= min_count)
            .map(|b| b.bias.abs())
            .fold(0.0, f64::max)
    }
}

/// `count` distinct vertex indices out of `total`, spread evenly with a deterministic stride
/// (every vertex class, roots to tips, is represented; no random generator involved).
pub fn sample_vertices(total: usize, count: usize) -> Vec<usize> {
    if total == 0 || count == 0 {
        return Vec::new();
    }
    let count = count.min(total);
    // A stride coprime with typical points-per-strand counts: step by total/count, offset by a
    // golden-ratio fraction so consecutive picks do not land on the same point index.
    (0..count)
        .map(|i| {
            let f = (i as f64 + 0.5) / count as f64;
            let jitter = ((i as f64 * 0.618_033_988_75).fract() - 0.5) / count as f64;
            (((f + jitter).clamp(0.0, 0.999_999)) * total as f64) as usize
        })
        .collect()
}

#[cfg(test)]
mod tests;
