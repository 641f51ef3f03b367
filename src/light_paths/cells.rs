//! The hair as pieces of fibre filed by cell (`light_paths` module doc, step 1): what a light
//! path collides with, and where light is kept for the gather.
//!
//! A grid of `cell_m` cubes covers the hair with one empty cell of margin on each side (at
//! most [`MAX_CELLS_PER_AXIS`] a side: a larger extent gets larger cells). Each render-strand
//! point stands for `lengths_m × fibers_per_strand` metres of fibre along its tangent; it is
//! cut into k = ⌈ℓ / (cell_m/2)⌉ ≤ 64 equal pieces, each filed under the cell of its middle, so
//! a piece never spans more than two cells and the cells' fibre follows the strand. The pieces
//! are sorted by cell (a counting sort: each cell's pieces in the points' order, so the same
//! input gives the same layout). Each cell keeps its longest piece ℓ_max, the bound of the
//! delta-tracking majorant (`trace.rs`).
//!
//! Light is kept only in the cells a seen point can gather from: the 3 × 3 × 3 around a cell
//! holding fibre (a point picks one of the 2 × 2 × 2 cells around it, all within one cell of
//! its own). Those cells are numbered as *slots* in cell order. One bit per cell says whether
//! a path's step there reads anything (pieces, a slot or a solid): most steps cross empty
//! space (94% on the smooth dance), which then costs one bit read from a small array.

use glam::{IVec3, UVec3, Vec3, Vec4};
use rayon::prelude::*;

/// Most cells per axis (a larger extent gets larger cells).
pub(super) const MAX_CELLS_PER_AXIS: usize = 256;

/// [`Cells::slot`] of a cell no point gathers from.
pub(crate) const NO_SLOT: u32 = u32::MAX;

/// Most pieces one point is cut into.
const MAX_PIECES_PER_POINT: usize = 64;

/// The render strands' points the light paths cross: each stands for `lengths_m` metres of
/// every one of its strand's `fibers_per_strand` fibres, along its unit tangent. The three
/// slices are read up to the shortest; a point with a non-finite value or a length ≤ 0 is
/// skipped.
#[derive(Clone, Copy, Debug)]
pub struct StrandPoints<'a> {
    /// Positions, metres.
    pub positions: &'a [Vec3],
    /// Tangents (normalised here; a zero tangent is skipped).
    pub tangents: &'a [Vec3],
    /// Length of strand each point stands for, metres.
    pub lengths_m: &'a [f32],
    /// Fibres per render strand.
    pub fibers_per_strand: f32,
}

impl StrandPoints<'_> {
    /// Points readable from all three slices.
    fn len(&self) -> usize {
        self.positions
            .len()
            .min(self.tangents.len())
            .min(self.lengths_m.len())
    }

    /// Whether point `i` is finite with a positive length.
    fn usable(&self, i: usize) -> bool {
        self.positions[i].is_finite()
            && self.tangents[i].is_finite()
            && self.lengths_m[i].is_finite()
            && self.lengths_m[i] > 0.0
    }

    /// The usable points' indices, in order.
    fn usable_indices(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.len()).filter(|&i| self.usable(i))
    }
}

/// One piece of fibre before filing: its cell, unit tangent and metres of fibre.
type Piece = (u32, Vec3, f32);

/// The hair as fibre pieces filed by cell (module doc).
#[derive(Clone, Debug, Default)]
pub(crate) struct Cells {
    pub(crate) origin: Vec3,
    pub(crate) cell_m: f32,
    pub(crate) dims: UVec3,
    /// Per cell, its pieces' range: `starts[c]..starts[c + 1]`.
    pub(crate) starts: Vec<u32>,
    /// Per piece, by cell: its unit tangent and its length of fibre (metres × fibres) over
    /// its cell's longest (in `w`): what a tentative collision reads, in one load.
    pub(crate) pieces: Vec<Vec4>,
    /// Per cell, the longest piece (metres of fibre).
    pub(crate) longest: Vec<f32>,
    /// Per cell, whether it lies wholly inside a solid (head, body): light that enters it is
    /// absorbed. Empty: no solids.
    pub(crate) solid: Vec<bool>,
    /// Per cell, its place among the cells a point can gather from (module doc), or
    /// [`NO_SLOT`]: light is kept only there.
    pub(crate) slot: Vec<u32>,
    pub(crate) slots: usize,
    /// One bit per cell (cell `i` is bit `i % 64` of word `i / 64`): set where a path's
    /// step reads anything (pieces, a slot or a solid).
    pub(crate) busy: Vec<u64>,
}

