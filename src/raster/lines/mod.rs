//! Anti-aliased, depth-tested, depth-sorted polylines (hair) into a [`Framebuffer`].
//!
//! What: [`draw_polylines`] draws every segment of equally long polylines with per-vertex
//! colours, a width (fixed in pixels, or a physical per-vertex width projected at its depth,
//! see [`LineWidth`]) and an opacity, hidden where the opaque depth buffer (the head) is
//! nearer, and composited per sub-sample over whatever is already in the colour buffer; the
//! coverage channel is one minus the light the hair lets through.
//!
//! Physical width: a line whose projected width is under the minimum is drawn at the minimum
//! width with its opacity lowered in proportion, which conserves its summed coverage
//! (length × projected width) while keeping sub-pixel lines free of aliasing; dense thin lines
//! then accumulate toward full coverage (`tests/raster_coverage.rs`), and lines side by side
//! hide what is behind them as their summed width does (`tests/raster_lines.rs`).
//!
//! How, in two parallel passes:
//! 1. **Set-up and binning** (parallel over fixed chunks of `SETUP_CHUNK` segments): each
//!    segment (`segment.rs`) goes to view space, is clipped to the near plane *in view space* (before the
//!    perspective division, which would flip or blow up points behind the eye), projected,
//!    then clipped in float to a guard rectangle a little larger than the image. Clipping in
//!    float before any conversion to integers is what makes NaN, ±inf and 1e30-metre points
//!    harmless: only finite values of at most a few image sizes ever become indices, and the
//!    per-pixel arithmetic keeps its precision. A visible segment (`Seg`: screen end points,
//!    1/depth, colours, end-cap flags, covered rows) is appended to its chunk's list for every
//!    band of `BAND_ROWS` image rows it touches. Chunks are fixed by the input, not by the
//!    thread count, and each has its own lists, so binning needs no serial pass and no locks.
//! 2. **Raster** (parallel over bands): a band keys its lists' segments from all chunks in
//!    chunk order (= input order), leaving out segments behind the opaque solids at every
//!    pixel they could touch (`cull.rs`, tiles of the band's farthest opaque depth; the same
//!    fragments in the same order), sorts the keys — mid-point 1/depth bits high, position
//!    low: far to near, ties in input order, a total order fixed by the input alone — with a
//!    radix sort, copies the segments into one contiguous array in that order, and walks each
//!    segment over its rows, near to far, visiting only
//!    pixel centres in the segment's expanded rectangle, emitting one fragment (pixel,
//!    1/depth, sub-sample mask, α, its segment and place along it: the colour is looked up
//!    when the fragments are grouped by pixel) per covered pixel whose centre is nearer than the
//!    opaque depth (`fragment.rs`, branch-free: each pixel writes a slot, kept only when
//!    covered and in front) and not behind nearer hair that already hides it (`hiding.rs`:
//!    the fragments the compositing would never reach, 89% of smooth's and 53% of dense
//!    hair's, and whole segments behind hidden tiles; the same bytes). A stable counting sort
//!    groups the fragments by pixel, in reverse emission order (far to near again); each
//!    pixel's run is put in depth order by an insertion sort (runs are nearly in order from
//!    the segment sort), or by a key sort where it is far from order, and composited front to
//!    back. Bands are whole
//!    rows so each owns a disjoint `&mut` slice of the framebuffer (no `unsafe`); the working
//!    buffers are per worker thread (an uncontended lock each).
//!
//! Measured before per-pixel order (100K segments of curly hair around a head at 1280x720,
//! `benches/raster.rs`, the 2 cores shared with other builds): about 27 ms per frame on one core (best of 30; criterion
//! median 29 ms under load), of which the depth sort is about 1.5 ms (input order: 25 ms).
//! Rejected on the way: the first version — a serial binning pass, one shared segment array
//! read in sorted order, `sort_unstable`, libm `ceil`/`floor` and saturating `as usize` per
//! row — at 36 ms; 8-row bands at +10%; `sort_unstable` alone was 15% of all instructions
//! (callgrind), the radix sort about 3%.
//!
//! Coverage is counted on 16 sub-samples per pixel (one per cell of a 4 × 4 grid and one per
//! sixteenth in x and in y, so thin lines of any direction cross them evenly): a plain line
//! covers the sub-samples within half its width of its axis and, along it, those with
//! `0 ≤ s < len` (ends and joints cut square), so consecutive segments of one hair tile it
//! without double-blending the joint pixel. A horizontal line of width w covers ⌊16w⌋ or
//! ⌈16w⌉ sixteenths of each column, exact on average over positions. A bundle's segment drawn
//! as its fibres (`bundle.rs`) keeps the analytic box filter of its fibres' profile and
//! covers all 16 sub-samples at that α. Depth is 1/depth interpolated linearly in screen
//! space (exact for perspective) at the pixel centre, compared without division as
//! `(1/z)·z_buffer > 1`; colour is interpolated linearly in screen space within a segment
//! (segments are a few pixels long), perspective-correctly at clip points.
//!
//! Hair over hair: hair does not write depth. Each pixel composites the fragments that cover
//! it front to back by 1/depth at the pixel centre, each sub-sample with its own
//! transmittance (a fragment adds `colour · α · Σ T_k / 16` over the sub-samples k it covers,
//! and multiplies their T_k by 1 − α), ties in the segment order above, so nearer hair is on
//! top at every pixel regardless of input order, and the result depends only on the input,
//! never on the thread count (each pixel belongs to one band, processed by one thread in one
//! order). A pixel whose sub-samples all pass under 1/1024 stops there and counts as opaque.
//! Until 2026-12-05 each fragment was one α over the whole pixel ("over", α = box-filtered
//! coverage × opacity), which treats fibres as covering a pixel independently: fibres side by
//! side (a wisp's layer) then let through as much of the darker hair behind as crossing ones,
//! and against a path tracer's first-hit fibres the raster read 0.93–0.96 of its own vertex
//! values side- and front-lit (ACCURACY.md §2). Sub-samples take it to 0.98, for about 4 ms
//! more on smooth and 12 on curly at 1280×720 (dense: 6% less, the pixels stop early;
//! BENCHMARKS.md). Until 2026-12-04 whole segments were composited in mid-point depth order
//! (the classic approach, as Sintorn & Assarsson 2008 sort hair segments); that misorders
//! any two segments whose depths cross where they overlap, which dense hair does all the time
//! (one fibre weaves over and under its neighbours within a segment): against a path tracer's
//! first-hit fibres, the raster showed side-lit dense hair 3.6% darker than its own vertex
//! values on those fibres (0.964), per-pixel order 1.0% (0.990), for about 14 ms more on
//! smooth at 1280×720 on 2 threads (ACCURACY.md §2, BENCHMARKS.md). Rejected: a hair z-buffer
//! (depth write + "over" in input order) drops hair behind the anti-aliased fringe of nearer
//! hair, leaving dark halos, and makes the picture depend on strand order; weighted blended
//! OIT is order independent but does not make near hair opaque over far hair, so dense hair
//! turns into an average colour. Known approximation: the head's anti-aliased edge pixels
//! (centre outside the silhouette) hold no depth, so hair behind the head shows through that
//! one-pixel fringe.

