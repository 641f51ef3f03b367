//! Building the map each frame: fill (Bertails 2005 §3.1) and transmittance sweep (§3.2, Eq. 3).
//!
//! 1. Fill, in parallel over samples: each sample's cell and its contribution (expected fibre
//!    crossings, their forward-scattering statistics, hair volume).
//! 2. Counting sort by column (sequential, O(samples + N²)), which keeps sample order inside a
//!    column.
//! 3. Per column, in parallel: sort along the light (ties by sample index, so the float sums
//!    below always add in the same order whatever the thread count), merge samples of one cell,
//!    and sweep from the first slice accumulating Eq. 3 in its dual-scattering form.

use super::{Cell, LightFrame, LightMap};
use crate::fiber::Fiber;
use glam::Vec3;
use rayon::prelude::*;

/// How expected crossing counts become transmittance (see the module doc of `map`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CountModel {
    /// Average over Poisson-distributed crossings: T_f = exp(−n̄(1 − ā_f)), direct = exp(−n̄).
    #[default]
    Poisson,
    /// A ray meeting exactly the mean count: T_f = ā_f^n̄, direct = 0^n̄ read as exp(−n̄).
    MeanCount,
}

/// What the map is built from: render-strand samples (world) and the fibre they are made of.
pub struct MapBuildInput<'a> {
    /// Sample positions, metres (world).
    pub positions: &'a [Vec3],
    /// Unit tangents at the samples.
    pub tangents: &'a [Vec3],
    /// Hair length each sample stands for, metres.
    pub lengths_m: &'a [f32],
    /// Real fibres per render strand.
    pub fibers_per_strand: f32,
    /// Direction the light travels (need not be normalised).
    pub light_dir: Vec3,
    /// The fibre (radius and forward-scattering statistics).
    pub fiber: &'a Fiber,
}

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

/// A sample piece before sorting.
#[derive(Clone, Copy, Debug, Default)]
struct Entry {
    /// Column index, or `u32::MAX` for a skipped (non-finite) sample.
    col: u32,
    /// Unwrapped slice ⌊x/ds⌋.
    slice: i64,
    cell: Cell,
}

/// Bounding box of filled cells in unwrapped cell indices (x, y, z).
#[derive(Clone, Copy, Debug)]
struct Extent {
    lo: [i64; 3],
    hi: [i64; 3],
}

impl Extent {
    const EMPTY: Extent = Extent {
        lo: [i64::MAX; 3],
        hi: [i64::MIN; 3],
    };

    #[inline]
    fn include(&mut self, c: [i64; 3]) {
        for ((lo, hi), v) in self.lo.iter_mut().zip(&mut self.hi).zip(c) {
            *lo = (*lo).min(v);
            *hi = (*hi).max(v);
        }
    }

    fn union(a: Extent, b: Extent) -> Extent {
        if b.lo[0] > b.hi[0] {
            return a; // b is empty
        }
        let mut u = a;
        u.include(b.lo);
        u.include(b.hi);
        u
    }
}

/// Reusable buffers: after the first frame, a build allocates nothing.
#[derive(Clone, Debug, Default)]
pub(super) struct Scratch {
    entries: Vec<Entry>,
    col_count: Vec<u32>,
}

/// Most pieces a sample is split into (a sample longer than 8 cells still makes 8).
const MAX_PIECES: usize = 8;

/// Coordinates beyond this many cells are treated as invalid (keeps `as i64` well defined).
const MAX_CELL_COORD: f32 = 1.0e12;

