//! Hair hidden behind nearer hair, found while a band's fragments are emitted (`fragment.rs`),
//! so that fragments the compositing would never reach are not stored, sorted or composited.
//!
//! Why: the compositing walks each pixel's fragments front to back and stops where every
//! sub-sample's transmittance is under `HIDDEN`. Most fragments lie behind that point:
//! smooth at 1280 × 720 emits about 40 fragments a pixel and composites 3.5 of them (8.5%);
//! dense one-fibre hair emits about 480 and composites 175 (37%). Without this, every one of
//! them would be stored, grouped by pixel and depth-sorted all the same.
//!
//! How: a band's segments are emitted near to far (by mid-point depth). Per pixel this keeps
//! the product of (1 − α) over each sub-sample the fragments kept so far cover, and the
//! farthest 1/depth among them. Once every sub-sample's product is under half of `HIDDEN`, the
//! pixel's cull depth becomes that farthest 1/depth, and later fragments strictly farther are
//! dropped.
//!
//! Why the picture is the same, bit for bit: let S be the fragments kept when a pixel's cull
//! depth was set, and f* the farthest of them. The compositing sorts the pixel's kept
//! fragments by depth; every dropped fragment is strictly farther than f*, so up to f* (and
//! every fragment tied with it) it composites exactly what it would have with nothing
//! dropped. By then it has composited all of S and perhaps more, so each sub-sample's
//! transmittance is at most S's product, which is under `HIDDEN` / 2 here (the two products
//! multiply the same factors ≤ 1 in another order; rounding moves them by a few ulps, far less
//! than the factor 2). The compositing therefore stops at or before f*, never reaching a
//! dropped fragment. Ties are never dropped (the test is strict), so equal depths keep their
//! order. Its tests composite every fragment against the dropped set, bit for bit
//! (random lines, widths and opacities over a solid); BENCHMARKS.md lists the frames compared
//! with `cmp`.
//!
//! Rows of a segment, and whole segments, are skipped without their pixel loop where every
//! pixel they could cover is already hidden at a depth nearer than all of the segment (its
//! larger end 1/depth with `cull.rs`'s margin over the interpolation): per row against the
//! row's cull depths, per segment against the 16-column tiles of `cull.rs` once all their
//! pixels are hidden.

use glam::Vec4;

use super::cull::{MARGIN, TILE_COLS, reach_tiles};
use super::samples::{HIDDEN, NIBBLE_LANES};
use super::segment::Seg;

/// Transmittance under which a pixel's sub-samples count as hidden here: half the
/// compositing's threshold, so float rounding in the other order cannot make the compositing
/// go on past the cull depth.
const HIDDEN_HERE: f32 = HIDDEN * 0.5;

/// One band's per-pixel hiding state. Buffers keep their capacity between bands and frames.
#[derive(Debug, Default)]
pub(super) struct Hiding {
    /// Per pixel: 1/depth strictly behind which nothing more is kept (0: nothing yet, every
    /// fragment's 1/depth is positive).
    cull_iz: Vec<f32>,
    /// Per pixel: each sub-sample's product of (1 − α) over the kept fragments; valid where
    /// `far_iz` is not 0.
    trans: Vec<[Vec4; 4]>,
    /// Per pixel: the smallest 1/depth among its kept fragments (0: none kept yet).
    far_iz: Vec<f32>,
    /// The band's width, pixels.
    width: usize,
    /// Per tile of [`TILE_COLS`] columns (`cull.rs`'s tiles): how many of its pixels are
    /// still not hidden, and the smallest cull 1/depth among those that are.
    open: Vec<u32>,
    tile_cull_iz: Vec<f32>,
}

