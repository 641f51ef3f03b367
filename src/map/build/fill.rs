//! Phase 1 of the build (Bertails 2005 §3.1): each sample's statistics, once, and its pieces,
//! in parallel over samples.
//!
//! A sample stands for a piece of strand of length ℓ along its tangent u, made of F fibres of
//! radius r. Over a column of cross-section dc² it adds, per piece of length ℓ/P,
//!
//!   n = F·(ℓ/P)·2r·sin ψ / dc²   expected crossings (ψ: angle between u and the light),
//!   n(1 − ā_f(θ)) and n·β̄_f²(θ)  their losses and variance (Zinke 2008 Eqs. 6, 19, 20),
//!   F·(ℓ/P)·πr² / (ds·dc²)       hair volume fraction,
//!
//! with the central projection's lateral scale for a point light (`Projection::strand`). A
//! sample longer than a cell is split into P = ⌈ℓ_max / ds⌉ ≤ [`MAX_PIECES`] equal pieces along
//! u, so a strand fills every cell it passes through instead of a dotted line of them (at the
//! default resolution samples are 11 mm apart and cells 7.4 mm). Each piece records its slice,
//! the first of the 2 × 2 columns it is splatted to and its place in their square (the
//! bilinear shares, `piece.rs`), and the depth range it spans in its slice.

use super::Scratch;
use super::input::{CountModel, MapBuildInput};
use super::piece::{Piece, PieceStats, SPLAT, splat_weight};
use crate::map::{MAX_CELL_COORD, MapGeometry, Projection};
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// Most pieces a sample is split into (a sample longer than 8 cells still makes 8).
pub(in crate::map) const MAX_PIECES: usize = 8;

/// Bounding box of filled cells in unwrapped cell indices (x, y, z).
#[derive(Clone, Copy, Debug)]
pub(super) struct Extent {
    pub(super) lo: [i64; 3],
    pub(super) hi: [i64; 3],
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

/// What the fill made: the filled cells' extent, and how many samples it took and skipped
/// and pieces it filled.
pub(super) struct Filled {
    pub(super) extent: Extent,
    /// Samples in the input (the shortest of its per-sample slices).
    pub(super) count: usize,
    /// Samples skipped as non-finite.
    pub(super) skipped: usize,
    /// Pieces with a positive share in some column.
    pub(super) pieces: usize,
}

/// How the fill turns a sample into pieces: the map's frame and sizes, and the per-metre
/// scales of the crossings and the volume fraction.
pub(super) struct Fill<'a> {
    input: &'a MapBuildInput<'a>,
    proj: Projection,
    /// Map metres to cells along X and to columns along Y, Z.
    inv_cell: Vec3,
    model: CountModel,
    /// Columns per lateral axis.
    ncol: i64,
    /// Expected crossings per metre of strand and unit sin ψ: F·2r / dc².
    crossing_scale: f32,
    /// Volume fraction per metre of strand: F·πr² / (ds·dc²).
    volume_scale: f32,
    /// Samples, and pieces per sample.
    count: usize,
    pieces: usize,
}

impl<'a> Fill<'a> {
    /// The fill of `input` into a map of `geom` read through `proj` (`inv_cell`: map metres
    /// to cells and columns).
    pub(super) fn new(
        input: &'a MapBuildInput<'a>,
        geom: &MapGeometry,
        proj: Projection,
        inv_cell: Vec3,
        model: CountModel,
    ) -> Self {
        let ds = geom.ds_m;
        let dc = geom.column_m();
        let r = input.fiber.params().radius_m;
        let count = input
            .positions
            .len()
            .min(input.tangents.len())
            .min(input.lengths_m.len());
        let max_len = (0..count)
            .map(|s| input.span_m(s))
            .filter(|l| l.is_finite())
            .fold(0.0f32, f32::max);
        Fill {
            input,
            proj,
            inv_cell,
            model,
            ncol: geom.columns_per_axis() as i64,
            crossing_scale: input.fibers_per_strand * 2.0 * r / (dc * dc),
            volume_scale: input.fibers_per_strand * std::f32::consts::PI * r * r / (ds * dc * dc),
            count,
            pieces: ((max_len / ds).ceil() as usize).clamp(1, MAX_PIECES),
        }
    }

    /// Fills `scratch`'s per-sample statistics, forward attenuations and pieces (sample after
    /// sample, [`Fill::pieces`] each). The extent comes from an exact min/max reduce, so the
    /// reduction order does not matter.
    pub(super) fn run(&self, scratch: &mut Scratch) -> Filled {
        let (count, pieces) = (self.count, self.pieces);
        // A piece's order (`Piece::id`) and sample are u32.
        assert!(
            u32::try_from(count * pieces).is_ok(),
            "the map takes at most 2^32 − 1 pieces"
        );
        // Exact reservations: a vector that grows by `resize` may double its capacity, which
        // the memory budget would have to count twice.
        let entries = &mut scratch.entries;
        entries.reserve_exact((count * pieces).saturating_sub(entries.len()));
        entries.resize(count * pieces, Piece::default());
        let stats = &mut scratch.stats;
        stats.reserve_exact(count.saturating_sub(stats.len()));
        stats.resize(count, PieceStats::default());
        let forward_a = &mut scratch.forward_a;
        forward_a.reserve_exact(count.saturating_sub(forward_a.len()));
        forward_a.resize(count, Vec3::NAN);
        let (extent, skipped) = entries
            .par_chunks_mut(pieces)
            .zip(stats.par_iter_mut().zip(forward_a.par_iter_mut()))
            .enumerate()
            .with_min_len(512)
            .map(|(s, (out, (stat, forward)))| self.sample(s, out, stat, forward))
            .reduce(
                || (Extent::EMPTY, 0),
                |a, b| (Extent::union(a.0, b.0), a.1 + b.1),
            );
        let filled = entries.par_iter().filter(|e| e.col != u32::MAX).count();
        Filled {
            extent,
            count,
            skipped,
            pieces: filled,
        }
    }

