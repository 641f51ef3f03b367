//! How a lookup finds a column's cells: column (j, k) of unwrapped lateral indices is
//! (j mod N')·N' + (k mod N') (N' columns a side, Bertails 2005 §2.2), and its [`ColumnIndex`]
//! record says where its cells and slot table lie. The slot table holds, per slice of the
//! column's span, the last filled cell at or before it, so the cell a depth reads is one load;
//! a sparse column (span over 4 slices per filled cell) has none and is read by binary search,
//! which keeps the slots under 4 per filled cell whatever N is.

use super::LightMap;

/// One column's entry in the lookup index: where its cells and slot table are, its first
/// slice, and the crossings of a ray through all of it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub(crate) struct ColumnIndex {
    /// First cell in `cells`, and how many.
    pub start: u32,
    pub len: u32,
    /// First slot in `slots`, and how many (0: no slot table, read by binary search).
    pub slot_start: u32,
    pub slot_len: u32,
    /// Relative slice of the column's first cell.
    pub base: u32,
    /// Σ n of the whole column (the running sum of its last cell), 0 when empty.
    pub total_n: f32,
}

impl ColumnIndex {
    pub(crate) const EMPTY: ColumnIndex = ColumnIndex {
        start: 0,
        len: 0,
        slot_start: 0,
        slot_len: 0,
        base: 0,
        total_n: 0.0,
    };
}

impl LightMap {
    /// Column index of unwrapped (j, k).
    #[inline]
    pub(super) fn column(&self, j: i64, k: i64) -> usize {
        let n = self.geom.columns_per_axis() as i64;
        (j.rem_euclid(n) * n + k.rem_euclid(n)) as usize
    }

    /// The filled cells of column `c`, sorted by slice.
    #[inline]
    #[cfg(test)]
    pub(super) fn column_cells(&self, c: usize) -> &[super::Cell] {
        &self.cells[self.col_start[c] as usize..self.col_start[c + 1] as usize]
    }

    /// Index in `cells` of the last filled cell of column `c` at or before relative slice
    /// `rel`, or `None` when the column has no cell that early.
    #[inline]
    pub(super) fn last_at_or_before(&self, c: usize, rel: u32) -> Option<usize> {
        let col = &self.index[c];
        if col.len == 0 || rel < col.base {
            return None;
        }
        let a = col.start as usize;
        if col.slot_len == 0 {
            // A sparse column without a slot table: binary search.
            let k = self.cells[a..a + col.len as usize].partition_point(|x| x.slice <= rel);
            return Some(a + k - 1);
        }
        let off = ((rel - col.base) as usize).min(col.slot_len as usize - 1);
        Some(self.slots[col.slot_start as usize + off] as usize)
    }
}
