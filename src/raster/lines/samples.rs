//! A pixel's 16 sub-samples, shared by the segment set-up (how far they reach), the coverage
//! (which a line covers), the compositing and the hiding (when a pixel is hidden).
//!
//! One sub-sample per cell of a 4 × 4 grid and one per sixteenth in x and in y (n-rooks), so
//! thin lines of any direction cross them evenly; a fragment names those it covers as the
//! bits of a `u16`, tested and composited four lanes at a time.

use glam::Vec4;

/// Sub-samples per pixel: a coverage mask per fragment, so fibres side by side hide what is
/// behind them as much as their summed width, not as independent layers.
pub(super) const SAMPLE_COUNT: usize = 16;

/// Every sub-sample.
pub(super) const ALL_SAMPLES: u16 = u16::MAX;

/// How far from a pixel's centre its farthest sub-sample lies along any direction, pixels
/// (at most 15/32 · √2).
pub(super) const SAMPLE_REACH: f32 = 0.67;

/// How far from a pixel's centre its sub-samples lie across and along a line of unit screen
/// direction (ux, uy), pixels: |ux·oy − uy·ox| and |ux·ox + uy·oy| are at most
/// (|ux| + |uy|)·15/32 for offsets within ±15/32, plus a little slack for rounding.
pub(super) fn sample_reach(ux: f32, uy: f32) -> f32 {
    (ux.abs() + uy.abs()) * (15.0 / 32.0) + 1e-3
}

/// Sub-sample offsets from the pixel centre, pixels, four lanes per group (`x`, `y`): one per
/// cell of a 4 × 4 grid and one per sixteenth in x and in y (n-rooks), so thin lines of any
/// direction cross them evenly. Sample `4g + l` is lane l of group g, bit `4g + l` of a mask.
pub(super) const SAMPLE_X: [Vec4; 4] = sample_lanes(true);
pub(super) const SAMPLE_Y: [Vec4; 4] = sample_lanes(false);

const fn sample_lanes(x: bool) -> [Vec4; 4] {
    let mut out = [Vec4::ZERO; 4];
    let mut g = 0;
    while g < 4 {
        let mut v = [0.0f32; 4];
        let mut l = 0;
        while l < 4 {
            // Cell (g, l) of the grid; its sixteenths in x and y.
            let xi = 4 * g + l;
            let yi = 4 * l + (g + 2 * l) % 4;
            let i = if x { xi } else { yi };
            v[l] = (i as f32 + 0.5) / 16.0 - 0.5;
            l += 1;
        }
        out[g] = Vec4::from_array(v);
        g += 1;
    }
    out
}

/// Lane masks of a 4-bit nibble: lane l is 1 where bit l is set.
pub(super) const NIBBLE_LANES: [Vec4; 16] = {
    let mut out = [Vec4::ZERO; 16];
    let mut n = 0;
    while n < 16 {
        let mut v = [0.0f32; 4];
        let mut l = 0;
        while l < 4 {
            v[l] = ((n >> l) & 1) as f32;
            l += 1;
        }
        out[n] = Vec4::from_array(v);
        n += 1;
    }
    out
};

/// Transmittance below which a sub-sample counts as hidden (front-to-back compositing stops
/// when all are): 1/1024.
pub(super) const HIDDEN: f32 = 1.0 / 1024.0;

#[cfg(test)]
mod tests;
