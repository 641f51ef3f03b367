//! Binning: each visible segment into the bands of rows it touches, and a band's segments
//! gathered back in the order emission reads them.
//!
//! What: [`bin_segments`] sets up every segment (`segment.rs`) in parallel over fixed chunks
//! of [`SETUP_CHUNK`] segments, each chunk appending its visible segments to its own list for
//! every band of [`BAND_ROWS`] rows they touch. [`gather_band`] collects one band's segments
//! from every chunk's list, leaves out those behind the solids at every pixel they could
//! touch (`cull.rs`), sorts them far to near by mid-point 1/depth, ties in input order
//! ([`band_key`]), and copies them in emission order (near to far).
//!
//! Why: chunks are fixed by the input, not by the thread count, and each has its own lists,
//! so binning needs no serial pass and no locks and gives the same lists for any thread
//! count; their order (chunk, then place in its list) is input order, so the sort's result
//! is fixed by the input alone. The sort is a radix sort (`crate::keysort`).

use rayon::prelude::*;

use super::cull::FarDepth;
use super::fibers::Fibers;
use super::params::Params;
use super::polyline::Polylines;
use super::segment::{Seg, SegColors, setup_segment};
use crate::keysort::sort_keys;

/// Image rows per band: the unit of binning and of parallel work (8-row bands drew 10%
/// slower).
pub(super) const BAND_ROWS: usize = 16;
/// Segments per parallel set-up task.
pub(super) const SETUP_CHUNK: usize = 4096;
/// Bits of a band key's position that hold the index within a chunk's list.
const CHUNK_BITS: usize = 12;

/// Most segments drawn per call: the sort key holds a position in 32 bits.
pub const MAX_SEGMENTS: usize = u32::MAX as usize;

/// Sort key of a segment in a band: far to near, then input order. The high 32 bits are the
/// bits of the mid-point 1/depth (positive floats order like their bits), the low 32 bits a
/// position that ascends in input order.
#[inline]
pub(super) fn band_key(s: &Seg, pos: usize) -> u64 {
    let iz_mid = (0.5 * (s.iz0 + s.iz1)).to_bits();
    (u64::from(iz_mid) << 32) | pos as u64
}

/// Sets up and bins `lines` (parallel over fixed chunks of segments, so the result does
/// not depend on the thread count): each chunk bins into its own lists in `chunks`, writes
/// its segments' colours into its part of the call's `colors` and, with bundles, their
/// [`Fibers`] into `fibers`. Returns how many chunks were filled, `None` when there are no
/// segments.
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

/// Band `b`'s segments gathered from every chunk's list into `segs`, leaving out those
/// behind the solids at every pixel they could touch (`far`, `cull.rs`: the same fragments
/// in the same order, without the walk), with their sort keys in `keys` (`tmp` the sort's
/// scratch), both in key order: far to near by mid-point depth, ties in input order; `segs`
/// in reverse, the order emission visits them, and each key's position its segment's place
/// in `segs`.
///
/// The segments are copied in emission order, not input order: a dense band's segments (2.7
/// MB for the dense preset's) do not fit in L2, and emission reading them in depth order
/// stalled on a miss per segment (14% of its time in the first read of each). Copied in that
/// order, the random reads are independent loads of one short loop, and emission reads its
/// segments forwards (read backwards, the descending stream missed as often).
pub(super) fn gather_band(
    b: usize,
    chunks: &[Vec<Vec<Seg>>],
    far: Option<&FarDepth>,
    segs: &mut Vec<Seg>,
    keys: &mut Vec<u64>,
    tmp: &mut Vec<u64>,
) {
    // Positions (chunk, index in its list) ascend in input order (chunks are in input order
    // and hold at most SETUP_CHUNK segments each), so the keys sort as those of the kept
    // segments' running count would.
    const _: () = assert!(SETUP_CHUNK <= 1 << CHUNK_BITS);
    keys.clear();
    for (c, bins) in chunks.iter().enumerate() {
        if let Some(bin) = bins.get(b) {
            keys.extend(
                bin.iter()
                    .enumerate()
                    .filter(|(_, s)| far.is_none_or(|f| !f.hides(s)))
                    .map(|(i, s)| band_key(s, (c << CHUNK_BITS) | i)),
            );
        }
    }
    sort_keys(keys, tmp);
    // Emission runs the keys from last to first, so the segments go in that order and are
    // read forwards.
    segs.clear();
    segs.extend(keys.iter().rev().map(|&k| {
        let pos = (k & 0xFFFF_FFFF) as usize;
        chunks[pos >> CHUNK_BITS][b][pos & ((1 << CHUNK_BITS) - 1)]
    }));
    let last = keys.len().wrapping_sub(1);
    for (i, k) in keys.iter_mut().enumerate() {
        *k = (*k & !0xFFFF_FFFF) | (last - i) as u64;
    }
}
