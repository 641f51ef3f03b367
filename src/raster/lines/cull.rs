//! Occlusion culling of hair segments behind the opaque solids, per band of rows.
//!
//! What: before a band's segments are sorted and walked (`bins.rs`), [`FarDepth`] keeps the
//! farthest opaque depth in each tile of [`TILE_COLS`] columns of the band, and
//! [`FarDepth::hides`] drops a segment that is behind the solids at every pixel it could
//! touch. Where the character faces the camera, the hair behind the head and body is such a
//! segment: without the cull, about 40% of the fragments the pixel loop computes on the
//! default dance at 1280×720 (t = 2 s) are rejected by the depth test one by one.
//!
//! Why it changes no byte: a pixel takes a fragment only where `iz·z > 1` (`fragment.rs`: 1/depth
//! of the hair, interpolated between the segment's ends, times the opaque depth). A segment is
//! dropped only if `iz_near·z_far·(1 + 10⁻⁵) ≤ 1`, with `iz_near` the larger of its ends' 1/depth
//! and `z_far` the farthest opaque depth over every tile its reach can touch: the interpolated
//! 1/depth exceeds `iz_near` by at most a few units in the last place, far inside the margin, so
//! every pixel of a dropped segment would have failed the test. Dropping it also leaves the
//! other segments' order unchanged (the band's sort keys order by depth, then by input order,
//! which filtering keeps), so the fragments and their order are the same. Background pixels
//! hold infinite depth, so a tile with any background never drops anything; a NaN depth
//! compares as hidden in the pixel test and is skipped by `f32::max` here, which agrees.

use super::segment::Seg;

/// Columns per tile: a segment's reach is a few pixels, so small tiles keep the test tight,
/// and 80 tiles per 1280-pixel band are cheap to scan.
pub(super) const TILE_COLS: usize = 16;

/// Relative margin of the test over the pixel loop's rounding (module doc).
pub(super) const MARGIN: f32 = 1e-5;

/// The farthest opaque depth (metres) in each tile of one band.
#[derive(Debug, Default)]
pub(super) struct FarDepth {
    /// One value per tile, left to right (rebuilt each call in place, so a warmed-up frame
    /// allocates nothing).
    pub(super) tiles: Vec<f32>,
}

impl FarDepth {
    /// Tiles of `depth` (rows of `width` pixels): the maximum over each tile's pixels.
    pub(super) fn build(&mut self, depth: &[f32], width: usize) {
        self.tiles.clear();
        if width == 0 {
            return;
        }
        self.tiles.resize(width.div_ceil(TILE_COLS), 0.0);
        for row in depth.chunks_exact(width) {
            for (far, px) in self.tiles.iter_mut().zip(row.chunks(TILE_COLS)) {
                *far = px.iter().fold(*far, |a, &z| a.max(z));
            }
        }
    }

    /// Whether segment `s` is behind the solids at every pixel of this band it could cover.
    #[inline]
    pub(super) fn hides(&self, s: &Seg) -> bool {
        let Some((t_lo, t_hi)) = reach_tiles(s, self.tiles.len()) else {
            return false;
        };
        let Some(tiles) = self.tiles.get(t_lo..=t_hi) else {
            return false;
        };
        let z_far = tiles.iter().fold(0.0f32, |a, &z| a.max(z));
        s.iz0.max(s.iz1) * z_far * (1.0 + MARGIN) <= 1.0
    }
}

/// The tiles (of [`TILE_COLS`] columns, `tiles` of them across the band) holding every pixel
/// segment `s` could cover, first and last; `None` when there are none or its extent is NaN.
/// Its reach is bounded by `2·half_w + 2` pixels around its axis: its sub-samples' reach
/// (under 0.67 px) or a bundle's box filter (half a pixel), plus at most `tan 30°·half_w + ½`
/// of a mitred joint past an end (`segment.rs`).
#[inline]
pub(super) fn reach_tiles(s: &Seg, tiles: usize) -> Option<(usize, usize)> {
    let reach = 2.0 * s.half_w + 2.0;
    let x1 = s.x0 + s.ux * s.len;
    let (lo, hi) = (s.x0.min(x1) - reach, s.x0.max(x1) + reach);
    if !(lo <= hi) || tiles == 0 {
        return None;
    }
    // Pixel centres i + ½ in [lo, hi]; the float clamps absorb ±inf before the casts.
    let last = (tiles - 1) as f32;
    let t_lo = (lo / TILE_COLS as f32).floor().clamp(0.0, last) as usize;
    let t_hi = (hi / TILE_COLS as f32).floor().clamp(0.0, last) as usize;
    Some((t_lo, t_hi))
}

#[cfg(test)]
mod tests;