impl Cells {
    /// Files the pieces of fibre `points` stand for in cells of `cell_m` or larger (module
    /// doc). `None` when no point is usable or `cell_m` or the fibre count is not positive.
    pub(crate) fn build(points: &StrandPoints, cell_m: f32) -> Option<Cells> {
        let mut cells = Cells::covering(points, cell_m)?;
        let pieces = cells.cut(points);
        cells.file(&pieces);
        cells.number_slots();
        cells.scale_to_longest();
        Some(cells)
    }

    /// The empty grid over the usable points' reach (half their length each way), with one
    /// cell of margin; cells of `cell_m`, enlarged to keep within [`MAX_CELLS_PER_AXIS`].
    fn covering(points: &StrandPoints, cell_m: f32) -> Option<Cells> {
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for i in points.usable_indices() {
            let reach = Vec3::splat(0.5 * points.lengths_m[i]);
            lo = lo.min(points.positions[i] - reach);
            hi = hi.max(points.positions[i] + reach);
        }
        if !(lo.is_finite() && hi.is_finite() && cell_m > 0.0 && points.fibers_per_strand > 0.0) {
            return None;
        }
        let extent = hi - lo;
        let cell_m = cell_m.max(extent.max_element() / (MAX_CELLS_PER_AXIS - 2) as f32);
        Some(Cells {
            origin: lo - Vec3::splat(cell_m),
            cell_m,
            dims: ((extent / cell_m).ceil() + Vec3::splat(2.0)).as_uvec3(),
            ..Default::default()
        })
    }

    /// The points cut into pieces of at most half a cell, each with the cell of its middle,
    /// in the points' order.
    fn cut(&self, points: &StrandPoints) -> Vec<Piece> {
        let half = 0.5 * self.cell_m;
        let mut pieces = Vec::new();
        for i in points.usable_indices() {
            let (p, len) = (points.positions[i], points.lengths_m[i]);
            let u = points.tangents[i].normalize_or_zero();
            if u == Vec3::ZERO {
                continue;
            }
            let k = ((len / half).ceil() as usize).clamp(1, MAX_PIECES_PER_POINT);
            let step = len / k as f32;
            for j in 0..k {
                let at = p + u * (step * (j as f32 + 0.5) - 0.5 * len);
                if let Some(c) = self.cell_of(at) {
                    pieces.push((c as u32, u, step * points.fibers_per_strand));
                }
            }
        }
        pieces
    }

    /// Sorts `pieces` by cell (counting sort, stable): fills `starts`, `pieces` (their
    /// lengths in `w`, over the longest once [`Cells::scale_to_longest`] has run)
    /// and each cell's `longest`.
    fn file(&mut self, pieces: &[Piece]) {
        let count = self.count();
        let mut starts = vec![0u32; count + 1];
        for &(c, _, _) in pieces {
            starts[c as usize + 1] += 1;
        }
        for c in 0..count {
            starts[c + 1] += starts[c];
        }
        let mut cursor = starts.clone();
        self.pieces = vec![Vec4::ZERO; pieces.len()];
        self.longest = vec![0.0; count];
        for &(c, u, len) in pieces {
            let at = &mut cursor[c as usize];
            self.pieces[*at as usize] = u.extend(len);
            *at += 1;
            let l = &mut self.longest[c as usize];
            *l = l.max(len);
        }
        self.starts = starts;
    }

    /// Numbers the cells within one of a filled cell as slots, in cell order, and marks busy
    /// the slots and the filled cells (module doc).
    fn number_slots(&mut self) {
        let count = self.count();
        let mut near = vec![false; count];
        let d = self.dims.as_ivec3();
        for i in self.filled() {
            let c = self.coords(i).as_ivec3();
            for k in 0..27 {
                let n = c + IVec3::new(k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1);
                if n.cmpge(IVec3::ZERO).all() && n.cmplt(d).all() {
                    near[self.index(n.as_uvec3())] = true;
                }
            }
        }
        let mut slots = 0u32;
        self.slot = near
            .iter()
            .map(|&n| {
                if !n {
                    return NO_SLOT;
                }
                slots += 1;
                slots - 1
            })
            .collect();
        self.slots = slots as usize;
        self.busy = vec![0; count.div_ceil(64)];
        for (i, &near) in near.iter().enumerate() {
            if near || self.starts[i + 1] > self.starts[i] {
                self.mark_busy(i);
            }
        }
    }

