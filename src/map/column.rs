//! One column of the map build (`build.rs` step 3): its entries sorted along the light, merged
//! into cells with where their crossings lie in depth, and swept from the light (Bertails 2005
//! Eq. 3 with the dual-scattering quantities).

use super::{Cell, DEPTH_BINS};
use glam::{Vec3, Vec4};

/// A sample piece's share of one column, before sorting: where it is and with what weight;
/// what it carries is its sample's [`PieceStats`] times `weight` (24 bytes, so the sort moves
/// a third of what whole cells would be).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Entry {
    /// Unwrapped slice ⌊x/ds⌋ after the fill; the slice relative to the first slice (0..N)
    /// after the counting sort.
    pub(super) slice: i64,
    /// Column index, or `u32::MAX` for a skipped (non-finite) sample or a zero share.
    pub(super) col: u32,
    /// The sample the piece belongs to (index into the per-sample statistics).
    pub(super) sample: u32,
    /// Bilinear share of the column, (0, 1].
    pub(super) weight: f32,
    /// The depth range along the light that the piece spans inside its cell, in 1/65535 of a
    /// cell from the light-side face.
    pub(super) depth: [u16; 2],
}

/// What one piece of a sample carries into a cell before its bilinear share: expected
/// crossings, their losses Σ n(1 − ā_f) and variance Σ n β̄_f², and hair volume fraction.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct PieceStats {
    pub(super) n: f32,
    pub(super) loss: [f32; 3],
    pub(super) sigma2: [f32; 3],
    pub(super) volume_fraction: f32,
}

/// Sorts one column's entries by (relative slice, sample). The counting sort by column keeps
/// each column in sample order, so a stable sort by slice alone gives that order: short
/// columns by insertion, longer ones by counting slices into a per-thread buffer,
/// O(length + span) and allocation-free once the buffers have grown. (Measured: the general
/// unstable sort on the pair key was a quarter of the build.)
pub(super) fn sort_column(col: &mut [Entry]) {
    debug_assert!(col.windows(2).all(|w| w[0].sample <= w[1].sample));
    if col.len() <= 16 {
        for i in 1..col.len() {
            let mut j = i;
            while j > 0 && col[j - 1].slice > col[j].slice {
                col.swap(j - 1, j);
                j -= 1;
            }
        }
        return;
    }
    let (lo, hi) = col.iter().fold((i64::MAX, i64::MIN), |(lo, hi), c| {
        (lo.min(c.slice), hi.max(c.slice))
    });
    if lo == hi {
        return;
    }
    thread_local! {
        static BUFFERS: std::cell::RefCell<(Vec<u32>, Vec<Entry>)> =
            const { std::cell::RefCell::new((Vec::new(), Vec::new())) };
    }
    BUFFERS.with_borrow_mut(|(count, copy)| {
        count.clear();
        count.resize((hi - lo) as usize + 1, 0);
        for c in col.iter() {
            count[(c.slice - lo) as usize] += 1;
        }
        let mut acc = 0u32;
        for k in count.iter_mut() {
            let n = *k;
            *k = acc;
            acc += n;
        }
        copy.clear();
        copy.extend_from_slice(col);
        for c in copy.iter() {
            let at = &mut count[(c.slice - lo) as usize];
            col[*at as usize] = *c;
            *at += 1;
        }
    });
}