use std::sync::Mutex;
use std::sync::atomic::AtomicBool;

use glam::Vec3;
use rayon::prelude::*;

mod budget;
mod bundle;
mod cull;
mod fragment;
mod hiding;
mod polyline;
mod samples;
mod seen;
mod segment;

pub use polyline::{Bundle, LineStyle, LineWidth, MAX_WIDTH_PX, Polylines};
pub use seen::{draw_seen_polylines, seen_points};

use crate::keysort::sort_keys;
use crate::raster::camera::Camera;
use crate::raster::framebuffer::Framebuffer;
use bundle::Profiles;
use cull::FarDepth;
use fragment::{
    Band, Emitted, Frag, Layer, Rows, band_colors, composite, emit_fragments, sort_by_pixel,
};
use hiding::Hiding;
use segment::{Fibers, Params, Seg, SegColors, setup_segment};

/// Image rows per band (the unit of parallel work and of binning).
pub(super) const BAND_ROWS: usize = 16;
/// Segments per parallel set-up task.
pub(super) const SETUP_CHUNK: usize = 4096;
/// Buffers reused between frames, so a warmed-up frame allocates nothing.
#[derive(Debug, Default)]
pub struct LineScratch {
    /// Per set-up chunk, per band: the chunk's visible segments touching the band, in input
    /// order. Inner capacities persist across frames.
    pub(super) chunks: Vec<Vec<Vec<Seg>>>,
    /// Per worker thread: the band being drawn (its segments, fragments and their sort).
    /// Capacities persist; a thread reuses its buffers for every band it draws.
    pub(super) threads: Vec<Mutex<BandScratch>>,
    /// The bundle profiles of the last call that drew bundles (`bundle.rs`).
    pub(super) profiles: Profiles,
    /// With bundles, each segment's [`Fibres`] (by segment index): grown to the largest call,
    /// never cleared; an entry is read only for a segment whose set-up wrote it this call.
    pub(super) fibers: Vec<Fibers>,
    /// Each segment's colours at its ends (by segment index), what its fragments are
    /// composited with: written by the set-up, or for the seen segments by
    /// [`super::draw_seen_polylines`]. Only grown; an entry is read only for a segment that
    /// kept a fragment this call.
    pub(super) colors: Vec<SegColors>,
    /// Every band's farthest opaque depth per tile (`cull.rs`), rebuilt by each call from
    /// the framebuffer's depth; and for [`seen_points`] a colour per point for the set-up
    /// (which reads colours only to reject non-finite ones; always zero).
    pub(super) far_bands: Vec<FarDepth>,
    pub(super) blank_colors: Vec<Vec3>,
    /// For [`super::seen_points`]: per segment of the call, whether it kept a fragment in some
    /// band (set from any thread; a union, so the same for any thread count). Only grown.
    pub(super) seen_segs: Vec<AtomicBool>,
    /// Per band, the fragments [`super::seen_points`] kept, in emission order, until
    /// [`super::draw_seen_polylines`] composites them; and what they were emitted for.
    pub(super) kept: Vec<KeptBand>,
    pub(super) kept_for: Option<KeptFor>,
}

