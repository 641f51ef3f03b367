//! Phase 3 of the build: the pieces merged into cells, column by column in parallel, and
//! swept from the light.
//!
//! Column (j, k) takes share t of the pieces of base column (j − (t >> 1), k − (t & 1))
//! (wrapping), each sorted along the light by phase 2. Its cells are first counted (the
//! distinct slices among those pieces with a positive share, from their marks alone), the
//! cells of all columns laid out column after column, and then each column's pieces merged
//! into its cells with their bilinear shares and swept (`cell_merge.rs`). The four sources are
//! merged in (slice, piece order, share) order, the order a sort of one entry per piece and
//! column would give, so every float sum adds in one fixed order whatever the thread count.

use super::cell_merge::CellMerge;
use super::piece::{MARK_SLICE_BITS, Placed, SPLAT, splat_weight};
use super::tasks::{COLUMNS_PER_TASK, for_each_column, task_start};
use crate::map::Cell;
use rayon::prelude::*;
use std::ops::Range;

/// Where the pieces of each base column lie in the sorted pieces, and which base columns share
/// into a column.
struct BaseColumns<'a> {
    /// Base column c's pieces are `starts[c]..starts[c + 1]`.
    starts: &'a [u32],
    /// Columns per lateral axis.
    ncol: usize,
}

impl BaseColumns<'_> {
    /// The row or column before `m`, wrapping.
    #[inline]
    fn back(&self, m: usize) -> usize {
        if m == 0 { self.ncol - 1 } else { m - 1 }
    }

    /// Pieces in row `j` of base columns.
    #[inline]
    fn row_pieces(&self, j: usize) -> u32 {
        self.starts[(j + 1) * self.ncol] - self.starts[j * self.ncol]
    }

    /// Where the four base columns whose pieces share into column (j, k) lie, by share index.
    #[inline]
    fn sources(&self, j: usize, k: usize) -> [Range<usize>; SPLAT] {
        let base = |j: usize, k: usize| {
            let c = j * self.ncol + k;
            self.starts[c] as usize..self.starts[c + 1] as usize
        };
        [
            base(j, k),
            base(j, self.back(k)),
            base(self.back(j), k),
            base(self.back(j), self.back(k)),
        ]
    }
}

/// The merge of sorted, marked pieces into cells.
pub(super) struct Merge<'a> {
    sorted: &'a [Placed],
    marks: &'a [u32],
    bases: BaseColumns<'a>,
}

impl<'a> Merge<'a> {
    /// The merge of `sorted` pieces and their `marks`, base column c's at
    /// `base_start[c]..base_start[c + 1]`, in a map of `ncol` columns a side.
    pub(super) fn new(
        sorted: &'a [Placed],
        marks: &'a [u32],
        base_start: &'a [u32],
        ncol: usize,
    ) -> Self {
        Merge {
            sorted,
            marks,
            bases: BaseColumns {
                starts: base_start,
                ncol,
            },
        }
    }

    /// Counts each column's cells into `counts` (one per column), in parallel over tasks;
    /// returns how many columns have a cell. Row by row of columns: a row whose base rows (its
    /// own and the one before) hold no piece has no cell.
    pub(super) fn count_cells(&self, counts: &mut [u32]) -> usize {
        let (bases, ncol) = (&self.bases, self.bases.ncol);
        counts
            .par_chunks_mut(COLUMNS_PER_TASK)
            .enumerate()
            .with_max_len(1)
            .map(|(task, counts)| {
                let c0 = task_start(task);
                let mut filled_columns = 0;
                let mut at = 0;
                while at < counts.len() {
                    let (j, k0) = ((c0 + at) / ncol, (c0 + at) % ncol);
                    let run = (ncol - k0).min(counts.len() - at);
                    let row = &mut counts[at..at + run];
                    if bases.row_pieces(j) == 0 && bases.row_pieces(bases.back(j)) == 0 {
                        row.fill(0);
                    } else {
                        for (k, count) in (k0..).zip(row.iter_mut()) {
                            let marks = bases.sources(j, k).map(|r| &self.marks[r]);
                            *count = column_cells(marks) as u32;
                            filled_columns += usize::from(*count > 0);
                        }
                    }
                    at += run;
                }
                filled_columns
            })
            .sum::<usize>()
    }