impl LightMap {
    /// Rebuilds the map for `input` (fill + sweep). Allocation-free once warmed up.
    pub fn build(&mut self, input: &MapBuildInput) {
        self.frame = LightFrame::new(input.light_dir);
        let n = self.geom.n as i64;
        let ds = self.geom.ds_m;
        let r = input.fiber.params().radius_m;
        // n = F·ℓ·2r·sinψ / ds² crossings; volume fraction = F·ℓ·πr² / ds³.
        let crossing_scale = input.fibers_per_strand * 2.0 * r / (ds * ds);
        let volume_scale = input.fibers_per_strand * std::f32::consts::PI * r * r / (ds * ds * ds);
        let count = input
            .positions
            .len()
            .min(input.tangents.len())
            .min(input.lengths_m.len());
        let frame = self.frame;
        let inv_ds = self.inv_ds;
        let model = self.model;
        let fiber = input.fiber;
        let to_light = -frame.x;

        // 1. Fill. A sample stands for a piece of strand of length ℓ along its tangent; when ℓ
        // exceeds a cell, it is split into `pieces` equal parts spread along the tangent,
        // so a strand fills every cell it passes through instead of a dotted line of them (at
        // the default resolution samples are 11 mm apart and cells 7.4 mm).
        let max_len = input.lengths_m[..count]
            .iter()
            .copied()
            .filter(|l| l.is_finite())
            .fold(0.0f32, f32::max);
        let pieces = ((max_len / ds).ceil() as usize).clamp(1, MAX_PIECES);
        let entries = &mut self.scratch.entries;
        entries.resize(count * pieces, Entry::default());
        // Per sample: the fibre's per-crossing statistics once, then its pieces. The extent of
        // the filled cells (first slice, overflow check) comes from an exact min/max reduce,
        // so the reduction order does not matter.
        let extent = entries
            .par_chunks_mut(pieces)
            .enumerate()
            .with_min_len(512)
            .map(|(s, out)| {
                let u = input.tangents[s];
                let len_total = input.lengths_m[s];
                let p0 = frame.to_map(input.positions[s]) * inv_ds;
                if !(p0.abs().max_element() < MAX_CELL_COORD
                    && u.is_finite()
                    && len_total.is_finite()
                    && len_total >= 0.0)
                {
                    out.iter_mut().for_each(|e| e.col = u32::MAX);
                    return Extent::EMPTY;
                }
                let cos_psi = u.dot(frame.x).clamp(-1.0, 1.0);
                let sin_psi = (1.0 - cos_psi * cos_psi).max(0.0).sqrt();
                let len = len_total / pieces as f32;
                let crossings = crossing_scale * len * sin_psi;
                let fs = fiber.forward_scatter(u.dot(to_light).clamp(-1.0, 1.0));
                let a = fs.a_f.clamp(Vec3::ZERO, Vec3::ONE);
                let loss = match model {
                    CountModel::Poisson => Vec3::ONE - a,
                    CountModel::MeanCount => -a.max(Vec3::splat(1e-30)).ln(),
                };
                let cell = Cell {
                    slice: 0,
                    col: 0,
                    seq: 0,
                    direct: crossings,
                    tf: (loss * crossings).to_array(),
                    sigma2: (fs.beta_f2 * crossings).to_array(),
                    volume_fraction: volume_scale * len,
                };
                let u_cells = frame.to_map(u) * inv_ds;
                let mut ext = Extent::EMPTY;
                for (q, e) in out.iter_mut().enumerate() {
                    let along = ((q as f32 + 0.5) / pieces as f32 - 0.5) * len_total;
                    // The piece's offset, in cells, is rounded to 1/1024 of a cell (7 µm at the
                    // default size): then moving the hair by whole cells moves every piece by
                    // exactly whole cells too (adding numbers on that grid is exact in f32),
                    // which keeps the modulo map's translation invariance exact.
                    let offset = (u_cells * along * 1024.0).round() / 1024.0;
                    let c = (p0 + offset).floor();
                    let (i, j, k) = (c.x as i64, c.y as i64, c.z as i64);
                    ext.include([i, j, k]);
                    e.col = (j.rem_euclid(n) * n + k.rem_euclid(n)) as u32;
                    e.slice = i;
                    e.cell = Cell {
                        seq: (s * pieces + q) as u32,
                        ..cell
                    };
                }
                ext
            })
            .reduce(|| Extent::EMPTY, Extent::union);
        let filled_entries = entries.len() - entries.iter().filter(|e| e.col == u32::MAX).count();
        self.first_slice = if filled_entries > 0 { extent.lo[0] } else { 0 };
        let overflow = filled_entries > 0 && (0..3).any(|a| extent.hi[a] - extent.lo[a] >= n);
        // A non-finite sample invalidates all its pieces together.
        let samples = filled_entries / pieces;

        // 2. Counting sort by column.
        let cols = (n * n) as usize;
        let col_count = &mut self.scratch.col_count;
        col_count.clear();
        col_count.resize(cols, 0);
        for e in entries.iter().filter(|e| e.col != u32::MAX) {
            col_count[e.col as usize] += 1;
        }
        let mut acc = 0u32;
        for (start, count) in self.col_start.iter_mut().zip(col_count.iter_mut()) {
            *start = acc;
            acc += *count;
            *count = *start; // becomes the write cursor
        }
        self.col_start[cols] = acc;
        self.cells.resize(filled_entries, Cell::default());
        let first = self.first_slice;
        for e in entries.iter().filter(|e| e.col != u32::MAX) {
            let at = col_count[e.col as usize] as usize;
            col_count[e.col as usize] += 1;
            let mut cell = e.cell;
            // Relative slice, wrapping modulo N (Bertails Figure 3); the sample index moves to
            // the sort key below.
            cell.slice = (e.slice - first).rem_euclid(n) as u32;
            cell.col = e.col;
            self.cells[at] = cell;
        }

        // 3. Per column: sort, merge, sweep. The key (slice, sample index) is unique, so an
        // unstable (allocation-free) sort gives one order whatever the thread count.
        let (filled, ncols) = self
            .cells
            .par_chunk_by_mut(|a, b| a.col == b.col)
            .map(|col| {
                col.sort_unstable_by_key(|c| (c.slice, c.seq));
                (sweep_column(col), 1usize)
            })
            .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));

        // Slot tables: per column, the last filled cell at or before each slice of its span.
        self.slots.clear();
        for c in 0..cols {
            self.slot_start[c] = self.slots.len() as u32;
            let (a, b) = (self.col_start[c] as usize, self.col_start[c + 1] as usize);
            if a == b {
                continue;
            }
            let base = self.cells[a].slice;
            let mut idx = a;
            for cell in a..b {
                let s = self.cells[cell].slice;
                if s == u32::MAX {
                    break;
                }
                while (self.slots.len() - self.slot_start[c] as usize) < (s - base) as usize {
                    self.slots.push(idx as u32);
                }
                self.slots.push(cell as u32);
                idx = cell;
            }
        }
        self.slot_start[cols] = self.slots.len() as u32;

        let mut peak = 0.0f32;
        for c in self.cells.iter().filter(|c| c.slice != u32::MAX) {
            peak = peak.max(c.volume_fraction);
        }
        self.stats = MapStats {
            samples,
            skipped: count - samples,
            filled_cells: filled,
            columns: ncols,
            peak_volume_fraction: peak,
            hair_volume_m3: filled as f32 * ds * ds * ds,
            overflow,
        };
    }
}

