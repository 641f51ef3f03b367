//! The line raster in two passes around shading: which points of the hair the raster could
//! show is found before they are shaded, so the engine shades only those ([`seen_points`]),
//! and the fragments that pass emits are kept and composited once the points have their
//! colours ([`draw_seen_polylines`]), with `draw_polylines`'s picture to the bit.
//!
//! A segment is seen when, drawn as `draw_polylines` draws it, it keeps at least one
//! fragment: it is on screen, in front of the solids somewhere (`cull.rs`), and not behind
//! nearer hair that already hides every pixel it covers (`hiding.rs`). The first pass runs the
//! raster's own set-up, binning and emission over every band with the colours left out:
//! whether a fragment is kept depends on the geometry, the widths and the opacity, never on
//! colour, and a fragment holds its segment and its place along it instead of a colour
//! (`fragment.rs`). So the pass keeps exactly the fragments a whole draw keeps, in the same
//! order, each band's in its own buffer. The second pass sets up the seen segments again with
//! the shaded colours (the same clipping, so the same colours at their clipped ends), then
//! groups each band's fragments by pixel and composites them as the one-pass draw does.
//!
//! Unseen points draw nothing whatever their colour, and need no shading: at 1280 × 720, of
//! the segment-band pairs left after the solids' cull, 19% keep a fragment on smooth, 10% on
//! curly and 45% on dense one-fibre hair; the dance's frame at t = 2 s shades 20,114 of its
//! 103,850 points (75,609 with the solids' cull alone).
//!
//! Why keep the fragments rather than emit the seen segments again after shading: a second
//! walk cost smooth 12.8 ms of emission a frame (CPU, both threads) and dense a second
//! emission of 45% of its segments; keeping them costs 24 bytes a fragment until they are
//! composited (dense at 1280 × 720: 12.4 M, 0.3 GB of peak), bounded by [`KEEP_PER_PIXEL`].

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use glam::Vec3;
use rayon::prelude::*;

use super::band::{BandScratch, BandSource, build_far_bands};
use super::bins::{BAND_ROWS, MAX_SEGMENTS, SETUP_CHUNK, bin_segments};
use super::composite::Band;
use super::draw::draw_polylines;
use super::params::Params;
use super::polyline::{LineStyle, Polylines};
use super::scratch::{
    KeptBand, KeptFor, LineScratch, equalise_capacities, lock_thread_scratch, prepare_threads,
};
use super::segment::{SegColors, setup_segment};
use crate::raster::camera::Camera;
use crate::raster::framebuffer::Framebuffer;

/// Most fragments a band keeps from the seen pass to the composite, per pixel of the band on
/// average: what bounds their memory (24 bytes each, so 1.5 KB a pixel: 1.4 GB at
/// 1280 × 720). A band that would keep more is emitted again by the composite instead.
/// Measured (the most any preset keeps): dense one-fibre hair keeps 12.4 M fragments at
/// 1280 × 720 (13 a pixel over the frame, 55 in its fullest band, every band kept whole); at
/// 640 × 480 five of its 30 bands would keep more (and are emitted again). Smooth and curly
/// keep under one a pixel in any band.
pub(super) const KEEP_PER_PIXEL: usize = 64;

/// Marks in `seen` (one flag per point of `lines`, resized to match) the points of every
/// segment `draw_polylines` would keep a fragment of in `fb` as it is now (module doc); the
/// rest draw nothing whatever their colour, so a caller may leave them unshaded. The
/// fragments are kept in `scratch` for [`draw_seen_polylines`], which composites them once
/// the marked points have their colours. The same flags and fragments for any thread count
/// (each band's pass is the raster's, and the flags are a union). Call it after the solids
/// are drawn.
pub fn seen_points(
    fb: &Framebuffer,
    cam: &Camera,
    lines: &Polylines,
    style: &LineStyle,
    scratch: &mut LineScratch,
    seen: &mut Vec<bool>,
) {
    seen.clear();
    seen.resize(lines.points.len(), false);
    // Nothing kept until this pass has emitted every band.
    scratch.kept_for = None;
    let n = lines.points_per_line;
    let segs_per_line = n.saturating_sub(1);
    let width = fb.width as usize;
    if segs_per_line == 0 || width == 0 {
        return;
    }
    build_far_bands(fb, &mut scratch.far_bands);
    // Zero whatever the length: only its length needs setting.
    scratch.blank_colors.resize(lines.points.len(), Vec3::ZERO);
    let blank = Polylines {
        colors: &scratch.blank_colors,
        ..*lines
    };
    let Some(params) = Params::new(fb, cam, &blank, style, &mut scratch.profiles) else {
        return;
    };
    let Some(chunk_count) = bin_segments(
        &params,
        &blank,
        &mut scratch.chunks,
        &mut scratch.fibers,
        &mut scratch.colors,
    ) else {
        return;
    };
    prepare_threads(&mut scratch.threads, width);
    let flags = cleared_flags(
        &mut scratch.seen_segs,
        blank.segment_count().min(MAX_SEGMENTS),
    );
    let source = BandSource {
        params: &params,
        chunks: &scratch.chunks[..chunk_count],
        fibers: &scratch.fibers,
        far_bands: &scratch.far_bands,
    };
    keep_bands(fb, &source, &scratch.threads, &mut scratch.kept, flags);
    scratch.kept_for = Some(KeptFor::of(fb, lines, chunk_count));
    mark_points(seen, flags, n);
}

