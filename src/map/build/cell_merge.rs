//! One column's cells as its pieces arrive in (slice, piece order): a new slice opens a cell,
//! the same slice adds its share to it, and the depth histogram of the cell's crossings is
//! closed into its CDF (`depth.rs`) when the next cell opens. Then the sweep of Bertails 2005
//! Eq. 3 in its dual-scattering form (Zinke 2008 §4): running sums from the light,
//!
//!   n_k = Σ_{i ≤ k} n_i,  loss_k = Σ_{i ≤ k} n_i(1 − ā_f,i),  σ²_k = Σ_{i ≤ k} n_i β̄²_f,i,
//!
//! so each cell holds what a ray has crossed up to its far face; the lookup takes
//! exp(−n) and exp(−loss).

use super::depth::{depth_cdf, spread_depth};
use super::piece::PieceStats;
use crate::map::{Cell, DEPTH_BINS};
use glam::Vec3;

/// One column's cells as pieces are added in order: a new slice opens a cell, the same slice
/// adds to it, and where along the light its crossings lie is kept as a histogram over
/// [`DEPTH_BINS`] sub-slices.
pub(super) struct CellMerge<'a> {
    cells: &'a mut [Cell],
    /// Cells opened so far.
    open: usize,
    hist: [f32; DEPTH_BINS],
}

impl<'a> CellMerge<'a> {
    /// A merge into `cells`, as many as the distinct slices it will be given.
    pub(super) fn new(cells: &'a mut [Cell]) -> Self {
        CellMerge {
            cells,
            open: 0,
            hist: [0.0; DEPTH_BINS],
        }
    }

    /// Adds share `weight` of a piece carrying `st` and lying over `depth` of its cell at
    /// `slice` (slices in non-decreasing order).
    #[inline]
    pub(super) fn add(&mut self, slice: u32, st: &PieceStats, weight: f32, depth: [u16; 2]) {
        let n = st.n * weight;
        let loss = (Vec3::from(st.loss) * weight).to_array();
        let sigma2 = (Vec3::from(st.sigma2) * weight).to_array();
        let vf = st.volume_fraction * weight;
        match self.open.checked_sub(1).map(|w| &mut self.cells[w]) {
            Some(m) if m.slice == slice => {
                m.n_sum += n;
                m.volume_fraction += vf;
                for ch in 0..3 {
                    m.loss[ch] += loss[ch];
                    m.sigma2[ch] += sigma2[ch];
                }
            }
            last => {
                if let Some(m) = last {
                    m.depth_cdf = depth_cdf(&self.hist);
                }
                self.hist = [0.0; DEPTH_BINS];
                self.cells[self.open] = Cell {
                    slice,
                    n_sum: n,
                    loss,
                    sigma2,
                    volume_fraction: vf,
                    depth_cdf: [0; DEPTH_BINS - 1],
                };
                self.open += 1;
            }
        }
        spread_depth(&mut self.hist, depth, n);
    }

    /// Closes the last cell and sweeps: running sums of crossings, losses and variance; each
    /// cell then holds what has been crossed up to its far face (the lookup takes
    /// exponentials).
    pub(super) fn finish(self) {
        debug_assert_eq!(self.open, self.cells.len());
        let cells = &mut self.cells[..self.open];
        if let Some(m) = cells.last_mut() {
            m.depth_cdf = depth_cdf(&self.hist);
        }
        let (mut n_sum, mut loss, mut var) = (0.0f32, [0.0f32; 3], [0.0f32; 3]);
        for c in cells.iter_mut() {
            n_sum += c.n_sum;
            c.n_sum = n_sum;
            for ch in 0..3 {
                loss[ch] += c.loss[ch];
                var[ch] += c.sigma2[ch];
            }
            c.loss = loss;
            c.sigma2 = var;
        }
    }
}
