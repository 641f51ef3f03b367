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
//! compressed-row layout: a counting sort of the samples by column (N² counters, the only
//! per-frame cost that depends on N) followed, per column and in parallel, by a sort of its
//! samples along X (relative to the first slice, wrapping modulo N as in Bertails Figure 3),
//! a merge of samples falling in the same cell, and the sweep of Eq. 3. An empty cell has the
//! value of the last filled cell before it in its column (Bertails §3.2: "otherwise cell (i,j,k)
//! is given the transmittance prevTrans"); a lookup finds it by binary search. A dense N³ grid
//! at N = 128 would clear and sweep 2M cells (56 MB at 7 floats) each frame for ~30K filled.
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
//! ray average (by Jensen); `tests/map_reference.rs` measures both against ray shooting.
//!
//! ## Where a value lives, and the filter that reads it
//! A cell stores the light *leaving its far face* (the face away from the light), i.e. after
//! all crossings in that cell; this is Bertails' "light received by its back side". Along X the
//! filter interpolates between the far faces of cells i−1 and i (Bertails §3.3), which is the
//! light entering and leaving cell i: exact at both faces. Across the light (Y, Z) a column's
//! value is its average over the column, so the filter interpolates between column centres.
//! A slab of hair perpendicular to L then reads exactly 1 in front of it and exactly the
//! analytic attenuation behind it (`tests/map_slab.rs`).

mod budget;
mod build;
mod lookup;
pub mod reference;

pub use build::{CountModel, MapBuildInput, MapStats};

use glam::Vec3;

/// Size of the map: N cells per axis, each `ds_m` metres wide.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapGeometry {
    /// Cells per axis.
    pub n: u32,
    /// Cell size in metres.
    pub ds_m: f32,
}

impl MapGeometry {
    /// A map that spans `span_m` with `n` cells per axis.
    pub fn with_resolution(span_m: f32, n: u32) -> Self {
        let n = n.max(1);
        Self {
            n,
            ds_m: span_m / n as f32,
        }
    }

    /// A map sized from the scene (Bertails §2.2): span 2·lmax + hmax, and a cell about twice
    /// the spacing between neighbouring render strands, so that a cell averages a few strands
    /// (finer cells resolve single render strands, which then shadow themselves; coarser ones
    /// blur wisps together). For the presets (3,350 strands: 3.7 mm spacing) this gives
    /// N = 129, Bertails' choice (§5: "a 128 × 128 resolution was sufficient"); `wisp bench`
    /// measures the error against N.
    pub fn for_scene(max_length_m: f32, head_size_m: f32, strand_spacing_m: f32) -> Self {
        let span = Self::span_m(max_length_m, head_size_m);
        let n = (span / (2.0 * strand_spacing_m.max(1e-6)))
            .ceil()
            .clamp(8.0, 1024.0) as u32;
        Self::with_resolution(span, n)
    }

    /// The smallest span that always holds the hair: 2·lmax + hmax (Bertails §2.2), plus 2%
    /// so that a strand pulled exactly straight does not land on the wrap boundary.
    pub fn span_m(max_length_m: f32, head_size_m: f32) -> f32 {
        1.02 * (2.0 * max_length_m + head_size_m)
    }
}

/// Orthonormal light frame: `x` is the direction the light travels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightFrame {
    pub x: Vec3,
    pub y: Vec3,
    pub z: Vec3,
}

impl LightFrame {
    /// The frame for light travelling along `l` (normalised here; a zero vector falls back to
    /// light travelling down, −Y).
    pub fn new(l: Vec3) -> Self {
        let x = l.normalize_or(Vec3::NEG_Y);
        let (y, z) = x.any_orthonormal_pair();
        Self { x, y, z }
    }

    /// World point -> map coordinates in metres.
    #[inline]
    pub fn to_map(&self, p: Vec3) -> Vec3 {
        Vec3::new(self.x.dot(p), self.y.dot(p), self.z.dot(p))
    }

    /// Map coordinates in metres -> world point.
    #[inline]
    pub fn to_world(&self, m: Vec3) -> Vec3 {
        self.x * m.x + self.y * m.y + self.z * m.z
    }
}