    /// Scales each piece's length by its cell's longest: the acceptance of a tentative
    /// collision (`trace.rs`) is then one product.
    fn scale_to_longest(&mut self) {
        for c in 0..self.count() {
            let longest = self.longest[c];
            for piece in &mut self.pieces[self.starts[c] as usize..self.starts[c + 1] as usize] {
                piece.w /= longest;
            }
        }
    }

    /// The cell holding `p`, or `None` outside the grid.
    pub(crate) fn cell_of(&self, p: Vec3) -> Option<usize> {
        let q = (p - self.origin) / self.cell_m;
        if !(q.x >= 0.0 && q.y >= 0.0 && q.z >= 0.0) {
            return None;
        }
        let (x, y, z) = (q.x as u32, q.y as u32, q.z as u32);
        let d = self.dims;
        (x < d.x && y < d.y && z < d.z).then(|| self.index(UVec3::new(x, y, z)))
    }

    /// The index of the cell at coordinates `c` (x fastest, then y, then z).
    #[inline]
    pub(crate) fn index(&self, c: UVec3) -> usize {
        ((c.z * self.dims.y + c.y) * self.dims.x + c.x) as usize
    }

    /// The coordinates of cell `i` ([`Cells::index`]'s inverse).
    pub(crate) fn coords(&self, i: usize) -> UVec3 {
        let (i, d) = (i as u32, self.dims);
        UVec3::new(i % d.x, (i / d.x) % d.y, i / (d.x * d.y))
    }

    /// Number of cells.
    pub(crate) fn count(&self) -> usize {
        (self.dims.x * self.dims.y * self.dims.z) as usize
    }

    /// The cells holding a piece of fibre, in cell order.
    pub(crate) fn filled(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.count()).filter(|&i| self.starts[i + 1] > self.starts[i])
    }

    /// Whether a path's step through cell `index` reads anything ([`Cells::busy`]).
    #[inline]
    pub(crate) fn is_busy(&self, index: usize) -> bool {
        self.busy[index / 64] >> (index % 64) & 1 != 0
    }

    fn mark_busy(&mut self, index: usize) {
        self.busy[index / 64] |= 1 << (index % 64);
    }

    /// Marks the cells whose centre lies deeper than half their diagonal inside a solid
    /// (`depth_m(p)`: how deep `p` lies inside one, metres, 0 outside), so wholly inside. Only
    /// the cells whose centres lie in one of the boxes `within` (lowest and highest corners,
    /// metres), which hold every point of positive depth, are asked.
    pub(super) fn mark_solids(
        &mut self,
        depth_m: &(impl Fn(Vec3) -> f32 + Sync),
        within: &[(Vec3, Vec3)],
    ) {
        let half_diagonal = 0.5 * 3f32.sqrt() * self.cell_m;
        let mut asked = vec![false; self.count()];
        let top = self.dims.as_vec3() - Vec3::ONE;
        for &(lo, hi) in within {
            // Cells whose centre origin + (c + ½)·cell_m may lie in the box.
            let to_cell = |p: Vec3| (p - self.origin) / self.cell_m - Vec3::splat(0.5);
            let (a, b) = (to_cell(lo).floor(), to_cell(hi).ceil());
            if !(a.cmple(top).all() && b.cmpge(Vec3::ZERO).all()) {
                continue;
            }
            let (a, b) = (a.max(Vec3::ZERO).as_uvec3(), b.min(top).as_uvec3());
            for z in a.z..=b.z {
                for y in a.y..=b.y {
                    let row = self.index(UVec3::new(a.x, y, z));
                    asked[row..=row + (b.x - a.x) as usize].fill(true);
                }
            }
        }
        let cells = &*self;
        let asked: Vec<usize> = (0..self.count()).filter(|&i| asked[i]).collect();
        let solid: Vec<bool> = asked
            .par_iter()
            .map(|&i| {
                let centre = cells.origin + (cells.coords(i).as_vec3() + 0.5) * cells.cell_m;
                depth_m(centre) > half_diagonal
            })
            .collect();
        self.solid = vec![false; self.count()];
        for (&i, &s) in asked.iter().zip(&solid) {
            if s {
                self.solid[i] = true;
                self.mark_busy(i);
            }
        }
    }
}
