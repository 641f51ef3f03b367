//! A band's fragments grouped by pixel, each pixel's run in depth order, with their colours:
//! what compositing reads.
//!
//! What: [`band_colors`] takes the colours of the band's segments out of the draw call's
//! table; [`sort_by_pixel`] groups the fragments by pixel (a stable counting sort) into
//! [`Layer`]s, each with its colour at its place along its segment; [`sort_run`] puts one
//! pixel's run in depth order.
//!
//! How: emission runs near to far and the counting sort scatters in reverse, so each run
//! comes far to near by mid-point depth, in the segments' key order, and is usually nearly
//! in order (smooth at 1280×720: 38 fragments a pixel, 0.74 insertion shifts per fragment):
//! a stable insertion sort costs O(length + inversions). Where a run is far from order
//! (dense hair: hundreds of crossing fibres a pixel), the insertion stops after
//! [`SHIFT_BUDGET`] shifts per fragment and a radix sort of (1/depth, position) keys
//! (`crate::keysort::sort_keys`) finishes it, the run then permuted in place along the
//! cycles of the keys' order. A stable sort by one key has one result, so the order is the
//! same whichever way a run is sorted; the insertion keeps equal depths in their order, so
//! the keys' positions still tell emission order.

use glam::Vec3;

use super::fragment::Frag;
use super::segment::SegColors;
use crate::keysort::sort_keys;

/// A fragment grouped with its pixel's, what compositing reads: its colour looked up, its
/// pixel told by its place (24 bytes, as a [`Frag`]).
///
/// Why the colour is looked up as fragments are grouped: the grouping reads them in emission
/// order, one segment's after another, so its reads of the band's colour table run in order;
/// compositing reads them pixel by pixel, a random read of the table each (29% of dense
/// hair's compositing, with the band's table).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Layer {
    /// As the fragment's.
    pub(super) iz_bits: u32,
    pub(super) alpha: f32,
    pub(super) color: Vec3,
    pub(super) mask: u16,
}

/// The colours of `ids`' segments, taken from the draw call's table `colors` (its index
/// `Seg::k`) into `out`, the table [`sort_by_pixel`] reads with [`Frag::seg`] (black for
/// a segment the draw call's table does not hold).
pub(super) fn band_colors(ids: &[u32], colors: &[SegColors], out: &mut Vec<SegColors>) {
    out.clear();
    out.extend(
        ids.iter()
            .map(|&k| colors.get(k as usize).copied().unwrap_or_default()),
    );
}

/// A fragment's linear RGB: its segment's colours at its place along it (black for a segment
/// the table does not hold).
#[inline(always)]
fn color_of(f: &Frag, colors: &[SegColors]) -> Vec3 {
    let [c0, c1] = colors.get(f.seg as usize).copied().unwrap_or_default();
    c0 + (c1 - c0) * f.t
}

/// Stable counting sort of `frags` by pixel into `sorted`, each with its colour from
/// `colors` (the band's table, [`band_colors`]); on return `starts[p]..starts[p+1]` is
/// pixel `p`'s run, in reverse emission order: emission runs near to far, so the runs come
/// far to near by mid-point depth, in the segments' key order.
pub(super) fn sort_by_pixel(
    frags: &[Frag],
    colors: &[SegColors],
    sorted: &mut Vec<Layer>,
    starts: &mut Vec<u32>,
    pixels: usize,
) {
    starts.clear();
    starts.resize(pixels + 1, 0);
    for f in frags {
        if let Some(c) = starts.get_mut(f.pixel as usize + 1) {
            *c += 1;
        }
    }
    for p in 1..=pixels {
        starts[p] += starts[p - 1];
    }
    sorted.clear();
    sorted.resize(frags.len(), Layer::default());
    // `starts[p]` walks pixel p's run while scattering, so afterwards it holds the run's end,
    // which is pixel p + 1's start: shift the table back by one entry.
    for f in frags.iter().rev() {
        let p = f.pixel as usize;
        if let Some(slot) = starts.get_mut(p) {
            let at = *slot as usize;
            *slot += 1;
            if let Some(dst) = sorted.get_mut(at) {
                *dst = Layer {
                    iz_bits: f.iz_bits,
                    alpha: f.alpha,
                    color: color_of(f, colors),
                    mask: f.mask,
                };
            }
        }
    }
    starts.copy_within(0..pixels, 1);
    starts[0] = 0;
}

/// Insertion shifts per fragment a run may take before its sort switches to keys. Smooth's
/// runs need 0.74 on average, dense hair's many more. Measured (1280×720, 2 threads): smooth's
/// raster 31.3 ms at 2 (32.9 at 1, 31.9 at 4), dense's 822–854 ms at 2 (922 at 4, and
/// 1,231–1,252 with no budget, an insertion sort alone).
pub(super) const SHIFT_BUDGET: usize = 2;

/// Sorts one pixel's `run` by 1/depth ascending, ties in their order (module doc):
/// insertion within the budget, else keys (`key_tmp` is the keys' scratch), and the run
/// permuted in place: no copy of it, so no buffer as long as the longest run.
pub(super) fn sort_run(run: &mut [Layer], run_keys: &mut Vec<u64>, key_tmp: &mut Vec<u64>) {
    if insertion_sort_by_depth(run, SHIFT_BUDGET * run.len()) {
        return;
    }
    run_keys.clear();
    run_keys.extend(
        run.iter()
            .enumerate()
            .map(|(i, f)| (u64::from(f.iz_bits) << 32) | i as u64),
    );
    sort_keys(run_keys, key_tmp);
    // Place j takes the layer at the position in key j. Follow each cycle of that
    // permutation once, marking the keys used.
    const DONE: u64 = u64::MAX;
    let from = |k: u64| (k & 0xFFFF_FFFF) as usize;
    for i in 0..run.len() {
        if run_keys[i] == DONE {
            continue;
        }
        let held = run[i];
        let mut j = i;
        loop {
            let src = from(run_keys[j]);
            run_keys[j] = DONE;
            if src == i {
                run[j] = held;
                break;
            }
            run[j] = run[src];
            j = src;
        }
    }
}

/// Stable insertion sort of `run` by 1/depth ascending, giving up after `budget` shifts;
/// `true` when `run` is sorted. Given up, `run` is a permutation of itself in which equal
/// depths keep their order.
#[inline]
fn insertion_sort_by_depth(run: &mut [Layer], budget: usize) -> bool {
    let mut shifts = 0;
    for i in 1..run.len() {
        let f = run[i];
        if run[i - 1].iz_bits <= f.iz_bits {
            continue;
        }
        let mut j = i;
        while j > 0 && run[j - 1].iz_bits > f.iz_bits {
            run[j] = run[j - 1];
            j -= 1;
        }
        run[j] = f;
        shifts += i - j;
        if shifts > budget {
            return false;
        }
    }
    true
}

#[cfg(test)]
mod tests;