/// Merges the entries of one column (sorted by slice) into its `cells` (one per distinct
/// slice), each piece carrying its sample's statistics times its share, and sweeps them from
/// the light (Bertails Eq. 3 with the dual-scattering quantities).
pub(super) fn merge_and_sweep(col: &[Entry], stats: &[PieceStats], cells: &mut [Cell]) {
    // Merge runs of equal slice, accumulating where along the light each run's crossings lie
    // (a histogram over DEPTH_BINS sub-slices).
    let mut w = 0usize;
    let mut hist = [0.0f32; DEPTH_BINS];
    for (r, e) in col.iter().enumerate() {
        let st = &stats[e.sample as usize];
        let wt = e.weight;
        let n = st.n * wt;
        let loss = (Vec3::from(st.loss) * wt).to_array();
        let sigma2 = (Vec3::from(st.sigma2) * wt).to_array();
        let vf = st.volume_fraction * wt;
        if r > 0 && e.slice == col[r - 1].slice {
            let m = &mut cells[w - 1];
            m.n_sum += n;
            m.volume_fraction += vf;
            for ch in 0..3 {
                m.loss[ch] += loss[ch];
                m.sigma2[ch] += sigma2[ch];
            }
        } else {
            if w > 0 {
                cells[w - 1].depth_cdf = depth_cdf(&hist);
            }
            hist = [0.0; DEPTH_BINS];
            cells[w] = Cell {
                slice: e.slice as u32,
                n_sum: n,
                loss,
                sigma2,
                volume_fraction: vf,
                depth_cdf: [0; DEPTH_BINS - 1],
            };
            w += 1;
        }
        spread_depth(&mut hist, e.depth, n);
    }
    if w > 0 {
        cells[w - 1].depth_cdf = depth_cdf(&hist);
    }
    debug_assert_eq!(w, cells.len());
    // Sweep: running sums of crossings, losses and variance; each cell then holds what has
    // been crossed up to its far face (the lookup takes exponentials).
    let (mut n_sum, mut loss, mut var) = (0.0f32, [0.0f32; 3], [0.0f32; 3]);
    for c in cells.iter_mut() {
        n_sum += c.n_sum;
        c.n_sum = n_sum;
        for ch in 0..3 {
            loss[ch] += c.loss[ch];
            var[ch] += c.sigma2[ch];
        }
        c.loss = loss;
        c.sigma2 = var;
    }
}

/// Adds `n` crossings spread evenly over the depth range `depth` (1/65535 of a cell) to the
/// sub-slice histogram `hist`.
#[inline]
fn spread_depth(hist: &mut [f32; DEPTH_BINS], depth: [u16; 2], n: f32) {
    let k = DEPTH_BINS as f32 / 65535.0;
    let (lo, hi) = (depth[0] as f32 * k, depth[1] as f32 * k);
    let width = hi - lo;
    if width < 1e-6 {
        hist[(lo as usize).min(DEPTH_BINS - 1)] += n;
        return;
    }
    let (b0, b1) = (
        (lo as usize).min(DEPTH_BINS - 1) as f32,
        (hi as usize).min(DEPTH_BINS - 1) as f32,
    );
    // The bins b0..=b1, four to a vector: each lane rounds its min, max, product and quotient
    // as the scalar `n * overlap / width` does (IEEE), and a lane outside b0..=b1 adds exactly
    // nothing, so this is the per-bin loop to the bit (also for a non-finite n) without its
    // scalar divisions, which were about a third of the merge.
    const _: () = assert!(DEPTH_BINS == 8);
    let (lo4, hi4, n4, width4) = (
        Vec4::splat(lo),
        Vec4::splat(hi),
        Vec4::splat(n),
        Vec4::splat(width),
    );
    for (half, start) in [(0, 0.0f32), (4, 4.0)] {
        let b = Vec4::new(start, start + 1.0, start + 2.0, start + 3.0);
        let overlap = (hi4.min(b + 1.0) - lo4.max(b)).max(Vec4::ZERO);
        let reached = b.cmpge(Vec4::splat(b0)) & b.cmple(Vec4::splat(b1));
        let add = Vec4::select(reached, n4 * overlap / width4, Vec4::ZERO);
        let h = Vec4::from_slice(&hist[half..half + 4]);
        Vec4::select(reached, h + add, h).write_to_slice(&mut hist[half..half + 4]);
    }
}

/// The cumulative shares of a sub-slice histogram at its inner boundaries, in 1/255. An empty
/// histogram (a cell whose pieces carry no crossings, e.g. fibres along the light) reads as
/// spread evenly.
fn depth_cdf(hist: &[f32; DEPTH_BINS]) -> [u8; DEPTH_BINS - 1] {
    let total: f32 = hist.iter().sum();
    let mut out = [0u8; DEPTH_BINS - 1];
    let mut acc = 0.0f32;
    for (k, o) in out.iter_mut().enumerate() {
        acc += hist[k];
        let share = if total > 0.0 {
            acc / total
        } else {
            (k + 1) as f32 / DEPTH_BINS as f32
        };
        *o = (share.clamp(0.0, 1.0) * 255.0).round() as u8;
    }
    out
}