    /// Merges every column's pieces into its cells, `col_start[c]..col_start[c + 1]` of
    /// `cells`, in parallel over tasks.
    pub(super) fn merge(&self, col_start: &[u32], cells: &mut [Cell]) {
        let ncol = self.bases.ncol;
        for_each_column(cells, col_start, &|c, cells: &mut [Cell]| {
            if !cells.is_empty() {
                let sources = self.bases.sources(c / ncol, c % ncol);
                merge_column(sources.map(|r| &self.sorted[r]), cells);
            }
        });
    }
}

/// Lays the cells out column after column: `col_start[c]` (one more entry than `counts`) is
/// where column c's `counts[c]` cells start. Returns the cells in all.
pub(super) fn lay_out(counts: &[u32], col_start: &mut [u32]) -> usize {
    let mut acc = 0u32;
    for (start, cells) in col_start.iter_mut().zip(counts) {
        *start = acc;
        acc = acc
            .checked_add(*cells)
            .expect("the map holds at most 2^32 − 1 cells");
    }
    col_start[counts.len()] = acc;
    acc as usize
}

/// How many cells one column has: the distinct slices among the pieces of `sources` (their
/// [`Placed::mark`]s, in the order of [`merge_column`]'s sources) whose share in it is
/// positive. A bit per slice over the slices the sources span, in a per-thread buffer.
pub(super) fn column_cells(sources: [&[u32]; SPLAT]) -> usize {
    let slice = |m: u32| m & ((1 << MARK_SLICE_BITS) - 1);
    let lo = sources
        .iter()
        .filter_map(|s| s.first())
        .map(|&m| slice(m))
        .min();
    let hi = sources
        .iter()
        .filter_map(|s| s.last())
        .map(|&m| slice(m))
        .max();
    let (Some(lo), Some(hi)) = (lo, hi) else {
        return 0;
    };
    thread_local! {
        static BITS: std::cell::RefCell<Vec<u64>> = const { std::cell::RefCell::new(Vec::new()) };
    }
    BITS.with_borrow_mut(|bits| {
        bits.clear();
        bits.resize(((hi - lo) / 64 + 1) as usize, 0);
        for (t, source) in sources.iter().enumerate() {
            for &m in source.iter() {
                let at = slice(m) - lo;
                let set = u64::from(m >> (MARK_SLICE_BITS as usize + t) & 1);
                bits[(at / 64) as usize] |= set << (at % 64);
            }
        }
        bits.iter().map(|w| w.count_ones() as usize).sum()
    })
}

/// Merges the pieces that reach one column into its `cells` (one per distinct slice,
/// [`column_cells`] of them), each piece carrying its sample's statistics times its bilinear
/// share, and sweeps them from the light (Bertails Eq. 3 with the dual-scattering
/// quantities). `sources[t]` holds the pieces whose share `t` falls in this column (those of
/// the base column `t >> 1` back along j and `t & 1` back along k), each sorted by (slice,
/// piece order). They are merged in (slice, piece order, t) order: the order a sort of one
/// entry per piece and column would give, so every float sum adds in one fixed order.
pub(super) fn merge_column(sources: [&[Placed]; SPLAT], cells: &mut [Cell]) {
    let key = |t: usize, i: usize| sources[t].get(i).map_or(u64::MAX, Placed::key);
    let mut at = [0usize; SPLAT];
    let mut keys = [key(0, 0), key(1, 0), key(2, 0), key(3, 0)];
    let mut merge = CellMerge::new(cells);
    loop {
        // The lowest key; a tie (only where the columns wrap onto themselves) goes to the
        // lower share index.
        let mut t = 0;
        for u in 1..SPLAT {
            if keys[u] < keys[t] {
                t = u;
            }
        }
        if keys[t] == u64::MAX {
            break;
        }
        let p = &sources[t][at[t]];
        at[t] += 1;
        keys[t] = key(t, at[t]);
        let weight = splat_weight(p.frac, t);
        // A share of exactly 0 (a piece on a column centre line) makes no cell.
        if weight > 0.0 {
            merge.add(p.slice, &p.stats, weight, p.depth);
        }
    }
    merge.finish();
}

#[cfg(test)]
mod tests;
