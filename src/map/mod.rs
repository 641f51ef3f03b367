//! The light-oriented, modulo-indexed map (Bertails 2005 §2–3), carrying the dual-scattering
//! statistics of Zinke 2008 §4 instead of an opacity.
//!
//! ## Frame and cells
//! The map frame is (X = L, Y, Z) with L the direction the light travels (Bertails §2.1). A
//! point with map coordinates (x, y, z) belongs to cell Ψ(P) = (⌊x/ds⌋ mod N, ⌊y/ds⌋ mod N,
//! ⌊z/ds⌋ mod N) (Bertails §2.2). The map spans N·ds ≥ 2·lmax + hmax, so the hair always fits
//! and moving the hair never reallocates or re-centres anything.
//!
//! ## Sparse storage: cost O(samples + touched cells)
//! Instead of N³ voxels, the map stores only filled cells, grouped by column (j, k) in a
//! compressed-row layout: a counting sort of the sample pieces by column (N² counters, the
//! only per-frame cost that depends on N) followed, per column and in parallel, by a sort of
//! its pieces along X (relative to the first slice, wrapping modulo N as in Bertails Figure
//! 3), a merge of pieces falling in the same cell, and the sweep of Eq. 3 (`build/`). An
//! empty cell has the value of the last filled cell before it in its column (Bertails §3.2:
//! "otherwise cell (i,j,k) is given the transmittance prevTrans"); a lookup finds it through
//! a per-column slot table. A dense N³ grid at N = 128 would clear and sweep 2M cells (56 MB
//! at 7 floats) each frame for ~30K filled.
//!
//! ## What a cell holds (DESIGN.md "Fill")
//! Each render-strand sample stands for a length ℓ of F real fibres of radius r. A light ray
//! through a column of cross-section ds² meets it with probability ℓ·2r·sin ψ / ds² (ψ: angle
//! between fibre and L), so the expected number of crossings the sample adds is
//! n = F·ℓ·2r·sin ψ / ds². Each crossing forward-scatters with the fibre's ā_f(θ) and adds
//! β̄_f²(θ) of angular variance (Zinke 2008 Eqs. 6, 19, 20), θ being the light's inclination to
//! that fibre. With crossings Poisson-distributed along a ray of the column (fibres placed
//! independently), the column-averaged quantities after crossings of mean total n̄ are:
//!
//! - direct fraction (no crossing yet): P(N = 0) = exp(−n̄);
//! - forward transmittance: E[∏ ā_f] = exp(−Σ n·(1 − ā_f)) per colour channel;
//! - spread: σ̄f² = Σ n·β̄_f².
//!
//! The alternative reading ā^n̄ (`CountModel::MeanCount`) is kept for measurement: it is the
//! transmittance of a ray meeting exactly the mean number of fibres, and it is darker than the
//! ray average (by Jensen); `tests/lib/map_reference.rs` measures both against ray shooting.
//! The sums are kept, not their exponentials, so a lookup can take any part of a cell exactly.
//!
//! ## Across the light: a bilinear splat and a bilinear read
//! A sample piece is shared by the four columns nearest to it, with bilinear (tent) weights
//! about their centres, and a lookup blends the four columns nearest to the point with the
//! same weights. A box fill (each piece into one column) makes the light jump where a strand
//! crosses a column boundary, which shows the grid as cell-sized blotches on front-lit hair
//! lying side by side; the splat removes them (measured on smooth at N = 129 against the exact
//! reference: T_f MAE 0.025 → 0.021, ACCURACY.md), at four shares per piece, taken as the
//! columns are merged (`build/merge.rs`).
//!
//! ## Along the light: where a cell's hair lies, and what a point receives
//! A cell stores the running sums of the sweep up to its *far face* (the face away from the
//! light; Bertails' "light received by its back side"), and a histogram of where along the
//! light its crossings lie: 8 sub-slices, as a cumulative share (`Cell::depth_cdf`;
//! each piece spreads its crossings evenly over the depth it spans). A point inside a cell
//! receives the sums entering the cell plus only the share of the cell's crossings in front of
//! it, turned into exp(−n) and exp(−loss) per column, so the front-most fibres of a cell are
//! not shadowed by hair lying beside or behind them (Bertails §6 names this family, adaptive
//! slicing along the light). Reading through a cell with a uniform spread (the filter of
//! Bertails §3.3) reads lit hair 0.16–0.23 too dark against the exact reference. A slab of hair
//! perpendicular to L still reads exactly 1 in front of it and exactly the analytic attenuation
//! at every face behind it (`tests/lib/map_slab.rs`).
//!
//! ## Opaque solids
//! The head and body are occluders in the same light frame ([`OccluderGrid`]: entry depth per
//! texel of a quarter cell), so they shadow the hair as the hair shadows them. A character's
//! skinned mesh is rasterised into the same grid.
//!
//! ## Contact shadows
//! For hair of one fibre per render strand, the fibres just in front of a vertex are taken
//! exactly ([`contact`]): the map gives the light reaching a window in front of the point, the
//! real fibres inside the window what gets through it.
//!
//! ## Measuring it
//! [`crate::accuracy::exact`] shoots rays through explicit fibre cylinders (no grid, no
//! statistics), and [`crate::accuracy`] compares the map with it; `wisp accuracy` prints the
//! tables of ACCURACY.md.
//!
//! ## Where things are
//! [`MapGeometry`] (`geometry.rs`) sizes the map; [`Projection`] (`projection.rs`) takes world
//! points into the light frame; [`LightMap::build`] (`build/`, one file per phase) fills and
//! sweeps the cells (`cell.rs`) and indexes the columns (`column_index.rs`); `lookup.rs` reads
//! them, and `seen.rs` for a point the camera sees. The solids' grid (`occluders/`), the skin's texture (`surface/`) and the contact
//! shadows (`contact/`) are built in the same light frame, and [`Shadow`] (`shadows.rs`) reads
//! a light's three together.

