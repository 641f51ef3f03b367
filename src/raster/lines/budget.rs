//! What the line raster's buffers hold, for the run's memory budget (`crate::budget`),
//! computed before they exist from the sizes and constants the raster uses.

use super::bins;
use super::fibers::Fibers;
use super::fragment::Frag;
use super::polyline::MAX_WIDTH_PX;
use super::scratch::LineScratch;
use super::seen;
use super::segment::{Seg, SegColors};

/// Rows of a band, as `bins.rs` bins them.
const BAND_ROWS: u64 = bins::BAND_ROWS as u64;
/// Fragments a band keeps per pixel at most, as `seen.rs` keeps them.
const KEEP_PER_PIXEL: u64 = seen::KEEP_PER_PIXEL as u64;
/// Segments per set-up chunk, as `bins.rs` bins them.
const SETUP_CHUNK: u64 = bins::SETUP_CHUNK as u64;
/// Bytes of one fragment (pixel, 1/depth bits, α, sub-sample mask, segment and place on it).
const FRAG_BYTES: u64 = size_of::<Frag>() as u64;
/// The densest band's fragments over the mean band's (see [`LineScratch::estimated_bytes`]).
const DENSEST_BAND: f64 = 5.0;
/// Bytes a segment adds to the raster's peak when lines are drawn at least [`MAX_WIDTH_PX`]
/// wide instead of the 0.5 px default (`tests/lib/hostile_budget.rs`, one thread, 200 × 200:
/// smooth's 100,500 segments 120 → 436 MB, 3.1 KB a segment; dense's 160,800 241 → 554 MB,
/// 1.9 KB; `wisp render --still` at 800 × 800 on 2 threads, 142 → 493 MB resident,
/// 3.5 KB), taken in proportion to the width between the two (measured at 16 px: 64 MB of
/// the 100 MB this gives; at 4 px, 15 MB of 22 MB).
const WIDEST_LINE_BYTES_PER_SEGMENT: f64 = 4096.0;

impl LineScratch {
    /// Bytes the line raster keeps ([`draw_polylines`](super::draw::draw_polylines), or
    /// [`seen_points`](super::seen::seen_points) then
    /// [`draw_seen_polylines`](super::seen::draw_seen_polylines)) for `segments` segments on an
    /// image `width` × `height`, when a segment covers `rows_per_segment` rows on average:
    /// each segment is binned once per band it touches (`Seg` in its chunk's list, then
    /// gathered into a band's list) with two `u64` sort keys and, if it keeps fragments there,
    /// its index in the band's `u32` list of their segments, plus one list header per chunk
    /// and band, and has its two colours; the fragments the seen pass keeps until they are
    /// composited (`Frag` is 24 bytes; all it emits, and at most [`KEEP_PER_PIXEL`] a pixel
    /// plus one segment's, a band's row span, per band); and per worker thread, the fragments
    /// of the densest band twice (emitted, then grouped by pixel) and its segments' colours
    /// (the band's colour table). A segment covers about 3 pixels per row it crosses at the
    /// 0.5 px minimum width; the densest band is taken as 5 times the mean
    /// band, at most the whole frame (the hair's screen rows hold it all in a fraction of the
    /// bands; measured over the bands of a frame, the densest holds 3.5 times the mean for
    /// smooth, 2.9 for curly and 3.7 for dense, at 1280×720 and 800×800 alike).
    /// Lines that stand for `bundles` of fibres add a table of how each segment draws them.
    /// Lines drawn at least `min_drawn_px` wide (the width model's minimum, at most
    /// [`MAX_WIDTH_PX`]) cover that many pixels of each row: past the 0.5 px default they add
    /// up to [`WIDEST_LINE_BYTES_PER_SEGMENT`], in proportion to the width (measured: the
    /// fragment model above, made for thin lines, is not).
    pub fn estimated_bytes(
        segments: u64,
        width: u32,
        height: u32,
        rows_per_segment: f64,
        min_drawn_px: f64,
        bundles: bool,
    ) -> u64 {
        let bands = (height as u64).div_ceil(BAND_ROWS).max(1);
        let touched = (1.0 + rows_per_segment.max(0.0) / BAND_ROWS as f64).min(bands as f64);
        let binned = (segments as f64 * touched).ceil() as u64;
        let per_binned =
            2 * size_of::<Seg>() as u64 + 2 * size_of::<u64>() as u64 + size_of::<u32>() as u64;
        let colors = segments.saturating_mul(size_of::<SegColors>() as u64);
        let headers = segments.div_ceil(SETUP_CHUNK) * bands * size_of::<Vec<Seg>>() as u64;
        let fragments = segments as f64 * 3.0 * (rows_per_segment.max(0.0) + 1.0);
        let densest_band = (fragments * DENSEST_BAND / bands as f64)
            .min(fragments)
            .ceil() as u64;
        let threads = rayon::current_num_threads().max(1) as u64;
        let densest_segments = (binned as f64 * DENSEST_BAND / bands as f64)
            .min(binned as f64)
            .ceil() as u64;
        let per_thread = densest_band
            .saturating_mul(2 * FRAG_BYTES)
            .saturating_add(densest_segments.saturating_mul(size_of::<SegColors>() as u64));
        let band_pixels = BAND_ROWS.saturating_mul(width as u64);
        let kept_at_most = bands.saturating_mul(band_pixels.saturating_mul(KEEP_PER_PIXEL + 1));
        let kept = (fragments.ceil() as u64)
            .min(kept_at_most)
            .saturating_mul(FRAG_BYTES);
        let fibers = if bundles {
            segments.saturating_mul(size_of::<Fibers>() as u64)
        } else {
            0
        };
        let widening = ((min_drawn_px - 0.5) / (MAX_WIDTH_PX as f64 - 0.5)).clamp(0.0, 1.0);
        let wide_lines = (segments as f64 * WIDEST_LINE_BYTES_PER_SEGMENT * widening) as u64;
        binned
            .saturating_mul(per_binned)
            .saturating_add(wide_lines)
            .saturating_add(fibers)
            .saturating_add(colors)
            .saturating_add(kept)
            .saturating_add(headers)
            .saturating_add(per_thread.saturating_mul(threads))
    }
}