/// One filled cell after the sweep: the light leaving its far face, and its hair content.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Cell {
    /// Slice index relative to the first slice (0..N); `u32::MAX` marks a merged-away entry.
    pub slice: u32,
    /// Column index (j·N + k).
    pub col: u32,
    /// Index of the (first) sample that made the cell: the tie-break of the sort.
    pub seq: u32,
    /// Expected crossings inside this cell (before the sweep), then exp(−Σ n) (after).
    pub direct: f32,
    /// Σ n·(1 − ā_f) (or Σ n·(−ln ā_f)) inside the cell, then T_f leaving the cell, RGB.
    pub tf: [f32; 3],
    /// Σ n·β̄_f² inside the cell, then σ̄f² leaving the cell (rad²), RGB.
    pub sigma2: [f32; 3],
    /// Hair volume fraction of the cell (fibre volume / cell volume).
    pub volume_fraction: f32,
}

/// The map: geometry, light frame, and the filled cells of the last build.
#[derive(Clone, Debug)]
pub struct LightMap {
    geom: MapGeometry,
    frame: LightFrame,
    inv_ds: f32,
    model: CountModel,
    /// Unwrapped index ⌊x/ds⌋ of the first slice in light order.
    first_slice: i64,
    /// Column offsets into `cells` (N² + 1 entries; column c = j·N + k).
    col_start: Vec<u32>,
    /// Filled cells grouped by column, each column sorted by relative slice.
    cells: Vec<Cell>,
    /// Per column, offsets into `slots` (N² + 1 entries).
    slot_start: Vec<u32>,
    /// For each column, one slot per slice from its first to its last filled slice: the index
    /// in `cells` of the last filled cell at or before that slice. Makes a lookup O(1); its
    /// size is the sum of the filled columns' spans, never N³.
    slots: Vec<u32>,
    scratch: build::Scratch,
    stats: MapStats,
}

impl LightMap {
    /// An empty map of the given geometry (allocates N² + 1 column offsets).
    pub fn new(geom: MapGeometry, model: CountModel) -> Self {
        let cols = geom.n as usize * geom.n as usize;
        Self {
            geom,
            frame: LightFrame::new(Vec3::NEG_Y),
            inv_ds: 1.0 / geom.ds_m,
            model,
            first_slice: 0,
            col_start: vec![0; cols + 1],
            cells: Vec::new(),
            slot_start: vec![0; cols + 1],
            slots: Vec::new(),
            scratch: build::Scratch::default(),
            stats: MapStats::default(),
        }
    }

    pub fn geometry(&self) -> MapGeometry {
        self.geom
    }
    pub fn frame(&self) -> LightFrame {
        self.frame
    }
    pub fn stats(&self) -> &MapStats {
        &self.stats
    }

    /// Cell-space coordinates (unwrapped, in cells) of a world point.
    #[inline]
    fn cell_coords(&self, p: Vec3) -> Vec3 {
        self.frame.to_map(p) * self.inv_ds
    }

    /// Column index of unwrapped (j, k).
    #[inline]
    fn column(&self, j: i64, k: i64) -> usize {
        let n = self.geom.n as i64;
        (j.rem_euclid(n) * n + k.rem_euclid(n)) as usize
    }

    /// The filled cells of column `c`, sorted by slice (merged-away entries at the end).
    #[inline]
    #[cfg(test)]
    fn column_cells(&self, c: usize) -> &[Cell] {
        &self.cells[self.col_start[c] as usize..self.col_start[c + 1] as usize]
    }

    /// Index in `cells` of the last filled cell of column `c` at or before relative slice
    /// `rel`, or `None` when the column has no cell that early.
    #[inline]
    fn last_at_or_before(&self, c: usize, rel: u32) -> Option<usize> {
        let (s0, s1) = (self.slot_start[c] as usize, self.slot_start[c + 1] as usize);
        if s0 == s1 {
            return None;
        }
        let base = self.cells[self.col_start[c] as usize].slice;
        if rel < base {
            return None;
        }
        let off = (rel - base) as usize;
        Some(self.slots[(s0 + off).min(s1 - 1)] as usize)
    }
}

#[cfg(test)]
mod tests;