/// Most fragments a band keeps from the seen pass to the composite, per pixel of the band on
/// average: what bounds their memory (24 bytes each, so 1.5 KB a pixel: 1.4 GB at
/// 1280 × 720). A band that would keep more is emitted again by the composite instead.
/// Measured (the most any preset keeps): dense one-fibre hair keeps 12.4 M fragments at
/// 1280 × 720 (13 a pixel over the frame, 55 in its fullest band, every band kept whole); at
/// 640 × 480 five of its 30 bands would keep more (and are emitted again). Smooth and curly
/// keep under one a pixel in any band.
pub(super) const KEEP_PER_PIXEL: usize = 64;

/// One band's kept fragments.
#[derive(Debug, Default)]
pub(super) struct KeptBand {
    pub(super) out: Emitted,
    /// Whether `out.frags` holds all of them (else it was over [`KEEP_PER_PIXEL`] and the band
    /// is emitted again).
    pub(super) whole: bool,
}

/// What [`LineScratch::kept`] was emitted for: the framebuffer's size, the lines' shape and the
/// set-up chunks binned (still in [`LineScratch::chunks`], for bands emitted again).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct KeptFor {
    pub(super) width: u32,
    pub(super) height: u32,
    pub(super) points: usize,
    pub(super) points_per_line: usize,
    pub(super) chunk_count: usize,
}

impl KeptFor {
    /// `lines` on `fb`, binned into `chunk_count` chunks.
    pub(super) fn of(fb: &Framebuffer, lines: &Polylines, chunk_count: usize) -> Self {
        KeptFor {
            width: fb.width,
            height: fb.height,
            points: lines.points.len(),
            points_per_line: lines.points_per_line,
            chunk_count,
        }
    }
}

