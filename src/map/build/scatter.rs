//! The counting sort of the pieces by base column, in parallel over fixed chunks of the pieces:
//! each chunk counts its pieces per column, the counts become per-chunk write cursors (chunk k
//! writes after chunks 0..k in every column), and the chunks scatter side by side into
//! disjoint places. Within a column the pieces keep their order, so the result is the
//! sequential sort's whatever the chunking or the thread count. O(pieces + chunks·N²).
//!
//! The chunks' places interleave (chunk 0's run of column c, chunk 1's, …, then column c + 1),
//! which no split of the output into `&mut` slices can express, so the scatter writes through a
//! raw pointer. This is the one file of the crate allowed `unsafe` (`lib.rs` denies it
//! elsewhere): the counts, the cursors made from them and the writes that rely on them are all
//! here, made from one shared borrow of the pieces.

#![allow(unsafe_code)]

use super::piece::{Piece, Placed};
use rayon::prelude::*;

/// The counting sort's buffers, reused from build to build.
pub(super) struct ColumnSort<'a> {
    /// Per chunk, one counter per column (chunk after chunk): the counts, then the cursors.
    pub(super) counts: &'a mut Vec<u32>,
    /// Where each column's pieces start in the output (columns + 1 entries).
    pub(super) starts: &'a mut Vec<u32>,
    /// One counter per column, a scratch for the cursors.
    pub(super) running: &'a mut [u32],
}

impl ColumnSort<'_> {
    /// Sorts the pieces of `entries` whose column ([`Piece::col`]) is not `u32::MAX` by
    /// column, in `chunks` fixed chunks, into `out` as `place` makes them, keeping their order
    /// within a column; `running.len()` is the number of columns.
    pub(super) fn run(
        self,
        entries: &[Piece],
        chunks: usize,
        out: &mut Vec<Placed>,
        place: impl Fn(&Piece) -> Placed + Sync,
    ) {
        let ColumnSort {
            counts,
            starts,
            running,
        } = self;
        let cols = running.len();
        // Every count, column total, prefix and cursor below is at most the number of pieces
        // sorted, so none of them wraps: the writes rely on it.
        assert!(
            u32::try_from(entries.len()).is_ok(),
            "the counting sort takes at most 2^32 − 1 pieces"
        );
        let chunk_len = entries.len().div_ceil(chunks).max(1);
        counts.clear();
        counts.resize(cols * chunks, 0);
        counts
            .par_chunks_mut(cols)
            .zip(entries.par_chunks(chunk_len))
            .for_each(|(count, part)| {
                for e in part.iter().filter(|e| e.col != u32::MAX) {
                    count[e.col as usize] += 1;
                }
            });
        let total = cursors(counts, starts, running) as usize;
        out.reserve_exact(total.saturating_sub(out.len()));
        out.resize(total, Placed::default());
        let at_out = SharedSlice(out.as_mut_ptr());
        let at_out = &at_out;
        counts
            .par_chunks_mut(cols)
            .zip(entries.par_chunks(chunk_len))
            .for_each(|(cursor, part)| {
                for e in part.iter().filter(|e| e.col != u32::MAX) {
                    let at = cursor[e.col as usize] as usize;
                    cursor[e.col as usize] += 1;
                    let placed = place(e);
                    // SAFETY: `at` < total = `out.len()`, and no other chunk writes it: chunk
                    // k's cursor in column c runs from the column's start plus the earlier
                    // chunks' counts there over exactly its own count (the counts were made
                    // above from the same `entries`, which are borrowed immutably, so each
                    // chunk meets the same pieces again). Every place is written once, by one
                    // chunk, and `out` is not otherwise touched until the chunks have joined.
                    unsafe { at_out.0.add(at).write(placed) };
                }
            });
    }
}

/// Turns per-chunk `counts` (one row of `running.len()` columns per chunk) into write cursors,
/// in passes that walk the counters in memory order (a column-major walk strides over the
/// chunks' rows): the column totals and their exclusive prefix into `starts` (one more entry
/// than the columns), then each chunk's cursor in a column after the column's start and the
/// earlier chunks' counts there. Returns the total.
///
/// The scatter's writes rely on every total, prefix and cursor here being exact, so each sum
/// is checked where it is made ([`sum_within_u32`]) and a sum past `u32::MAX` panics instead
/// of wrapping: a wrapped prefix would send two chunks' writes to the same places. A cursor
/// is at most its column's end, itself a prefix, so the cursors cannot pass the checked total.
fn cursors(counts: &mut [u32], starts: &mut Vec<u32>, running: &mut [u32]) -> u32 {
    let cols = running.len();
    starts.clear();
    starts.resize(cols + 1, 0);
    for row in counts.chunks_exact(cols) {
        for (total, n) in starts.iter_mut().zip(row) {
            *total = sum_within_u32(*total, *n);
        }
    }
    let mut acc = 0u32;
    for start in starts.iter_mut() {
        (*start, acc) = (acc, sum_within_u32(acc, *start));
    }
    running.copy_from_slice(&starts[..cols]);
    for row in counts.chunks_exact_mut(cols) {
        for (next, count) in running.iter_mut().zip(row) {
            let n_k = *count;
            *count = *next; // becomes this chunk's write cursor in the column
            *next = sum_within_u32(*next, n_k);
        }
    }
    acc
}

/// `a + b`, panicking (in every build, not only with overflow checks) when the sum passes
/// `u32::MAX`: the invariant the scatter's raw writes stand on. [`ColumnSort::run`] refuses
/// more than `u32::MAX` pieces and the memory budget keeps a map far below that, so the
/// panic marks a broken invariant, never an input.
#[inline]
fn sum_within_u32(a: u32, b: u32) -> u32 {
    a.checked_add(b)
        .expect("counting sort: a column total or cursor passed u32::MAX")
}

/// A buffer as a raw pointer that parallel chunks write through, each to its own places (see
/// the SAFETY note at the write).
struct SharedSlice<T>(*mut T);

// SAFETY: the chunks write disjoint places of one live allocation (`out`, borrowed mutably for
// the whole of `ColumnSort::run`), which outlives the parallel scope.
unsafe impl<T: Send> Sync for SharedSlice<T> {}

#[cfg(test)]
mod tests;
