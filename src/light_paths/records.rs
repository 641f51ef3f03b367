//! What a light path leaves (`light_paths` module doc, step 3): one [`Record`] per straight
//! flight of scattered light through a cell a point gathers from, and a block's records filed
//! by the merge's ranges of slots ([`BlockRecords`]).
//!
//! Σ records' `power_m` / V over a cell estimates ∫ L(ω) dω there (the track-length
//! estimator), direction by direction. Each block's records are filed by range with a stable
//! counting sort, so the merge (`bins.rs`) adds every slot's records in the paths' order
//! whatever the thread count: the same sums to the bit.

use glam::Vec3;

/// One straight flight of scattered light through one cell (module doc).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Record {
    /// The cell's `Cells::slot`.
    pub(crate) slot: u32,
    /// Unit direction the light came from (against its travel).
    pub(crate) from: Vec3,
    /// Its power times the length flown in the cell, W·m, RGB.
    pub(crate) power_m: Vec3,
}

/// One block's records, grouped by range of `span` slots (range j: slots j·span..), each
/// range's in the order the paths left them.
pub(super) struct BlockRecords {
    records: Vec<Record>,
    /// Range j's records: `records[ends[j - 1]..ends[j]]` (from 0 for j = 0).
    ends: Vec<u32>,
}

impl BlockRecords {
    /// Groups `records` by range of `span` slots, `ranges` ranges (a stable counting sort).
    pub(super) fn new(records: Vec<Record>, span: usize, ranges: usize) -> BlockRecords {
        let range_of = |r: &Record| (r.slot as usize / span).min(ranges - 1);
        let mut ends = vec![0u32; ranges];
        for r in &records {
            ends[range_of(r)] += 1;
        }
        let mut at = 0;
        let mut cursor: Vec<u32> = ends
            .iter_mut()
            .map(|e| {
                let start = at;
                at += *e;
                *e = at;
                start
            })
            .collect();
        let mut grouped = records.clone();
        for r in records {
            let c = &mut cursor[range_of(&r)];
            grouped[*c as usize] = r;
            *c += 1;
        }
        BlockRecords {
            records: grouped,
            ends,
        }
    }

    /// The records of range `j`, in the paths' order.
    pub(super) fn range(&self, j: usize) -> &[Record] {
        let start = j
            .checked_sub(1)
            .and_then(|i| self.ends.get(i))
            .map_or(0, |&e| e as usize);
        let end = self.ends.get(j).map_or(start, |&e| e as usize);
        &self.records[start..end.max(start)]
    }
}