#[derive(Debug, Default)]
pub(super) struct BandScratch {
    /// The band's segments gathered contiguously in emission order, and their sort keys (see
    /// `band_key`, [`gather_band`]) with the radix sort's second buffer.
    pub(super) segs: Vec<Seg>,
    pub(super) keys: Vec<u64>,
    pub(super) tmp: Vec<u64>,
    /// Its fragments in emission order and their segments, then grouped by pixel with their
    /// colours (`sorted`, with each pixel's first index in `starts`); the colours of the
    /// segments of the band being composited ([`band_colours`]).
    pub(super) out: Emitted,
    pub(super) colors: Vec<SegColors>,
    pub(super) sorted: Vec<Layer>,
    pub(super) starts: Vec<u32>,
    /// One out-of-order pixel's sort keys, when its insertion sort gives up.
    pub(super) run_keys: Vec<u64>,
    /// Which pixels nearer hair already hides, while the band's fragments are emitted.
    pub(super) hiding: Hiding,
}

impl LineScratch {
    /// Bytes of heap held (capacities), to check that warmed-up frames do not grow it.
    pub fn capacity_bytes(&self) -> usize {
        let segs: usize = self
            .chunks
            .iter()
            .map(|c| c.iter().map(Vec::capacity).sum::<usize>() + c.capacity())
            .sum();
        let per_thread: usize = self
            .threads
            .iter()
            .map(|t| {
                let t = t.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
                t.segs.capacity() * size_of::<Seg>()
                    + (t.keys.capacity() + t.tmp.capacity()) * 8
                    + t.out.frags.capacity() * size_of::<Frag>()
                    + t.sorted.capacity() * size_of::<Layer>()
                    + t.out.ids.capacity() * 4
                    + t.colors.capacity() * size_of::<SegColors>()
                    + t.starts.capacity() * 4
                    + t.run_keys.capacity() * 8
                    + t.hiding.capacity_bytes()
            })
            .sum();
        let far: usize = self.far_bands.iter().map(|f| f.tiles.capacity() * 4).sum();
        let kept: usize = self
            .kept
            .iter()
            .map(|k| {
                k.out.frags.capacity() * size_of::<Frag>()
                    + k.out.ids.capacity() * 4
                    + size_of::<KeptBand>()
            })
            .sum();
        segs * size_of::<Seg>()
            + self.colors.capacity() * size_of::<SegColors>()
            + kept
            + self.fibers.capacity() * size_of::<Fibers>()
            + far
            + self.far_bands.capacity() * size_of::<FarDepth>()
            + self.blank_colors.capacity() * size_of::<Vec3>()
            + self.seen_segs.capacity()
            + per_thread
            + self.chunks.capacity()
            + self.threads.capacity() * size_of::<Mutex<BandScratch>>()
    }
}

/// Sort key of a segment in a band: far to near, then input order. The high 32 bits are the
/// bits of the mid-point 1/depth (positive floats order like their bits), the low 32 bits a
/// position that ascends in input order.
#[inline]
pub(super) fn band_key(s: &Seg, pos: usize) -> u64 {
    let iz_mid = (0.5 * (s.iz0 + s.iz1)).to_bits();
    (u64::from(iz_mid) << 32) | pos as u64
}

/// Most segments drawn per call: the sort key holds a position in 32 bits.
pub const MAX_SEGMENTS: usize = u32::MAX as usize;

/// The per-call constants of drawing `lines` into `fb`, with the bundle profiles prepared in
/// `profiles`; `None` when nothing would be drawn (an empty or inconsistent framebuffer, no
/// width or opacity, a camera that projects nowhere).
pub(super) fn prepare<'a>(
    fb: &Framebuffer,
    cam: &Camera,
    lines: &Polylines,
    style: &LineStyle,
    profiles: &'a mut Profiles,
) -> Option<Params<'a>> {
    let (width, height) = (fb.width as usize, fb.height as usize);
    if width == 0 || height == 0 || !fb.is_consistent() {
        return None;
    }
    let width_ok = match style.width {
        LineWidth::Pixels(w) => w > 0.0,
        LineWidth::Projected { min_px } => min_px > 0.0,
    };
    if !width_ok || !(style.opacity > 0.0) {
        return None;
    }
    let view = cam.view_for(fb.width, fb.height)?;
    let bundles = matches!(style.width, LineWidth::Projected { .. })
        && lines.bundle.is_some_and(|b| profiles.prepare(&b));
    Some(Params {
        view,
        width_model: style.width,
        opacity: style.opacity.min(1.0),
        width,
        height,
        bundle: bundles.then_some(&*profiles),
    })
}