mod budget;
mod build;
mod cell;
mod column_index;
pub mod contact;
mod entry_depths;
mod geometry;
pub(crate) mod lateral_bins;
mod lookup;
pub(crate) mod occluders;
mod projection;
mod seen;
mod shadows;
pub mod surface;

pub use build::{CountModel, MapBuildInput, MapStats};
pub(crate) use cell::{Cell, DEPTH_BINS};
pub(crate) use column_index::ColumnIndex;
pub use geometry::{MAX_LATERAL_COLUMNS, MapGeometry};
pub use occluders::{OccluderGrid, OccluderMesh, Solid};
pub use projection::{CENTRAL_MIN_DEPTH_M, LightFrame, MapLight, Projection};
pub use shadows::{BuiltEarlier, Shadow, Shadows};

use glam::{Vec2, Vec3};

/// Coordinates beyond this many cells are treated as invalid (keeps `as i64` well defined).
const MAX_CELL_COORD: f32 = 1.0e12;

/// Whether map coordinates `c` (in cells) can be read: finite and within [`MAX_CELL_COORD`].
#[inline]
fn on_map(c: Vec3) -> bool {
    c.is_finite() && c.abs().max_element() < MAX_CELL_COORD
}

/// Contact-shadow bins across the light, in map columns. Their count does not change the
/// parts a query visits much (a bin's parts shrink as the parts per query grow): measured on
/// smooth × 4 strands of one fibre (shading, 2 threads) 1 column 7.6 s, ½ 6.5 s, ¼ 6.9 s; but
/// the memory grows as 1/bin (the dense preset's 1.1 M segments make 13 M parts at a column).
pub const CONTACT_BIN_COLUMNS: f32 = 1.0;

/// The map: geometry, light frame, and the filled cells of the last build.
#[derive(Clone, Debug)]
pub struct LightMap {
    geom: MapGeometry,
    /// World -> map coordinates (the light frame, and for a point light its central
    /// projection).
    proj: Projection,
    inv_ds: f32,
    /// Map metres to cells along X and to columns along Y, Z.
    inv_cell: Vec3,
    model: CountModel,
    /// Unwrapped index ⌊x/ds⌋ of the first slice in light order.
    first_slice: i64,
    /// Unwrapped cell indices (slice, column j, column k) of the filled cells' bounding box
    /// (`lo > hi` when the map is empty).
    hair_lo: [i64; 3],
    hair_hi: [i64; 3],
    /// Column offsets into `cells` (N² + 1 entries; column c = j·N + k).
    col_start: Vec<u32>,
    /// Filled cells grouped by column, each column sorted by relative slice.
    cells: Vec<Cell>,
    /// For each column, one slot per slice from its first to its last filled slice: the index
    /// in `cells` of the last filled cell at or before that slice. Makes a lookup O(1). Sparse
    /// columns (span over 4 slices per filled cell) have none and are read by binary search,
    /// so the slots never exceed 4 per filled cell, whatever N is.
    slots: Vec<u32>,
    /// Per column, what a lookup needs in one 32-byte record (one cache line holds two): its
    /// cells, its slot table, its first slice and its total crossings.
    index: Vec<ColumnIndex>,
    scratch: build::Scratch,
    stats: MapStats,
    /// The exact fibres in front of each vertex, for one-fibre-per-strand hair
    /// ([`LightMap::build_contact`]).
    contact: Option<contact::ContactShadows>,
}

