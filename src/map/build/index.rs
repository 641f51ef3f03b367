//! Phase 4 of the build: the lookup index, one [`ColumnIndex`] record per column, and the slot
//! tables: per column, for each slice from its first filled one to its last, the last filled
//! cell at or before that slice, so a lookup finds the cell a depth reads with one load
//! (`column_index.rs`). A sparse column (a span over [`SLOT_SPAN_PER_CELL`] slices per filled
//! cell) gets no table and is read by binary search, so the tables never hold more than that
//! many slots per cell, whatever N is.

use crate::map::{Cell, ColumnIndex};

/// Most slots a column's slot table may hold per filled cell (a sparser column is read by binary
/// search): bounds the tables by the cells, whatever the span of a column.
pub(in crate::map) const SLOT_SPAN_PER_CELL: usize = 4;

/// Fills `index` (one record per column) and `slots` for the `cells` laid out by `col_start`
/// (one more entry than the columns).
pub(super) fn index_columns(
    col_start: &[u32],
    cells: &[Cell],
    slots: &mut Vec<u32>,
    index: &mut Vec<ColumnIndex>,
) {
    let cols = col_start.len() - 1;
    slots.clear();
    index.resize(cols, ColumnIndex::EMPTY);
    for c in 0..cols {
        let (a, b) = (col_start[c] as usize, col_start[c + 1] as usize);
        if a == b {
            index[c] = ColumnIndex::EMPTY;
            continue;
        }
        let slot_start = slots.len();
        let base = cells[a].slice;
        let span = (cells[b - 1].slice - base) as usize + 1;
        if span <= SLOT_SPAN_PER_CELL * (b - a) {
            let mut idx = a;
            for (cell, filled) in (a..b).zip(&cells[a..b]) {
                let s = filled.slice;
                while slots.len() - slot_start < (s - base) as usize {
                    slots.push(idx as u32);
                }
                slots.push(cell as u32);
                idx = cell;
            }
        }
        index[c] = ColumnIndex {
            start: a as u32,
            len: (b - a) as u32,
            slot_start: slot_start as u32,
            slot_len: (slots.len() - slot_start) as u32,
            base,
            total_n: cells[b - 1].n_sum,
        };
    }
}
