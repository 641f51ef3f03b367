//! What a [`LightMap`](super::LightMap) holds, for the run's memory budget (`crate::budget`):
//! an upper bound from the map's geometry and the number of samples, computed before the map
//! exists. Keep it in step with `build.rs` (the vectors listed below) when the map changes;
//! `tests/hostile_budget.rs` measures a real build against it.

use super::{Cell, MapGeometry};

/// Most pieces a sample is split into: `MAX_PIECES` in `build.rs`.
const MAX_PIECES: u64 = 8;

impl MapGeometry {
    /// Pieces each sample is split into when the longest sample is `sample_len_m` long
    /// (`build.rs`: ⌈ℓ / ds⌉, clamped to [1, 8]).
    pub fn pieces_for(&self, sample_len_m: f32) -> u64 {
        let pieces = (sample_len_m / self.ds_m).ceil();
        if pieces.is_finite() {
            (pieces as u64).clamp(1, MAX_PIECES)
        } else {
            MAX_PIECES
        }
    }

    /// Upper bound, in bytes, of what a map of this geometry holds once built from `samples`
    /// render-strand samples split into `pieces` each:
    /// - `col_start`, `slot_start` (N² + 1 `u32` each) and the scratch `col_count` (N²);
    /// - the scratch `entries` (one per piece; `Entry` is `{ col: u32, slice: i64, cell: Cell }`,
    ///   private to `build.rs`, measured here as the tuple of the same fields);
    /// - `cells` (one per piece at most);
    /// - `slots`: per filled column, one `u32` per slice of its span, at most N; filled columns
    ///   are at most min(pieces, N²). `slots` grows by `push`, so its capacity may reach twice
    ///   its length.
    pub fn estimated_bytes(&self, samples: u64, pieces: u64) -> u64 {
        let n = self.n as u64;
        let columns = n * n;
        let u32_bytes = size_of::<u32>() as u64;
        let entries = samples.saturating_mul(pieces);
        let entry_bytes = size_of::<(u32, i64, Cell)>() as u64;
        let cell_bytes = size_of::<Cell>() as u64;
        let offsets = (3 * columns + 2) * u32_bytes;
        let slots = 2 * entries.min(columns).saturating_mul(n) * u32_bytes;
        offsets
            .saturating_add(entries.saturating_mul(entry_bytes + cell_bytes))
            .saturating_add(slots)
    }
}
