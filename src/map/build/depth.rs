//! Where along the light a cell's crossings lie: each piece spreads its crossings evenly over
//! the depth range it spans inside its cell ([`spread_depth`], into a histogram of
//! [`DEPTH_BINS`] sub-slices), and the cell keeps the cumulative shares at the inner
//! sub-slice boundaries ([`depth_cdf`], in 1/255), which `Cell::share_before` interpolates
//! linearly. A piece over [λ₀, λ₁] (cell units, ×8 for sub-slices) adds to sub-slice b
//!
//!   n · |[λ₀, λ₁] ∩ [b, b + 1]| / (λ₁ − λ₀),
//!
//! or all of n to the sub-slice holding λ₀ when the range is narrower than 1e-6.

use crate::map::DEPTH_BINS;
use glam::Vec4;

/// Adds `n` crossings spread evenly over the depth range `depth` (1/65535 of a cell) to the
/// sub-slice histogram `hist`.
#[inline]
pub(super) fn spread_depth(hist: &mut [f32; DEPTH_BINS], depth: [u16; 2], n: f32) {
    let k = DEPTH_BINS as f32 / 65535.0;
    let (lo, hi) = (depth[0] as f32 * k, depth[1] as f32 * k);
    let width = hi - lo;
    if width < 1e-6 {
        hist[(lo as usize).min(DEPTH_BINS - 1)] += n;
        return;
    }
    // The first and last bins reached, as floats: lo and hi lie in [0, 8] (from u16 depths),
    // where floor is the truncation `as usize` did, without its saturating conversions.
    let last_bin = (DEPTH_BINS - 1) as f32;
    let (b0, b1) = (lo.floor().min(last_bin), hi.floor().min(last_bin));
    // The bins b0..=b1, four to a vector: each lane rounds its min, max, product and quotient
    // as the scalar `n * overlap / width` does (IEEE), and a lane outside b0..=b1 adds exactly
    // nothing, so this is the per-bin loop to the bit (also for a non-finite n) without its
    // scalar divisions, which cost about a third of the merge.
    const _: () = assert!(DEPTH_BINS == 8);
    let (lo4, hi4, n4, width4) = (
        Vec4::splat(lo),
        Vec4::splat(hi),
        Vec4::splat(n),
        Vec4::splat(width),
    );
    for (half, start) in [(0, 0.0f32), (4, 4.0)] {
        let b = Vec4::new(start, start + 1.0, start + 2.0, start + 3.0);
        let overlap = (hi4.min(b + 1.0) - lo4.max(b)).max(Vec4::ZERO);
        let reached = b.cmpge(Vec4::splat(b0)) & b.cmple(Vec4::splat(b1));
        let add = Vec4::select(reached, n4 * overlap / width4, Vec4::ZERO);
        let h = Vec4::from_slice(&hist[half..half + 4]);
        Vec4::select(reached, h + add, h).write_to_slice(&mut hist[half..half + 4]);
    }
}

/// The cumulative shares of a sub-slice histogram at its inner boundaries, in 1/255. An empty
/// histogram (a cell whose pieces carry no crossings, e.g. fibres along the light) reads as
/// spread evenly.
pub(super) fn depth_cdf(hist: &[f32; DEPTH_BINS]) -> [u8; DEPTH_BINS - 1] {
    let total: f32 = hist.iter().sum();
    let mut out = [0u8; DEPTH_BINS - 1];
    let mut acc = 0.0f32;
    for (k, o) in out.iter_mut().enumerate() {
        acc += hist[k];
        let share = if total > 0.0 {
            acc / total
        } else {
            (k + 1) as f32 / DEPTH_BINS as f32
        };
        *o = (share.clamp(0.0, 1.0) * 255.0).round() as u8;
    }
    out
}

#[cfg(test)]
mod tests;