impl Hiding {
    /// Starts a band of `pixels` pixels in rows of `width` with nothing hidden.
    pub(super) fn reset(&mut self, pixels: usize, width: usize) {
        self.width = width.max(1);
        let rows = pixels / self.width;
        let tiles = width.div_ceil(TILE_COLS);
        self.open.clear();
        self.open
            .extend((0..tiles).map(|t| (rows * (width - t * TILE_COLS).min(TILE_COLS)) as u32));
        self.tile_cull_iz.clear();
        self.tile_cull_iz.resize(tiles, f32::INFINITY);
        self.cull_iz.clear();
        self.cull_iz.resize(pixels, 0.0);
        self.far_iz.clear();
        self.far_iz.resize(pixels, 0.0);
        // Entries are written before they are read (`far_iz` = 0 marks them unset), so only
        // the length matters.
        if self.trans.len() < pixels {
            self.trans.resize(pixels, [Vec4::ONE; 4]);
        }
    }

    /// Bytes of heap held.
    pub(super) fn capacity_bytes(&self) -> usize {
        (self.cull_iz.capacity()
            + self.far_iz.capacity()
            + self.tile_cull_iz.capacity()
            + self.open.capacity())
            * 4
            + self.trans.capacity() * size_of::<[Vec4; 4]>()
    }

    /// The cull depths of pixels `range` (a row's visited pixels): a fragment there is kept
    /// only if its 1/depth is at least this.
    #[inline]
    pub(super) fn cull_row(&self, range: std::ops::RangeInclusive<usize>) -> Option<&[f32]> {
        self.cull_iz.get(range)
    }

    /// Takes in a fragment just emitted and kept at `pixel` (1/depth `iz`, opacity `alpha`
    /// over the sub-samples of `mask`); a segment adds at most one per pixel.
    #[inline]
    pub(super) fn add(&mut self, pixel: usize, iz: f32, alpha: f32, mask: u16) {
        let (Some(far), Some(trans), Some(cull)) = (
            self.far_iz.get_mut(pixel),
            self.trans.get_mut(pixel),
            self.cull_iz.get_mut(pixel),
        ) else {
            return;
        };
        if *far == 0.0 {
            *trans = [Vec4::ONE; 4];
        }
        *far = if *far == 0.0 || iz < *far { iz } else { *far };
        let a = Vec4::splat(alpha);
        let mut most = Vec4::ZERO;
        for (g, t) in trans.iter_mut().enumerate() {
            let m = NIBBLE_LANES[usize::from((mask >> (4 * g)) & 15)];
            *t -= *t * (m * a);
            most = most.max(*t);
        }
        if most.max_element() < HIDDEN_HERE {
            if *cull == 0.0 {
                // First hidden: one pixel fewer open in its tile.
                let t = (pixel % self.width) / TILE_COLS;
                if let (Some(open), Some(tc)) = (self.open.get_mut(t), self.tile_cull_iz.get_mut(t))
                {
                    *open = open.saturating_sub(1);
                    *tc = tc.min(*far);
                }
            }
            *cull = *far;
        }
    }

    /// Whether every pixel segment `s` could cover in this band is hidden by nearer hair at a
    /// depth nearer than all of `s`: then it would emit no fragment, and is skipped without
    /// its walk. Its nearest 1/depth, with `cull.rs`'s margin over the pixel loop's
    /// interpolation, against the smallest cull depth of the tiles it could reach, each of
    /// which must be wholly hidden.
    #[inline]
    pub(super) fn hides(&self, s: &Seg) -> bool {
        let Some((t_lo, t_hi)) = reach_tiles(s, self.open.len()) else {
            return false;
        };
        let (Some(open), Some(cull)) = (
            self.open.get(t_lo..=t_hi),
            self.tile_cull_iz.get(t_lo..=t_hi),
        ) else {
            return false;
        };
        if open.iter().any(|&n| n != 0) {
            return false;
        }
        let cull = cull.iter().fold(f32::INFINITY, |a, &c| a.min(c));
        s.iz0.max(s.iz1) * (1.0 + MARGIN) < cull
    }
}

#[cfg(test)]
mod tests;
