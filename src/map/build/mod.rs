//! Building the map each frame: the fill of Bertails 2005 §3.1 and the transmittance sweep of
//! §3.2 (Eq. 3, with the dual-scattering sums of Zinke 2008 §4), in four phases, one file each:
//!
//! 1. `fill.rs`: in parallel over samples, each sample's statistics once (expected fibre
//!    crossings, their losses and variance, hair volume), and per piece one record: its slice,
//!    the first of the 2 × 2 columns it is splatted to, its place in their square, its depth
//!    range.
//! 2. `sort.rs`: the pieces grouped by that base column (a counting sort over fixed chunks,
//!    `scatter.rs`), then each base column sorted along the light.
//! 3. `merge.rs`: per column, its cells counted from the pieces of the four base columns that
//!    share into it, laid out column after column, and merged with their bilinear shares and
//!    depth histograms (`cell_merge.rs`, `depth.rs`) and swept from the light.
//! 4. `index.rs`: the slot tables and the per-column lookup index.
//!
//! Cost O(samples + filled cells + N²), the N² counters being the only per-frame cost that
//! depends on N. Every phase gives the same bits for any thread count: reductions are exact
//! (min, max, counts), a column's float sums add in one fixed order, and columns are handled in
//! fixed tasks (`tasks.rs`). Only the counting sort's scatter writes through a raw pointer
//! (`scatter.rs`, the crate's one file with `unsafe`).

mod cell_merge;
mod depth;
mod fill;
mod index;
mod input;
mod merge;
mod piece;
mod scatter;
mod sort;
mod tasks;

pub(super) use fill::MAX_PIECES;
pub(super) use index::SLOT_SPAN_PER_CELL;
pub use input::{CountModel, MapBuildInput};
pub(super) use piece::{Piece, PieceStats, Placed, SPLAT};

use super::{Cell, LightMap};
use fill::{Fill, Filled};
use glam::Vec3;
use index::index_columns;
use merge::{Merge, lay_out};
use rayon::prelude::*;
use sort::sort_pieces;

/// Figures of the last build.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MapStats {
    /// Samples filled (non-finite samples are skipped and counted in `skipped`).
    pub samples: usize,
    pub skipped: usize,
    /// Filled cells after merging.
    pub filled_cells: usize,
    /// Columns holding at least one filled cell.
    pub columns: usize,
    /// Largest hair volume fraction of a cell.
    pub peak_volume_fraction: f32,
    /// Volume of the filled cells, m³ (a measure of the hair's volume at map resolution).
    pub hair_volume_m3: f32,
    /// True when the hair extends over more than N cells along an axis, so the modulo
    /// indexing aliases distant hair (the map is too small for the scene).
    pub overflow: bool,
}

/// Reusable buffers: after the first frame, a build allocates nothing.
#[derive(Clone, Debug, Default)]
pub(super) struct Scratch {
    /// Per sample: what each of its pieces carries.
    stats: Vec<PieceStats>,
    /// Per sample: the forward attenuation ā_f (clamped to [0, 1]) its pieces carry, NaN for a
    /// sample the fill skipped; the skin's texture reads it instead of evaluating it again.
    pub(super) forward_a: Vec<Vec3>,
    /// Per sample piece: the fill's output, in piece order.
    entries: Vec<Piece>,
    /// The filled pieces grouped by base column (counting sort), each column sorted along the
    /// light.
    sorted: Vec<Placed>,
    /// Where each base column's pieces start in `sorted` (N² + 1).
    base_start: Vec<u32>,
    /// Per piece of `sorted`: its [`Placed::mark`] (what counting a column's cells reads).
    marks: Vec<u32>,
    /// Per chunk of the counting sort and column: its counts, then its cursors; then, one per
    /// column, the column's cells.
    col_count: Vec<u32>,
}

impl LightMap {
    /// Rebuilds the map for `input` (fill + sweep). Allocation-free once warmed up.
    pub fn build(&mut self, input: &MapBuildInput) {
        self.proj = input.light.projection(input.positions);
        let ncol = self.geom.columns_per_axis() as usize;
        let cols = ncol * ncol;
        // 1. Fill.
        let fill = Fill::new(input, &self.geom, self.proj, self.inv_cell, self.model);
        let filled = fill.run(&mut self.scratch);
        let overflow = self.locate_hair(&filled);
        // 2. Sort. The cursors run in `col_start`, which takes the cells' offsets afterwards.
        let n = self.geom.n as i64;
        let running = &mut self.col_start[..cols];
        sort_pieces(&mut self.scratch, running, self.first_slice, n);
        // 3. Merge.
        let scratch = &mut self.scratch;
        let merge = Merge::new(&scratch.sorted, &scratch.marks, &scratch.base_start, ncol);
        let counts = &mut scratch.col_count[..cols];
        let columns = merge.count_cells(counts);
        let cells = lay_out(counts, &mut self.col_start);
        self.cells
            .reserve_exact(cells.saturating_sub(self.cells.len()));
        self.cells.resize(cells, Cell::default());
        merge.merge(&self.col_start, &mut self.cells);
        // 4. Index.
        index_columns(
            &self.col_start,
            &self.cells,
            &mut self.slots,
            &mut self.index,
        );
        self.stats = self.build_stats(&filled, columns, overflow);
    }

    /// Records where the hair is, unwrapped (its first slice, and the filled cells' bounding
    /// box: a lookup outside it must not read hair that the modulo indexing aliases there, as a
    /// dancer's body reaches far beyond the hair's span), and returns whether the hair spans
    /// more than the map along some axis.
    fn locate_hair(&mut self, filled: &Filled) -> bool {
        let (any, extent) = (filled.pieces > 0, &filled.extent);
        self.first_slice = if any { extent.lo[0] } else { 0 };
        (self.hair_lo, self.hair_hi) = if any {
            (extent.lo, extent.hi)
        } else {
            ([i64::MAX; 3], [i64::MIN; 3])
        };
        let n = self.geom.n as i64;
        let ncol = self.geom.columns_per_axis() as i64;
        any && (extent.hi[0] - extent.lo[0] >= n
            || (1..3).any(|a| extent.hi[a] - extent.lo[a] >= ncol))
    }

    /// The figures of the build that `filled` the map's `columns` columns.
    fn build_stats(&self, filled: &Filled, columns: usize, overflow: bool) -> MapStats {
        let (ds, dc) = (self.geom.ds_m, self.geom.column_m());
        let cells = self.cells.len();
        // A maximum does not depend on the order of the reduction.
        let peak = self
            .cells
            .par_iter()
            .map(|c| c.volume_fraction)
            .reduce(|| 0.0f32, f32::max);
        MapStats {
            samples: filled.count - filled.skipped,
            skipped: filled.skipped,
            filled_cells: cells,
            columns,
            peak_volume_fraction: peak,
            hair_volume_m3: cells as f32 * ds * dc * dc,
            overflow,
        }
    }
}