/// The first `seg_count` of `flags`, grown to hold them and all cleared.
fn cleared_flags(flags: &mut Vec<AtomicBool>, seg_count: usize) -> &[AtomicBool] {
    if flags.len() < seg_count {
        flags.resize_with(seg_count, || AtomicBool::new(false));
    }
    let flags = &flags[..seg_count];
    flags
        .par_iter()
        .for_each(|f| f.store(false, Ordering::Relaxed));
    flags
}

/// Emits every band of `fb` from `source`, in parallel, keeping each band's fragments in
/// its entry of `kept` (at most [`KEEP_PER_PIXEL`] a pixel, else none and `whole` false) and
/// setting in `flags` the segments that keep one.
fn keep_bands(
    fb: &Framebuffer,
    source: &BandSource,
    pool: &[Mutex<BandScratch>],
    kept: &mut Vec<KeptBand>,
    flags: &[AtomicBool],
) {
    let width = fb.width as usize;
    let bands = fb.depth.len().div_ceil(width * BAND_ROWS);
    if kept.len() < bands {
        kept.resize_with(bands, Default::default);
    }
    let at_most = KEEP_PER_PIXEL * width * BAND_ROWS;
    fb.depth
        .par_chunks(width * BAND_ROWS)
        .zip(kept.par_iter_mut())
        .enumerate()
        .with_max_len(1)
        .for_each(|(b, (depth, kept))| {
            let mut guard = lock_thread_scratch(pool);
            kept.whole = source.emit(
                &mut guard,
                b,
                depth,
                Some(&mut kept.out),
                Some((flags, at_most)),
            );
        });
}

/// Marks in `seen` both points of every segment flagged in `flags`, for lines of `n` ≥ 2
/// points (parallel over lines).
fn mark_points(seen: &mut [bool], flags: &[AtomicBool], n: usize) {
    seen.par_chunks_mut(n)
        .zip(flags.par_chunks(n - 1))
        .for_each(|(points, segs)| {
            for (i, f) in segs.iter().enumerate() {
                if f.load(Ordering::Relaxed)
                    && let Some(pair) = points.get_mut(i..i + 2)
                {
                    pair.fill(true);
                }
            }
        });
}

/// Draws into `fb` the fragments the last [`seen_points`] kept, with the colours `lines` now
/// has: `draw_polylines`'s image to the bit when `lines` has the geometry and widths
/// `seen_points` was given and `fb` is as it was then (the colours of the points it left
/// unmarked are never read). A marked point's non-finite colour draws black. Without kept
/// fragments for lines of this shape on a framebuffer of this size (no `seen_points` since
/// the last draw), it draws every segment with `draw_polylines`.
pub fn draw_seen_polylines(
    fb: &mut Framebuffer,
    cam: &Camera,
    lines: &Polylines,
    style: &LineStyle,
    scratch: &mut LineScratch,
) {
    let chunk_count = match scratch.kept_for.take() {
        Some(kept) if kept == KeptFor::of(fb, lines, kept.chunk_count) => kept.chunk_count,
        _ => return draw_polylines(fb, cam, lines, style, scratch),
    };
    let width = fb.width as usize;
    let Some(params) = Params::new(fb, cam, lines, style, &mut scratch.profiles) else {
        return;
    };
    let seg_count = lines.segment_count().min(MAX_SEGMENTS);
    let flags = &scratch.seen_segs[..seg_count.min(scratch.seen_segs.len())];
    shade_seen(&params, lines, flags, &mut scratch.colors);
    prepare_threads(&mut scratch.threads, width);
    let colors = &scratch.colors[..];
    let pool = &scratch.threads;
    // For bands that kept too many: the pass's lists, bundle table and solids' depth tiles.
    let source = BandSource {
        params: &params,
        chunks: &scratch.chunks[..chunk_count.min(scratch.chunks.len())],
        fibers: &scratch.fibers,
        far_bands: &scratch.far_bands,
    };
    fb.color
        .par_chunks_mut(width * BAND_ROWS)
        .zip(fb.depth.par_chunks(width * BAND_ROWS))
        .zip(fb.coverage.par_chunks_mut(width * BAND_ROWS))
        .zip(scratch.kept.par_iter_mut())
        .enumerate()
        .with_max_len(1)
        .for_each(|(b, (((color, depth), coverage), kept))| {
            let mut guard = lock_thread_scratch(pool);
            let t = &mut *guard;
            let band = Band {
                color,
                depth,
                coverage,
            };
            if kept.whole {
                t.composite(Some(&mut kept.out), colors, band);
            } else {
                // The same emission again, now storing every kept fragment.
                source.emit(t, b, band.depth, None, None);
                t.composite(None, colors, band);
            }
        });
    equalise_capacities(&mut scratch.threads);
}

/// The colours of the segments `flags` marks seen, into their entries of `colors`, from the
/// set-up with `lines`' shaded colours (the geometry, so the clipping, is the first pass's):
/// parallel over the set-up's fixed chunks.
fn shade_seen(params: &Params, lines: &Polylines, flags: &[AtomicBool], colors: &mut [SegColors]) {
    colors
        .par_chunks_mut(SETUP_CHUNK)
        .zip(flags.par_chunks(SETUP_CHUNK))
        .enumerate()
        .for_each(|(chunk, (colors, flags))| {
            for (i, (c, f)) in colors.iter_mut().zip(flags).enumerate() {
                if f.load(Ordering::Relaxed) {
                    *c = setup_segment(params, lines, chunk * SETUP_CHUNK + i)
                        .map_or(SegColors::default(), |(_, _, c)| c);
                }
            }
        });
}
