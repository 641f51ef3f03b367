//! The line raster's buffers, kept across frames so a warmed-up frame allocates nothing
//! ([`LineScratch`]): the set-up's lists and tables, one [`BandScratch`] per worker thread,
//! and the fragments the seen pass keeps for the composite.
//!
//! Which thread draws which band varies between frames, so after each call every thread's
//! buffers are grown to the largest any of them needed ([`equalise_capacities`]), exactly,
//! so that two threads never outgrow each other frame after frame.

use std::sync::atomic::AtomicBool;
use std::sync::{Mutex, MutexGuard, PoisonError};

use glam::Vec3;

use super::band::BandScratch;
use super::bins::BAND_ROWS;
use super::bundle::Profiles;
use super::cull::FarDepth;
use super::fibers::Fibers;
use super::fragment::{Emitted, Frag};
use super::pixel_runs::Layer;
use super::polyline::Polylines;
use super::segment::{Seg, SegColors};
use crate::raster::framebuffer::Framebuffer;

/// Buffers reused between frames, so a warmed-up frame allocates nothing.
#[derive(Debug, Default)]
pub struct LineScratch {
    /// Per set-up chunk, per band: the chunk's visible segments touching the band, in input
    /// order. Inner capacities persist across frames.
    pub(super) chunks: Vec<Vec<Vec<Seg>>>,
    /// Per worker thread: the band being drawn (its segments, fragments and their sort).
    pub(super) threads: Vec<Mutex<BandScratch>>,
    /// The bundle profiles of the last call that drew bundles (`bundle.rs`).
    pub(super) profiles: Profiles,
    /// With bundles, each segment's [`Fibers`] (by segment index): grown to the largest call,
    /// never cleared; an entry is read only for a segment whose set-up wrote it this call.
    pub(super) fibers: Vec<Fibers>,
    /// Each segment's colours at its ends (by segment index), what its fragments are
    /// composited with: written by the set-up, or for the seen segments by
    /// `draw_seen_polylines`. Only grown; an entry is read only for a segment that kept a
    /// fragment this call.
    pub(super) colors: Vec<SegColors>,
    /// Every band's farthest opaque depth per tile (`cull.rs`), rebuilt by each call from
    /// the framebuffer's depth.
    pub(super) far_bands: Vec<FarDepth>,
    /// For `seen_points`: a colour per point for the set-up, which reads colours only to
    /// reject non-finite ones (always zero).
    pub(super) blank_colors: Vec<Vec3>,
    /// For `seen_points`: per segment of the call, whether it kept a fragment in some band
    /// (set from any thread; a union, so the same for any thread count). Only grown.
    pub(super) seen_segs: Vec<AtomicBool>,
    /// Per band, the fragments `seen_points` kept, in emission order, until
    /// `draw_seen_polylines` composites them; and what they were emitted for.
    pub(super) kept: Vec<KeptBand>,
    pub(super) kept_for: Option<KeptFor>,
}

/// One band's kept fragments.
#[derive(Debug, Default)]
pub(super) struct KeptBand {
    pub(super) out: Emitted,
    /// Whether `out.frags` holds all of them (else it was over `seen::KEEP_PER_PIXEL` a
    /// pixel and the band is emitted again).
    pub(super) whole: bool,
}

/// What [`LineScratch::kept`] was emitted for: the framebuffer's size, the lines' shape and
/// the set-up chunks binned (still in [`LineScratch::chunks`], for bands emitted again).
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
                let t = t.lock().unwrap_or_else(PoisonError::into_inner);
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

/// One buffer set per worker thread, each with its hiding state sized for bands of `width`.
pub(super) fn prepare_threads(pool: &mut Vec<Mutex<BandScratch>>, width: usize) {
    let threads = rayon::current_num_threads().max(1);
    if pool.len() < threads {
        pool.resize_with(threads, Default::default);
    }
    // Sized for a whole band now, so no band of a warmed-up frame grows them.
    for t in pool.iter_mut() {
        t.get_mut()
            .unwrap_or_else(PoisonError::into_inner)
            .hiding
            .reset(width * BAND_ROWS, width);
    }
}

/// This worker thread's buffers. Each worker thread has its own; the lock is never contended.
/// A poisoned lock only means another band panicked, and the buffers are cleared before use.
pub(super) fn lock_thread_scratch(pool: &[Mutex<BandScratch>]) -> MutexGuard<'_, BandScratch> {
    let slot = rayon::current_thread_index().unwrap_or(0) % pool.len().max(1);
    pool[slot].lock().unwrap_or_else(PoisonError::into_inner)
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
        let t = t.get_mut().unwrap_or_else(PoisonError::into_inner);
        for (n, c) in need.iter_mut().zip(caps(t)) {
            *n = (*n).max(c);
        }
    }
    for t in threads.iter_mut() {
        let t = t.get_mut().unwrap_or_else(PoisonError::into_inner);
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
