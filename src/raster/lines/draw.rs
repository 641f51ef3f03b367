//! The one-pass draw: [`draw_polylines`] sets up and bins every segment, then draws each band
//! (emission, grouping by pixel, compositing) in parallel.

use rayon::prelude::*;

use super::band::{BandSource, build_far_bands};
use super::bins::{BAND_ROWS, bin_segments};
use super::composite::Band;
use super::params::Params;
use super::polyline::{LineStyle, Polylines};
use super::scratch::{LineScratch, equalise_capacities, lock_thread_scratch, prepare_threads};
use crate::raster::camera::Camera;
use crate::raster::framebuffer::Framebuffer;

/// Draws `lines` into `fb` (see the module doc of [`crate::raster::lines`] for the scheme).
/// Deterministic: the result is bit-identical for any rayon thread count. Never panics on
/// any input; segments with non-finite points or colours, or entirely nearer than the near
/// plane, draw nothing. At most [`MAX_SEGMENTS`](super::bins::MAX_SEGMENTS) (2³² − 1)
/// segments are drawn. The projection uses the framebuffer's size (the camera's
/// `width`/`height` are overridden), so one camera can serve buffers of several sizes.
pub fn draw_polylines(
    fb: &mut Framebuffer,
    cam: &Camera,
    lines: &Polylines,
    style: &LineStyle,
    scratch: &mut LineScratch,
) {
    scratch.kept_for = None;
    let width = fb.width as usize;
    let Some(params) = Params::new(fb, cam, lines, style, &mut scratch.profiles) else {
        return;
    };
    let Some(chunk_count) = bin_segments(
        &params,
        lines,
        &mut scratch.chunks,
        &mut scratch.fibers,
        &mut scratch.colors,
    ) else {
        return;
    };
    prepare_threads(&mut scratch.threads, width);
    build_far_bands(fb, &mut scratch.far_bands);
    let source = BandSource {
        params: &params,
        chunks: &scratch.chunks[..chunk_count],
        fibers: &scratch.fibers,
        far_bands: &scratch.far_bands,
    };
    let colors = &scratch.colors[..];
    let pool = &scratch.threads;
    fb.color
        .par_chunks_mut(width * BAND_ROWS)
        .zip(fb.depth.par_chunks(width * BAND_ROWS))
        .zip(fb.coverage.par_chunks_mut(width * BAND_ROWS))
        .enumerate()
        // One job per band: rayon splits a range only about log2(threads) deep unless a part
        // is stolen, so the dozen bands that hold the hair ran on one thread while the other
        // idled (smooth at 1280 × 720: 28 ms of bands on 2 threads for 39 ms of work).
        .with_max_len(1)
        .for_each(|(b, ((color, depth), coverage))| {
            let mut guard = lock_thread_scratch(pool);
            let t = &mut *guard;
            source.emit(t, b, depth, None, None);
            let band = Band {
                color,
                depth,
                coverage,
            };
            t.composite(None, colors, band);
        });
    // Which thread draws which band varies between frames: give every thread the largest
    // capacities any of them needed, so a warmed-up frame allocates nothing whichever bands
    // its threads get.
    equalise_capacities(&mut scratch.threads);
}
