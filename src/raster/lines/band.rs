//! One band of rows drawn by one thread: its segments gathered (`bins.rs`), emitted as
//! fragments (`fragment.rs`), grouped by pixel and composited (`pixel_runs.rs`,
//! `composite.rs`), in working buffers the thread reuses for every band it draws.
//!
//! Bands are whole rows, so each owns a disjoint `&mut` slice of the framebuffer (no
//! `unsafe`), and each pixel belongs to one band drawn by one thread in an order fixed by the
//! input: the picture is the same for any thread count.

use std::sync::atomic::AtomicBool;

use rayon::prelude::*;

use super::bins::{BAND_ROWS, gather_band};
use super::composite::{Band, composite};
use super::cull::FarDepth;
use super::fibers::Fibers;
use super::fragment::{BandSegs, Emitted, Rows, emit_fragments};
use super::hiding::Hiding;
use super::params::Params;
use super::pixel_runs::{Layer, band_colors, sort_by_pixel};
use super::segment::{Seg, SegColors};
use crate::raster::framebuffer::Framebuffer;

/// One thread's working buffers for the band it draws. Capacities persist; a thread reuses
/// them for every band it draws.
#[derive(Debug, Default)]
pub(super) struct BandScratch {
    /// The band's segments gathered contiguously in emission order, and their sort keys (see
    /// `bins::band_key`, [`gather_band`]) with the radix sort's second buffer.
    pub(super) segs: Vec<Seg>,
    pub(super) keys: Vec<u64>,
    pub(super) tmp: Vec<u64>,
    /// Its fragments in emission order and their segments, then grouped by pixel with their
    /// colours (`sorted`, with each pixel's first index in `starts`); the colours of the
    /// segments of the band being composited ([`band_colors`]).
    pub(super) out: Emitted,
    pub(super) colors: Vec<SegColors>,
    pub(super) sorted: Vec<Layer>,
    pub(super) starts: Vec<u32>,
    /// One out-of-order pixel's sort keys, when its insertion sort gives up.
    pub(super) run_keys: Vec<u64>,
    /// Which pixels nearer hair already hides, while the band's fragments are emitted.
    pub(super) hiding: Hiding,
}

impl BandScratch {
    /// Groups a band's fragments by pixel and composites them into `band` with their
    /// segments' `colors` (the draw call's table): `kept` (a band's kept fragments), or with
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

/// What a band's fragments are emitted from: the call's constants, the set-up chunks' lists,
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
        let far = self.far_bands.get(b);
        gather_band(b, self.chunks, far, &mut t.segs, &mut t.keys, &mut t.tmp);
        let rows = Rows {
            row0: b * BAND_ROWS,
            depth,
        };
        let out = match out {
            Some(out) => out,
            None => &mut t.out,
        };
        out.clear();
        let band = BandSegs {
            segs: &t.segs,
            keys: &t.keys,
            fibers: self.fibers,
        };
        emit_fragments(self.params, band, rows, &mut t.hiding, out, seen)
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
