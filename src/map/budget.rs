//! What a [`LightMap`](super::LightMap) holds, for the run's memory budget (`crate::budget`):
//! an upper bound from the map's geometry and the number of samples, computed before the map
//! exists. Keep it in step with `build.rs` (the vectors listed below) when the map changes;
//! `tests/hostile_budget.rs` measures a real build against it.

use super::MapGeometry;
use super::build::{MAX_PIECES, SLOT_SPAN_PER_CELL, SPLAT};
use super::column::{Entry, PieceStats};
use super::{Cell, OccluderGrid, occluders::MAX_TEXELS};

impl MapGeometry {
    /// Pieces each sample is split into when the longest sample is `sample_len_m` long
    /// (`build.rs`: ⌈ℓ / ds⌉, clamped to [1, 8]).
    pub fn pieces_for(&self, sample_len_m: f32) -> u64 {
        let pieces = (sample_len_m / self.ds_m).ceil();
        let max = MAX_PIECES as u64;
        if pieces.is_finite() {
            (pieces as u64).clamp(1, max)
        } else {
            max
        }
    }

    /// Upper bound, in bytes, of what a map of this geometry holds once built from `samples`
    /// render-strand samples split into `pieces` each:
    /// - `col_start` (N² + 1 `u32`), the lookup `index` (N² records) and the scratch
    ///   `col_count` (N², or one set per chunk of the parallel sort: at most the entries'
    ///   count, `sort_chunks`);
    /// - the scratch `entries` (one per piece and column it is splatted to, `SPLAT` = 4) and
    ///   `sorted` (the same entries grouped by column), and `stats` (one per sample);
    /// - `cells` (one per entry at most);
    /// - the occluder grid (at most `MAX_TEXELS`² depths);
    /// - `slots`: at most `SLOT_SPAN_PER_CELL` per filled cell (sparser columns have none), so
    ///   at most that many per entry. `slots` grows by `push`, so its capacity may reach twice
    ///   its length.
    pub fn estimated_bytes(&self, samples: u64, pieces: u64) -> u64 {
        let n = self.columns_per_axis() as u64;
        let columns = n * n;
        let u32_bytes = size_of::<u32>() as u64;
        let entries = samples.saturating_mul(pieces).saturating_mul(SPLAT as u64);
        let entry_bytes = size_of::<Entry>() as u64;
        let occluders =
            (MAX_TEXELS * MAX_TEXELS * size_of::<f32>()) as u64 + size_of::<OccluderGrid>() as u64;
        let cell_bytes = size_of::<Cell>() as u64;
        let offsets =
            (2 * columns + 1) * u32_bytes + columns * size_of::<super::ColumnIndex>() as u64;
        // Per sample: its pieces' statistics and the forward attenuation kept for the skin.
        let stats =
            samples.saturating_mul((size_of::<PieceStats>() + size_of::<glam::Vec3>()) as u64);
        let slots = 2 * entries.saturating_mul(SLOT_SPAN_PER_CELL as u64) * u32_bytes;
        offsets
            .saturating_add(entries.saturating_mul(2 * entry_bytes + cell_bytes + u32_bytes))
            .saturating_add(stats)
            .saturating_add(slots)
            .saturating_add(occluders)
    }
}