/// Draws `lines` into `fb` (see the module doc for the scheme). Deterministic: the result is
/// bit-identical for any rayon thread count. Never panics on any input; segments with
/// non-finite points or colours, or entirely nearer than the near plane, draw nothing.
/// At most [`MAX_SEGMENTS`] (2³² − 1) segments are drawn. The projection uses the
/// framebuffer's size (the camera's `width`/`height` are overridden), so one camera can serve
/// buffers of several sizes.
pub fn draw_polylines(
    fb: &mut Framebuffer,
    cam: &Camera,
    lines: &Polylines,
    style: &LineStyle,
    scratch: &mut LineScratch,
) {
    scratch.kept_for = None;
    let width = fb.width as usize;
    let Some(params) = prepare(fb, cam, lines, style, &mut scratch.profiles) else {
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

    // 2. Raster, parallel over bands: gather the band's segments contiguously in emission
    //    order (the walk then reads one array forwards), turn them into fragments,
    //    sort the fragments by pixel and depth, composite. Working memory is per thread.
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

impl BandScratch {
    /// Groups a band's fragments by pixel and composites them into `band` with their
    /// segments' `colours` (the draw call's table): `kept` (a band's kept fragments), or with
    /// `None` the ones this thread emitted.
    pub(super) fn composite(
        &mut self,
        kept: Option<&mut Emitted>,
        colors: &[SegColors],
        band: Band,
    ) {
        let out = match kept {
            Some(kept) => kept,
            None => &mut self.out,
        };
        band_colors(&out.ids, colors, &mut self.colors);
        sort_by_pixel(
            &out.frags,
            &self.colors,
            &mut self.sorted,
            &mut self.starts,
            band.color.len(),
        );
        composite(
            &mut self.sorted,
            &self.starts,
            &mut self.run_keys,
            &mut self.tmp,
            band,
        );
    }
}

/// 1. Set-up and binning, parallel over fixed chunks of segments (the chunking is fixed, so it
///    does not depend on the thread count): each chunk bins into its own lists in
///    `scratch.chunks`, writes its segments' colours into its part of the call's `colours`
///    and with bundles their `Fibres` into `fibres`. Returns how many chunks were filled,
///    `None` when there are no segments.
pub(super) fn bin_segments(
    params: &Params,
    lines: &Polylines,
    chunks: &mut Vec<Vec<Vec<Seg>>>,
    fibers: &mut Vec<Fibers>,
    colors: &mut Vec<SegColors>,
) -> Option<usize> {
    let seg_count = lines.segment_count().min(MAX_SEGMENTS);
    if seg_count == 0 {
        return None;
    }
    let band_count = params.height.div_ceil(BAND_ROWS);
    let chunk_count = seg_count.div_ceil(SETUP_CHUNK);
    if chunks.len() < chunk_count {
        chunks.resize_with(chunk_count, Vec::new);
    }
    let setup_chunk = |chunk: usize,
                       bins: &mut Vec<Vec<Seg>>,
                       fibers: &mut [Fibers],
                       colors: &mut [SegColors]| {
        if bins.len() < band_count {
            bins.resize_with(band_count, Vec::new);
        }
        let bins = &mut bins[..band_count];
        for bin in bins.iter_mut() {
            bin.clear();
        }
        let first = chunk * SETUP_CHUNK;
        for k in first..(first + SETUP_CHUNK).min(seg_count) {
            if let Some((seg, f, c)) = setup_segment(params, lines, k) {
                if let Some(slot) = fibers.get_mut(k - first) {
                    *slot = f;
                }
                if let Some(slot) = colors.get_mut(k - first) {
                    *slot = c;
                }
                let (b0, b1) = (
                    seg.row_lo as usize / BAND_ROWS,
                    seg.row_hi as usize / BAND_ROWS,
                );
                for bin in &mut bins[b0..=b1] {
                    bin.push(seg);
                }
            }
        }
    };
    // Only grown: a segment's entries are read only when its set-up wrote them this call.
    if colors.len() < seg_count {
        colors.resize(seg_count, SegColors::default());
    }
    let chunks = chunks[..chunk_count]
        .par_iter_mut()
        .zip(colors.par_chunks_mut(SETUP_CHUNK))
        .enumerate();
    if params.bundle.is_some() {
        if fibers.len() < seg_count {
            fibers.resize(seg_count, Fibers::default());
        }
        chunks
            .zip(fibers.par_chunks_mut(SETUP_CHUNK))
            .for_each(|((chunk, (bins, colors)), fibers)| setup_chunk(chunk, bins, fibers, colors));
    } else {
        chunks.for_each(|(chunk, (bins, colors))| setup_chunk(chunk, bins, &mut [], colors));
    }
    Some(chunk_count)
}

/// One buffer set per worker thread, each with its hiding state sized for bands of `width`.
pub(super) fn prepare_threads(pool: &mut Vec<Mutex<BandScratch>>, width: usize) {
    let threads = rayon::current_num_threads().max(1);
    if pool.len() < threads {
        pool.resize_with(threads, Default::default);
    }
    // Sized for a whole band now, so no band of a warmed-up frame grows them.
    for t in pool.iter_mut() {
        t.get_mut()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .hiding
            .reset(width * BAND_ROWS, width);
    }
}

/// This worker thread's buffers. Each worker thread has its own; the lock is never contended.
/// A poisoned lock only means another band panicked, and the buffers are cleared before use.
pub(super) fn lock_thread_scratch(
    pool: &[Mutex<BandScratch>],
) -> std::sync::MutexGuard<'_, BandScratch> {
    let slot = rayon::current_thread_index().unwrap_or(0) % pool.len().max(1);
    pool[slot]
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// A band's segments gathered from every chunk's list into `t.segs`, leaving out those behind
/// the solids at every pixel they could touch (`cull.rs`: the same fragments in the same order,
/// without the walk), with their sort keys in `t.keys`, both in key order (far to near by
/// mid-point depth, ties in input order; `t.segs` in reverse, the order emission visits them).
///
/// The segments are copied in emission order, not input order: a dense band's segments (2.7
/// MB for the dense preset's) do not fit in L2, and emission reading them in depth order
/// stalled on a miss per segment (14% of its time in the first read of each). Copied in that
/// order, the random reads are independent loads of one short loop, and emission reads its
/// segments forwards (read backwards, the descending stream still missed as often).
pub(super) fn gather_band(
    t: &mut BandScratch,
    b: usize,
    chunks: &[Vec<Vec<Seg>>],
    far: Option<&FarDepth>,
) {
    // Positions (chunk, index in its bin) ascend in input order (chunks are in input order and
    // hold at most SETUP_CHUNK segments each), so the keys sort as those of the kept segments'
    // running count would.
    const _: () = assert!(SETUP_CHUNK <= 1 << CHUNK_BITS);
    t.keys.clear();
    for (c, bins) in chunks.iter().enumerate() {
        if let Some(bin) = bins.get(b) {
            t.keys.extend(
                bin.iter()
                    .enumerate()
                    .filter(|(_, s)| far.is_none_or(|f| !f.hides(s)))
                    .map(|(i, s)| band_key(s, (c << CHUNK_BITS) | i)),
            );
        }
    }
    sort_keys(&mut t.keys, &mut t.tmp);
    // Emission runs the keys from last to first, so the segments go in that order and are
    // read forwards.
    t.segs.clear();
    t.segs.extend(t.keys.iter().rev().map(|&k| {
        let pos = (k & 0xFFFF_FFFF) as usize;
        chunks[pos >> CHUNK_BITS][b][pos & ((1 << CHUNK_BITS) - 1)]
    }));
    let last = t.keys.len().wrapping_sub(1);
    for (i, k) in t.keys.iter_mut().enumerate() {
        *k = (*k & !0xFFFF_FFFF) | (last - i) as u64;
    }
}

/// Bits of a band key's position that hold the index within a chunk's bin.
const CHUNK_BITS: usize = 12;

/// What a band's fragments are emitted from: the call's constants, the set-up chunks' bins,
/// the bundle table and the solids' depth tiles.
pub(super) struct BandSource<'a> {
    pub(super) params: &'a Params<'a>,
    pub(super) chunks: &'a [Vec<Vec<Seg>>],
    pub(super) fibers: &'a [Fibers],
    pub(super) far_bands: &'a [FarDepth],
}

impl BandSource<'_> {
    /// Band `b`'s fragments over its opaque `depth`: its segments gathered ([`gather_band`])
    /// and emitted into `out` (the thread's own buffer with `None`), `seen` as
    /// [`emit_fragments`] takes it. Returns whether `out` holds every kept fragment.
    pub(super) fn emit(
        &self,
        t: &mut BandScratch,
        b: usize,
        depth: &[f32],
        out: Option<&mut Emitted>,
        seen: Option<(&[AtomicBool], usize)>,
    ) -> bool {
        gather_band(t, b, self.chunks, self.far_bands.get(b));
        let rows = Rows {
            row0: b * BAND_ROWS,
            depth,
        };
        let out = match out {
            Some(out) => out,
            None => &mut t.out,
        };
        out.clear();
        emit_fragments(
            self.params,
            &t.segs,
            self.fibers,
            &t.keys,
            rows,
            &mut t.hiding,
            out,
            seen,
        )
    }
}

