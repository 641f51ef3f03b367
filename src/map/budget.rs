//! What a [`LightMap`](super::LightMap) holds, for the run's memory budget (`crate::budget`):
//! an upper bound from the map's geometry and the number of samples, computed before the map
//! exists. Keep it in step with `build/` (the vectors listed below) when the map changes;
//! `tests/lib/hostile_budget.rs` measures a real build against it.

use super::build::{MAX_PIECES, Piece, PieceStats, Placed, SLOT_SPAN_PER_CELL, SPLAT};
use super::{Cell, ColumnIndex, MapGeometry};

impl MapGeometry {
    /// Pieces each sample is split into when the longest sample is `sample_len_m` long
    /// (`build/fill.rs`: ⌈ℓ / ds⌉, clamped to [1, 8]).
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
    /// - `col_start` (N² + 1 `u32`), the lookup `index` (N² records), the scratch
    ///   `base_start` (N² + 1) and `col_count` (N², or one set per chunk of the parallel sort:
    ///   at most the pieces' count, `sort_chunks`);
    /// - the scratch `entries` (one [`Piece`] per piece) and `sorted` (one [`Placed`] per
    ///   piece), and `stats` (one per sample);
    /// - `cells` (at most one per piece and column it is shared with, `SPLAT` = 4);
    /// - `slots`: at most `SLOT_SPAN_PER_CELL` per filled cell (sparser columns have none).
    ///   `slots` grows by `push`, so its capacity may reach twice its length.
    pub fn estimated_bytes(&self, samples: u64, pieces: u64) -> u64 {
        let n = self.columns_per_axis() as u64;
        let columns = n * n;
        let u32_bytes = size_of::<u32>() as u64;
        let pieces = samples.saturating_mul(pieces);
        let cells = pieces.saturating_mul(SPLAT as u64);
        let piece_bytes = (size_of::<Piece>() + size_of::<Placed>()) as u64 + u32_bytes;
        let cell_bytes = size_of::<Cell>() as u64;
        let offsets = (3 * columns + 2) * u32_bytes + columns * size_of::<ColumnIndex>() as u64;
        // Per sample: its pieces' statistics and the forward attenuation kept for the skin.
        let stats =
            samples.saturating_mul((size_of::<PieceStats>() + size_of::<glam::Vec3>()) as u64);
        let slots = 2 * cells.saturating_mul(SLOT_SPAN_PER_CELL as u64) * u32_bytes;
        offsets
            .saturating_add(pieces.saturating_mul(piece_bytes))
            .saturating_add(cells.saturating_mul(cell_bytes))
            .saturating_add(stats)
            .saturating_add(slots)
    }
}