impl LightMap {
    /// An empty map of the given geometry (allocates N² + 1 column offsets).
    pub fn new(geom: MapGeometry, model: CountModel) -> Self {
        let cols = geom.columns_per_axis() as usize * geom.columns_per_axis() as usize;
        Self {
            geom,
            proj: Projection::Parallel {
                frame: LightFrame::new(Vec3::NEG_Y),
            },
            inv_ds: 1.0 / geom.ds_m,
            inv_cell: Vec3::new(
                1.0 / geom.ds_m,
                1.0 / geom.column_m(),
                1.0 / geom.column_m(),
            ),
            model,
            first_slice: 0,
            hair_lo: [i64::MAX; 3],
            hair_hi: [i64::MIN; 3],
            col_start: vec![0; cols + 1],
            cells: Vec::new(),
            slots: Vec::new(),
            index: vec![ColumnIndex::EMPTY; cols],
            scratch: build::Scratch::default(),
            stats: MapStats::default(),
            contact: None,
        }
    }

    /// Builds (or with `None` drops) the map's contact shadows: the fibres of `input` binned in
    /// the map's current light frame (call after [`LightMap::build`], which sets the frame).
    /// Bins are [`CONTACT_BIN_COLUMNS`] columns wide across the light.
    pub fn build_contact(&mut self, input: Option<&contact::ContactInput>) {
        self.contact = input.map(|i| {
            contact::ContactShadows::build(
                i,
                &self.proj,
                CONTACT_BIN_COLUMNS * self.geom.column_m(),
            )
        });
    }

    pub fn geometry(&self) -> MapGeometry {
        self.geom
    }
    pub fn frame(&self) -> LightFrame {
        self.proj.frame()
    }
    pub fn stats(&self) -> &MapStats {
        &self.stats
    }

    /// The map's projection of world points into its light frame.
    pub fn projection(&self) -> &Projection {
        &self.proj
    }

    /// The lateral extent of the filled columns (map metres, Y and Z: low and high corners),
    /// or `None` when the map holds no hair.
    pub(crate) fn hair_extent_m(&self) -> Option<(Vec2, Vec2)> {
        if self.hair_lo[1] > self.hair_hi[1] {
            return None;
        }
        let dc = self.geom.column_m();
        let lo = Vec2::new(self.hair_lo[1] as f32, self.hair_lo[2] as f32) * dc;
        let hi = Vec2::new(self.hair_hi[1] as f32 + 1.0, self.hair_hi[2] as f32 + 1.0) * dc;
        Some((lo, hi))
    }

    /// Each sample's clamped ā_f as the last build's fill evaluated it (NaN where it did not).
    pub(crate) fn sample_forward_a(&self) -> &[Vec3] {
        &self.scratch.forward_a
    }

    /// Cell-space coordinates (unwrapped: slices along X, columns along Y and Z) of a world
    /// point.
    #[inline]
    fn cell_coords(&self, p: Vec3) -> Vec3 {
        self.proj.point(p) * self.inv_cell
    }

    /// A key that orders points by the map column they read (the first of their bilinear
    /// taps), so that lookups made in key order walk the map's memory in order; `u32::MAX` for
    /// points off the map. Any order gives the same lookups; this one only makes them faster.
    pub fn lookup_order_key(&self, p: Vec3) -> u32 {
        let c = self.cell_coords(p);
        if !on_map(c) {
            return u32::MAX;
        }
        self.column((c.y - 0.5).floor() as i64, (c.z - 0.5).floor() as i64) as u32
    }
}

#[cfg(test)]
mod tests;