/// Every band's farthest opaque depth per tile, from `fb`'s depth (parallel over bands).
pub(super) fn build_far_bands(fb: &Framebuffer, far_bands: &mut Vec<FarDepth>) {
    let width = fb.width as usize;
    far_bands.resize_with((fb.height as usize).div_ceil(BAND_ROWS), FarDepth::default);
    if width == 0 {
        return;
    }
    far_bands
        .par_iter_mut()
        .zip(fb.depth.par_chunks(width * BAND_ROWS))
        .for_each(|(far, depth)| far.build(depth, width));
}

/// Grows `v`'s capacity to at least `cap`, exactly `cap` when it has to grow.
fn grow_to<T>(v: &mut Vec<T>, cap: usize) {
    if v.capacity() < cap {
        v.reserve_exact(cap - v.len());
    }
}

/// Grows every thread's buffers to the largest capacity among them (a no-op once warm).
pub(super) fn equalise_capacities(threads: &mut [Mutex<BandScratch>]) {
    let mut need = [0usize; 9];
    let caps = |t: &BandScratch| {
        [
            t.keys.capacity(),
            t.tmp.capacity(),
            t.segs.capacity(),
            t.out.frags.capacity(),
            t.sorted.capacity(),
            t.starts.capacity(),
            t.run_keys.capacity(),
            t.out.ids.capacity(),
            t.colors.capacity(),
        ]
    };
    for t in threads.iter_mut() {
        let t = t
            .get_mut()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        for (n, c) in need.iter_mut().zip(caps(t)) {
            *n = (*n).max(c);
        }
    }
    for t in threads.iter_mut() {
        let t = t
            .get_mut()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        // `reserve_exact`, not `reserve`: amortised growth would double past `need`, and two
        // threads would then outgrow each other every frame without bound.
        grow_to(&mut t.keys, need[0]);
        grow_to(&mut t.tmp, need[1]);
        grow_to(&mut t.segs, need[2]);
        grow_to(&mut t.out.frags, need[3]);
        grow_to(&mut t.sorted, need[4]);
        grow_to(&mut t.starts, need[5]);
        grow_to(&mut t.run_keys, need[6]);
        grow_to(&mut t.out.ids, need[7]);
        grow_to(&mut t.colors, need[8]);
    }
}

#[cfg(test)]
mod tests;