    /// Sample `s`: its statistics into `stat`, its clamped ā_f into `forward` and its pieces
    /// into `out`; returns the extent of its pieces and 1 when it is skipped (non-finite).
    fn sample(
        &self,
        s: usize,
        out: &mut [Piece],
        stat: &mut PieceStats,
        forward: &mut Vec3,
    ) -> (Extent, usize) {
        let input = self.input;
        let u = input.tangents[s];
        let len_total = input.lengths_m[s];
        let p = input.positions[s];
        let p0 = self.proj.point(p) * self.inv_cell;
        if !(p0.abs().max_element() < MAX_CELL_COORD
            && u.is_finite()
            && len_total.is_finite()
            && len_total >= 0.0)
        {
            out.iter_mut().for_each(|e| e.col = u32::MAX);
            *forward = Vec3::NAN;
            return (Extent::EMPTY, 1);
        }
        // The strand's image in map coordinates; for a point light its crossing and volume
        // weights carry the lateral scale (see `Projection::strand`).
        let (u_map, across, volume_weight) = self.proj.strand(p, u);
        let len = len_total / self.pieces as f32;
        let (st, a) = self.piece_stats(p, u, len, across, volume_weight);
        *stat = st;
        *forward = a;
        let u_cells = u_map * self.inv_cell;
        (self.place(s, p0, u_cells, input.span_m(s), out), 0)
    }

    /// What each piece of length `len` of a sample at `p` with tangent `u` carries (its strand
    /// crossing the light's rays by `across` per metre, its fibre volume scaled by
    /// `volume_weight`), and the fibre's ā_f clamped to [0, 1].
    fn piece_stats(
        &self,
        p: Vec3,
        u: Vec3,
        len: f32,
        across: f32,
        volume_weight: f32,
    ) -> (PieceStats, Vec3) {
        let crossings = self.crossing_scale * len * across;
        let fs = self
            .input
            .fiber
            .forward_scatter(u.dot(self.proj.toward_light(p)).clamp(-1.0, 1.0));
        let a = fs.a_f.clamp(Vec3::ZERO, Vec3::ONE);
        let loss = match self.model {
            CountModel::Poisson => Vec3::ONE - a,
            CountModel::MeanCount => -a.max(Vec3::splat(1e-30)).ln(),
        };
        let stats = PieceStats {
            n: crossings,
            loss: (loss * crossings).to_array(),
            sigma2: (fs.beta_f2 * crossings).to_array(),
            volume_fraction: self.volume_scale * len * volume_weight,
        };
        (stats, a)
    }

    /// Places sample `s`'s pieces (at cell coordinates `p0`, along `u_cells` per metre, over a
    /// piece of strand `span_total` long) into `out`; returns the extent of their columns.
    fn place(
        &self,
        s: usize,
        p0: Vec3,
        u_cells: Vec3,
        span_total: f32,
        out: &mut [Piece],
    ) -> Extent {
        let (pieces, ncol) = (self.pieces, self.ncol);
        // Half the depth a piece spans along the light, in cells (its whole length of strand,
        // also where a tapered tip has fewer fibres).
        let half_depth = 0.5 * (u_cells.x * span_total / pieces as f32).abs();
        let mut ext = Extent::EMPTY;
        for (q, e) in out.iter_mut().enumerate() {
            let along = ((q as f32 + 0.5) / pieces as f32 - 0.5) * span_total;
            // The piece's offset, in cells, is rounded to 1/1024 of a cell (7 µm at the default
            // size): then moving the hair by whole cells moves every piece by exactly whole
            // cells too (adding numbers on that grid is exact in f32), which keeps the modulo
            // map's translation invariance exact.
            let offset = (u_cells * along * 1024.0).round() / 1024.0;
            let at = p0 + offset;
            let c = at.floor();
            let i = c.x as i64;
            // The piece's depth range inside its slice (the part of it beyond the slice's
            // faces is counted at the face: pieces are at most a cell long).
            let lambda = at.x - c.x;
            let q16 = |v: f32| (v.clamp(0.0, 1.0) * 65535.0).round() as u16;
            let depth = [q16(lambda - half_depth), q16(lambda + half_depth)];
            // Across the light, the piece is shared by the four nearest columns with bilinear
            // (tent) weights about their centres, so a strand moving across a column boundary
            // changes the light smoothly (a box fill shows the cell grid as blotches on hair
            // lying side by side). The piece keeps the first of them and its place in their
            // square; the merge takes the shares.
            let lat = Vec2::new(at.y, at.z) - Vec2::splat(0.5);
            let l0 = lat.floor();
            let frac = (lat - l0).to_array();
            let (j0, k0) = (l0.x as i64, l0.y as i64);
            ext.include([i, j0, k0]);
            ext.include([i, j0 + 1, k0 + 1]);
            let shared = (0..SPLAT).any(|t| splat_weight(frac, t) > 0.0);
            *e = Piece {
                slice: i,
                col: if shared {
                    (j0.rem_euclid(ncol) * ncol + k0.rem_euclid(ncol)) as u32
                } else {
                    u32::MAX
                },
                sample: s as u32,
                id: (s * pieces + q) as u32,
                frac,
                depth,
            };
        }
        ext
    }
}