#[cfg(test)]
mod sort_tests {
    use super::*;
    use proptest::prelude::*;

    /// The depth spread as a plain loop over the bins the piece reaches, one division each:
    /// what the vector version must give to the bit.
    fn spread_depth_per_bin(hist: &mut [f32; DEPTH_BINS], depth: [u16; 2], n: f32) {
        let k = DEPTH_BINS as f32 / 65535.0;
        let (lo, hi) = (depth[0] as f32 * k, depth[1] as f32 * k);
        let width = hi - lo;
        if width < 1e-6 {
            hist[(lo as usize).min(DEPTH_BINS - 1)] += n;
            return;
        }
        let (b0, b1) = (
            (lo as usize).min(DEPTH_BINS - 1),
            (hi as usize).min(DEPTH_BINS - 1),
        );
        for (b, h) in hist.iter_mut().enumerate().take(b1 + 1).skip(b0) {
            let overlap = (hi.min(b as f32 + 1.0) - lo.max(b as f32)).max(0.0);
            *h += n * overlap / width;
        }
    }

    proptest! {
        /// Spreading pieces over the depth bins gives the plain per-bin loop's bits, for any
        /// depth range (empty, within one bin, ending on a bin's edge, the whole cell), any
        /// crossings (0, tiny, huge, infinite) and any sums already in the bins.
        #[test]
        fn depth_spread_is_the_per_bin_loop_to_the_bit(
            pieces in prop::collection::vec(
                (0u16..=65535, 0u16..=65535, prop_oneof![
                    Just(0.0f32), Just(1e-30), Just(3.0e38), Just(f32::INFINITY),
                    0.0f32..10.0,
                ], any::<bool>()),
                1..12,
            ),
        ) {
            let (mut ours, mut reference) = ([0.0f32; DEPTH_BINS], [0.0f32; DEPTH_BINS]);
            for (a, b, n, on_edge) in pieces {
                // Depths on a bin's edge (multiples of 65535/8 rounded) as well as anywhere.
                let edge = |v: u16| ((v as u32 * 8 / 65536) * 65535 / 8) as u16;
                let (a, b) = if on_edge { (edge(a), edge(b)) } else { (a, b) };
                let depth = [a.min(b), a.max(b)];
                spread_depth(&mut ours, depth, n);
                spread_depth_per_bin(&mut reference, depth, n);
            }
            prop_assert_eq!(ours.map(f32::to_bits), reference.map(f32::to_bits));
        }

        /// The column sort (insertion for short columns, a counting sort by slice for long
        /// ones) gives exactly the order of a sort on (slice, sample) for any column in sample
        /// order, the order the counting sort by column leaves: the merge's float sums then
        /// add in the same order as before, whatever the column's length or slice spread.
        #[test]
        fn column_sort_is_the_sort_on_slice_then_sample(
            slices in prop::collection::vec(0i64..40, 0..200),
            repeats in prop::collection::vec(1u32..4, 200),
        ) {
            // Samples in non-decreasing order (a sample's four splat entries may share one).
            let mut sample = 0u32;
            let col: Vec<Entry> = slices
                .iter()
                .zip(&repeats)
                .map(|(&slice, &r)| {
                    sample += r / 2;
                    Entry { slice, col: 7, sample, weight: r as f32, depth: [r as u16, 0] }
                })
                .collect();
            let mut ours = col.clone();
            sort_column(&mut ours);
            let mut reference: Vec<(usize, Entry)> = col.iter().copied().enumerate().collect();
            reference.sort_by_key(|(i, e)| (e.slice, e.sample, *i));
            let key = |e: &Entry| (e.slice, e.sample, e.weight.to_bits(), e.depth);
            prop_assert_eq!(
                ours.iter().map(key).collect::<Vec<_>>(),
                reference.iter().map(|(_, e)| key(e)).collect::<Vec<_>>()
            );
        }
    }
}
