//! Phase 2 of the build: the pieces grouped by base column (the first of the 2 × 2 columns each
//! is shared with), then each base column sorted along the light.
//!
//! 1. The counting sort by base column (`scatter.rs`), O(pieces + N²), keeps piece order
//!    inside a column and carries each sample's statistics beside its pieces (read in sample
//!    order here, not at random in the merge), with each piece's slice made relative to the
//!    first slice and wrapped modulo N (Bertails 2005 Figure 3).
//! 2. Per base column, in parallel: a stable sort along the light ([`sort_column`]; ties stay
//!    in piece order, so the merge's float sums always add in the same order whatever the
//!    thread count), and each piece's mark (`Placed::mark`: its slice and which of its shares
//!    are positive), which is all that counting a column's cells reads.
//!
//! Sorting pieces instead of one entry per piece and column moves a quarter of the bytes; the
//! merge adds in the order that sort of entries would give, so the cells are the same bits.

use super::Scratch;
use super::piece::Placed;
use super::scatter::ColumnSort;
use super::tasks::for_each_column;

/// Most chunks of the parallel counting sort.
const MAX_SORT_CHUNKS: usize = 8;

/// Chunks of the counting sort: as many as fit with their per-column counters in no more memory
/// than the entries' own count (so a huge sparse map sorts in one chunk), at most
/// [`MAX_SORT_CHUNKS`]. The result does not depend on it.
fn sort_chunks(entries: usize, cols: usize) -> usize {
    (entries / cols.max(1)).clamp(1, MAX_SORT_CHUNKS)
}

/// Sorts `scratch`'s pieces into `scratch.sorted` by base column (column starts in
/// `scratch.base_start`), each column along the light, and marks them (`scratch.marks`).
/// `running` (one counter per column) is a scratch for the cursors; `first` is the first
/// slice and `n` the slices of the map.
pub(super) fn sort_pieces(scratch: &mut Scratch, running: &mut [u32], first: i64, n: i64) {
    let cols = running.len();
    let Scratch {
        stats,
        entries,
        sorted,
        base_start,
        marks,
        col_count,
        ..
    } = scratch;
    let chunks = sort_chunks(entries.len(), cols);
    let sort = ColumnSort {
        counts: col_count,
        starts: base_start,
        running,
    };
    sort.run(entries, chunks, sorted, |e| {
        // Relative slice, wrapping modulo N (Bertails Figure 3).
        let rel = (e.slice - first).rem_euclid(n) as u32;
        Placed::new(e, rel, stats[e.sample as usize])
    });
    marks.reserve_exact(sorted.len().saturating_sub(marks.len()));
    marks.resize(sorted.len(), 0);
    for_each_column((&mut sorted[..], &mut marks[..]), base_start, &|_,
                                                                     (
        col,
        col_marks,
    ): (
        &mut [Placed],
        &mut [u32],
    )| {
        sort_column(col);
        for (m, p) in col_marks.iter_mut().zip(col.iter()) {
            *m = p.mark();
        }
    });
}

/// Sorts one base column's pieces by (relative slice, piece order). The counting sort by
/// column keeps each column in piece order, so a stable sort by slice alone gives that order:
/// short columns by insertion, longer ones by counting slices into a per-thread buffer,
/// O(length + span) and allocation-free once the buffers have grown. (Measured: the general
/// unstable sort on the pair key takes a quarter of the build.)
pub(super) fn sort_column(col: &mut [Placed]) {
    debug_assert!(col.windows(2).all(|w| w[0].id < w[1].id));
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
    let (lo, hi) = col.iter().fold((u32::MAX, u32::MIN), |(lo, hi), c| {
        (lo.min(c.slice), hi.max(c.slice))
    });
    if lo == hi {
        return;
    }
    thread_local! {
        static BUFFERS: std::cell::RefCell<(Vec<u32>, Vec<Placed>)> =
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

#[cfg(test)]
mod tests;