/// Merges the cells of one column (sorted by slice) and sweeps them from the light (Bertails
/// Eq. 3 with the dual-scattering quantities). Returns the number of distinct cells.
fn sweep_column(col: &mut [Cell]) -> usize {
    // Merge runs of equal slice into the front of the slice.
    let mut w = 0usize;
    for r in 0..col.len() {
        if r > 0 && col[r].slice == col[w - 1].slice {
            let c = col[r];
            let m = &mut col[w - 1];
            m.direct += c.direct;
            m.volume_fraction += c.volume_fraction;
            for ch in 0..3 {
                m.tf[ch] += c.tf[ch];
                m.sigma2[ch] += c.sigma2[ch];
            }
        } else {
            col[w] = col[r];
            w += 1;
        }
    }
    for c in &mut col[w..] {
        c.slice = u32::MAX;
    }
    // Sweep: running sums of crossings, losses and variance; each cell then holds what leaves
    // its far face.
    let (mut n_sum, mut loss, mut var) = (0.0f32, [0.0f32; 3], [0.0f32; 3]);
    for c in &mut col[..w] {
        n_sum += c.direct;
        c.direct = (-n_sum).exp();
        for ch in 0..3 {
            loss[ch] += c.tf[ch];
            var[ch] += c.sigma2[ch];
            c.tf[ch] = (-loss[ch]).exp();
            c.sigma2[ch] = var[ch];
        }
    }
    w
}
