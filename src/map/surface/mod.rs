//! The hair's shadow on surfaces (skin, clothes) at finer than the map's columns.
//!
//! Why: a surface shows the map's lateral reconstruction directly as a shadow. Long render
//! strands over a shoulder cast long thin streaks on the arm (ACCURACY.md §1, "skin": exact
//! rays draw them), while columns of ¾ of a strand spacing, blended between their centres,
//! draw blobs on the column grid, a stipple the eye reads as an artefact, whatever the blend.
//!
//! What: a light-space texture across the light, [`TEXELS_PER_COLUMN`] texels per map column,
//! holding the optical depth Σ n(1 − ā_f) (RGB) of the hair along each texel's ray.
//! Each map sample (a piece of strand of length ℓ) is drawn into it as a ribbon: its image
//! across the light, [`ribbon_width_m`] wide (the spread of the fibres a render strand stands
//! for, as the exact reference places them), with the piece's crossings
//! F·2r·ℓ·sin ψ spread over the texels by their box-filtered overlap with the ribbon
//! (normalised, so each piece deposits exactly its crossings). Only hair before the first
//! solid along each ray is drawn (the occluder grid's entry depth, plus two of its texels for
//! hair resting on the surface): a lit surface point lies on that first solid, so all the hair
//! drawn is in front of it, and it receives
//!
//!   T_f = exp(−L) · V
//!
//! (the Poisson reading of the map, `map` module doc), with L the texture's optical depth
//! and V the solids' own visibility. A point in a solid's shadow has V = 0 whatever L says.
//! Each piece's texels are visited once, in parallel over runs of pieces (their overlaps, and
//! the sum that normalises them), then the texture is filled in parallel over bands of texel
//! rows, each band adding the pieces that reach it in one fixed order (by first row, then
//! input order), so it is the same bits for any thread count. Pieces go through both steps in
//! waves, so only one wave's texels are held at once.

use super::entry_depths::EntryDepths;
use super::occluders::OccluderGrid;
use super::{MapBuildInput, Projection};
use crate::keysort::sort_keys;
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// Texels per map column across the light, along each axis.
pub const TEXELS_PER_COLUMN: f32 = 2.0;
/// Texels per axis at most; a larger extent gets coarser texels.
const MAX_TEXELS_PER_AXIS: usize = 1024;
/// Texel rows per parallel band.
const BAND_ROWS: usize = 16;
/// Samples per parallel job turned into pieces (fixed, so their order does not depend on the
/// thread count), and the bits of a piece's position that hold its place in its job's list.
const PIECE_CHUNK: usize = 4096;
const PIECE_CHUNK_BITS: usize = 12;
/// Sorted pieces whose texels one parallel task gathers.
const GATHER_RUN: usize = 256;
/// Pieces whose texels are gathered and deposited at a time (a multiple of [`GATHER_RUN`]).
const WAVE_PIECES: usize = 64 * GATHER_RUN;
/// Texels per side of the tiles that keep their deepest limit, so a piece lying behind the
/// first solid at every texel it can touch is dropped before it is summed and deposited.
/// Smooth under the default light at t = 2 s: 4 catches 31,238 of the 32,661 pieces behind
/// (per-texel maximum over each piece's box), 8 catches 29,736, 16 catches 25,853.
const LIMIT_TILE: usize = 4;

/// How wide a render strand's shadow is across the light: its fibres' spread. The exact
/// reference places F fibres uniformly in a disc of radius R (half the strand spacing); the
/// crossings across such a disc have the variance of a box √3·R wide.
pub fn ribbon_width_m(bundle_radius_m: f32) -> f32 {
    3f32.sqrt() * bundle_radius_m
}

/// A sample's piece of strand drawn as a ribbon across the light, in texel coordinates: from
/// `a` along unit `dir` for `len` (≥ 1) texels, `half_w` either side, its depth along the
/// light (map metres) running from `depth.0` to `depth.1`, its crossings' losses Σ n(1 − ā_f)
/// times their cross-section (`loss`, m²; over a texel's area it is an optical depth; once
/// gathered, what a unit of overlap deposits per texel area) and its ribbon's summed box
/// overlap (the sum [`Piece::gather`] returns), so a texel of overlap w gets loss · w / sum
/// over its area: the whole ribbon deposits the piece's own.
#[derive(Clone, Copy, Debug)]
struct Piece {
    a: Vec2,
    dir: Vec2,
    len: f32,
    half_w: f32,
    depth: (f32, f32),
    loss: Vec3,
    /// Where its gathered texels ([`Piece::gather`]) lie in its run's buffer
    /// ([`SurfaceShadow::build`], step 3).
    texels: [u32; 2],
    /// Texel box the ribbon touches: rows `x0..x1`, columns `y0..y1`.
    x0: u32,
    x1: u32,
    y0: u32,
    y1: u32,
}

impl Piece {
    /// The ribbon from `a` to `b` (texel coordinates), or `None` when it touches no texel of a
    /// `dims` texture.
    fn new(a: Vec2, b: Vec2, depth: (f32, f32), half_w: f32, dims: [usize; 2]) -> Option<Piece> {
        let d = b - a;
        let len = d.length();
        // A piece seen end-on still covers its width along some direction: at least one texel.
        let (dir, len, a) = if len >= 1.0 {
            (d / len, len, a)
        } else {
            let dir = if len > 0.0 { d / len } else { Vec2::X };
            (dir, 1.0, 0.5 * (a + b) - dir * 0.5)
        };
        let reach = half_w + 1.0;
        let end = a + dir * len;
        let (lo, hi) = (
            a.min(end) - Vec2::splat(reach),
            a.max(end) + Vec2::splat(reach),
        );
        let x0 = lo.x.floor().max(0.0) as usize;
        let y0 = lo.y.floor().max(0.0) as usize;
        let x1 = (hi.x.ceil().max(0.0) as usize).min(dims[0]);
        let y1 = (hi.y.ceil().max(0.0) as usize).min(dims[1]);
        if x0 >= x1 || y0 >= y1 {
            return None;
        }
        Some(Piece {
            a,
            dir,
            len,
            half_w,
            depth,
            loss: Vec3::ZERO,
            texels: [0, 0],
            x0: x0 as u32,
            x1: x1 as u32,
            y0: y0 as u32,
            y1: y1 as u32,
        })
    }

    /// Texel (x, y)'s box overlap with the ribbon, and where the texel's centre projects on
    /// the ribbon's axis (texels from `a`; [`Piece::depth_at`] turns it into a depth).
    #[inline]
    fn at(&self, x: usize, y: usize) -> (f32, f32) {
        let overlap = |c: f32, lo: f32, hi: f32| ((c + 0.5).min(hi) - (c - 0.5).max(lo)).max(0.0);
        let q = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) - self.a;
        let s = q.dot(self.dir);
        let w =
            overlap(s, 0.0, self.len) * overlap(q.dot(self.dir.perp()), -self.half_w, self.half_w);
        (w, s)
    }

    /// The piece's depth along the light (map metres) at axis position `s` (from [`Piece::at`]),
    /// asked only where a texel overlaps: the division is skipped for the rest.
    #[inline]
    fn depth_at(&self, s: f32) -> f32 {
        let t = (s / self.len).clamp(0.0, 1.0);
        self.depth.0 + (self.depth.1 - self.depth.0) * t
    }

    /// The two strips of [`Piece::row_span`], prepared once per piece.
    #[inline]
    fn strips(&self) -> [Strip; 2] {
        let (dx, dy) = (self.dir.x, self.dir.y);
        [
            // Along: s = qx·dx + qy·dy in (−½, len + ½).
            Strip::new(dx, dy, -0.5, self.len + 0.5),
            // Across: d = −qx·dy + qy·dx in (−half_w − ½, half_w + ½).
            Strip::new(-dy, dx, -self.half_w - 0.5, self.half_w + 0.5),
        ]
    }

    /// The columns `y` of row `x` whose texel centre can overlap the ribbon (strictly within
    /// half a texel of it along and across, where [`Piece::at`] gives a positive overlap): the
    /// intersection of two open strips ([`Piece::strips`]), each an interval in y, widened by
    /// more than the rounding of either computation, so no texel with overlap is left out and
    /// at most one without it is visited at each end. (A texel visited without overlap adds
    /// +0 to the ribbon's sum and is not kept: the spans may change, the sums cannot.)
    #[inline]
    fn row_span(&self, x: usize, strips: &[Strip; 2]) -> std::ops::Range<usize> {
        let qx = x as f32 + 0.5 - self.a.x;
        let mut lo = f32::NEG_INFINITY;
        let mut hi = f32::INFINITY;
        for st in strips {
            let c = qx * st.per_qx;
            if st.steep {
                let (u, v) = ((st.from - c) * st.inv_k, (st.to - c) * st.inv_k);
                let slack = st.slack + st.slack_per_c * c.abs();
                lo = lo.max(u.min(v) - slack);
                hi = hi.min(u.max(v) + slack);
            } else if !(c > st.from && c < st.to) {
                hi = f32::NEG_INFINITY;
            }
        }
        if lo.is_nan() || hi.is_nan() || lo > hi {
            return 0..0;
        }
        // Texel y's centre is at qy = y + ½ − a.y: the texels strictly inside are the integers
        // in (lo, hi) + a.y − ½.
        let to_y = |qy: f32| qy + self.a.y - 0.5;
        let y0 = ((to_y(lo).floor() + 1.0).max(self.y0 as f32)) as usize;
        let y1 = (to_y(hi).ceil().min(self.y1 as f32)).max(0.0) as usize;
        y0..y1.max(y0)
    }

    /// Sum of the overlaps over the texels the ribbon touches, rows then columns: the order
    /// [`Piece::gather`] adds them in (its reference in the tests).
    #[cfg(test)]
    fn overlap_sum(&self) -> f32 {
        let mut sum = 0.0;
        let strips = self.strips();
        for x in self.x0 as usize..self.x1 as usize {
            for y in self.row_span(x, &strips) {
                sum += self.at(x, y).0;
            }
        }
        sum
    }

    /// Visits the ribbon's texels once, rows then columns, in a texture of `cols` columns:
    /// appends to `out` each texel (row-major index) with a positive overlap where the
    /// ribbon's depth is at most the texel's `limit`, with that overlap, and returns the sum
    /// of the overlaps over all its texels (what normalises its deposit).
    fn gather(&self, cols: usize, limit: &[f32], out: &mut Vec<(u32, f32)>) -> f32 {
        let mut sum = 0.0;
        let strips = self.strips();
        for x in self.x0 as usize..self.x1 as usize {
            for y in self.row_span(x, &strips) {
                let (w, along) = self.at(x, y);
                sum += w;
                let k = x * cols + y;
                if w > 0.0 && self.depth_at(along) <= limit[k] {
                    out.push((k as u32, w));
                }
            }
        }
        sum
    }
}

/// One strip of a ribbon across a row of texels ([`Piece::row_span`]): the texel centres
/// with `qx·per_qx + qy·k` in (`from`, `to`), qx and qy the centre's offset from the ribbon's
/// start.
///
/// Why reciprocals: the spans were four divisions a row and their slack two more, 21% of
/// curly's texture. A product by `1/k` is within an ulp or two of the quotient, and the slack
/// (a hundredth of a texel, plus 1e-5 of the magnitudes over |k|) is 80 times that.
struct Strip {
    per_qx: f32,
    /// Whether |k| > 1e-6: else the strip does not depend on y, and holds the row or not.
    steep: bool,
    inv_k: f32,
    from: f32,
    to: f32,
    /// The slack is `slack + slack_per_c · |qx·per_qx|`.
    slack: f32,
    slack_per_c: f32,
}

impl Strip {
    fn new(per_qx: f32, k: f32, from: f32, to: f32) -> Strip {
        let steep = k.abs() > 1e-6;
        let inv_k = if steep { 1.0 / k } else { 0.0 };
        // A hundredth of a texel, plus far more than the rounding of from − c (a few ulps of
        // the larger) magnified by the division.
        let per = 1e-5 * inv_k.abs();
        Strip {
            per_qx,
            steep,
            inv_k,
            from,
            to,
            slack: 1e-2 + per * (from.abs() + to.abs() + 1.0),
            slack_per_c: per,
        }
    }
}

/// Adds a ribbon's gathered `texels` (row-major index, overlap) that lie in `band` (rows) to
/// `rows` (the band's texels, `cols` per row): `per` × the overlap each, `per` being the
/// piece's loss ÷ its overlap sum, per texel area.
fn deposit(
    per: Vec3,
    texels: &[(u32, f32)],
    band: std::ops::Range<usize>,
    cols: usize,
    rows: &mut [Vec3],
) {
    let (first, end) = ((band.start * cols) as u32, (band.end * cols) as u32);
    // The texels are in row-major order: those of earlier bands first.
    let from = texels.partition_point(|&(k, _)| k < first);
    for &(k, w) in texels[from..].iter().take_while(|&&(k, _)| k < end) {
        rows[(k - first) as usize] += per * w;
    }
}

/// The deepest limit (`SurfaceShadow::limit`) of each [`LIMIT_TILE`]² tile of texels, so a
/// piece lying behind the first solid at every texel its box holds can be found without
/// visiting them.
#[derive(Clone, Debug, Default)]
struct LimitTiles {
    cols: usize,
    deepest: Vec<f32>,
}

impl LimitTiles {
    /// The tiles of a `dims` texture's per-texel `limit` (row-major). Reuses its memory.
    fn build(&mut self, limit: &[f32], dims: [usize; 2]) {
        self.cols = dims[1].div_ceil(LIMIT_TILE);
        self.deepest.clear();
        self.deepest
            .resize(dims[0].div_ceil(LIMIT_TILE) * self.cols, f32::NEG_INFINITY);
        for (x, row) in limit.chunks_exact(dims[1]).enumerate() {
            let tiles = &mut self.deepest[(x / LIMIT_TILE) * self.cols..][..self.cols];
            for (deepest, block) in tiles.iter_mut().zip(row.chunks(LIMIT_TILE)) {
                for &l in block {
                    *deepest = deepest.max(l);
                }
            }
        }
    }

    /// Whether `piece` is deeper than the limit at every texel of its box, so
    /// [`Piece::deposit`] keeps none of them. Conservative: it may answer `false` for such a
    /// piece (its box's tiles reach beyond it), never `true` for one that deposits.
    fn behind_all(&self, piece: &Piece) -> bool {
        let mut deepest = f32::NEG_INFINITY;
        let ys = piece.y0 as usize / LIMIT_TILE..=(piece.y1 as usize - 1) / LIMIT_TILE;
        for tx in piece.x0 as usize / LIMIT_TILE..=(piece.x1 as usize - 1) / LIMIT_TILE {
            for &l in &self.deepest[tx * self.cols..][ys.clone()] {
                deepest = deepest.max(l);
            }
        }
        // A texel's depth interpolates between the ends' (`Piece::depth_at`): never nearer
        // than the nearer end by more than its rounding, far within this margin.
        let nearest = piece.depth.0.min(piece.depth.1);
        nearest - 1e-5 * (1.0 + nearest.abs()) > deepest
    }
}

/// The texture (see the module doc).
#[derive(Clone, Debug, Default)]
pub struct SurfaceShadow {
    /// Map coordinates (metres, across the light: map Y, Z) of texel (0, 0)'s corner.
    origin: Vec2,
    texel_m: f32,
    dims: [usize; 2],
    /// Optical depth R, G, B per texel, row-major (rows along map Y).
    sums: Vec<Vec3>,
    /// Per texel, the depth along the light (map metres) beyond which hair is not drawn: the
    /// first solid's entry depth there plus two occluder texels (hair resting on it counts).
    limit: Vec<f32>,
    /// Scratch: a summed-area table of the texels with a solid behind them (finite `limit`),
    /// (dims[0] + 1) × (dims[1] + 1), so a piece can ask in O(1) whether any surface will read
    /// what it deposits.
    solid_sat: Vec<u32>,
    /// Scratch: the solids' entry depths over the texture (`limit` before its tolerance).
    entry: EntryDepths,
    /// Scratch: the deepest `limit` per tile of texels.
    limit_tiles: LimitTiles,
    /// Scratch: the pieces that draw, per fixed chunk of samples, in sample order; their sort
    /// keys (first row, position) with the radix sort's second buffer; the pieces sorted by
    /// first row.
    chunk_pieces: Vec<Vec<Piece>>,
    keys: Vec<u64>,
    key_tmp: Vec<u64>,
    pieces: Vec<Piece>,
    /// Scratch: per band, the range of `pieces` that may reach it.
    band_first: Vec<u32>,
    /// Scratch: per run of [`GATHER_RUN`] sorted pieces, their gathered texels (row-major
    /// index, overlap), each piece's at its `texels` range.
    gathered: Vec<Vec<(u32, f32)>>,
}

impl SurfaceShadow {
    /// Bytes the texture keeps for an extent of `columns` map columns per axis and `samples`
    /// map samples, each gathering at most `ribbon_texels` texels
    /// ([`SurfaceShadow::ribbon_texel_bound`]).
    pub fn estimated_bytes(columns: u64, samples: u64, ribbon_texels: u64) -> u64 {
        let per_axis =
            ((columns as f32 * TEXELS_PER_COLUMN) as u64).min(MAX_TEXELS_PER_AXIS as u64) + 4;
        // Per texel: the sums, the limit, the solids' count and the two passes of the entry
        // depths (`EntryDepths`, at most the texture's texels); the tiles are a sixteenth.
        let texel = (std::mem::size_of::<Vec3>() + 5 * std::mem::size_of::<f32>()) as u64;
        // The gathered texels of one wave of pieces, in buffers that grow by `push` (so up to
        // twice their length).
        let gathered = samples
            .min(WAVE_PIECES as u64)
            .saturating_mul(ribbon_texels)
            .saturating_mul(2 * std::mem::size_of::<(u32, f32)>() as u64);
        // The pieces: per chunk of samples (reserved whole), then sorted; their two key buffers.
        let chunked = samples.div_ceil(PIECE_CHUNK as u64) * PIECE_CHUNK as u64;
        let pieces = chunked
            .saturating_add(samples)
            .saturating_mul(std::mem::size_of::<Piece>() as u64)
            .saturating_add(samples.saturating_mul(2 * std::mem::size_of::<u64>() as u64));
        (per_axis * per_axis * texel)
            .saturating_add(pieces)
            .saturating_add(gathered)
    }

    /// Most texels one ribbon gathers, for map columns `column_m` wide, render strands whose
    /// fibres spread over `bundle_radius_m` and samples at most `sample_len_m` long. A texel
    /// with overlap has its centre strictly inside the ribbon widened by half a texel, a
    /// rectangle a × b texels (a = length + 1, b = width + 1 at the finest texels, a column
    /// over [`TEXELS_PER_COLUMN`]), which holds at most ab + a + b + 1 = (a + 1)(b + 1) lattice
    /// points (a convex set of area A and perimeter P holds at most A + P/2 + 1).
    pub fn ribbon_texel_bound(column_m: f32, bundle_radius_m: f32, sample_len_m: f32) -> u64 {
        let texel_m = column_m / TEXELS_PER_COLUMN;
        let length = (sample_len_m / texel_m).max(1.0);
        let width = ribbon_width_m(bundle_radius_m) / texel_m;
        let bound = ((length + 2.0) * (width + 2.0)).ceil();
        if bound.is_finite() {
            bound as u64
        } else {
            u64::MAX
        }
    }

    /// Fills the texture from `input`'s samples in the map's light frame `proj`, over the
    /// lateral extent `lo..hi` (map metres, Y and Z), with `column_m`-wide columns and
    /// render strands whose fibres spread over `bundle_radius_m`. A tapered sample's ribbon is
    /// drawn over its piece's whole length (`MapBuildInput::span_m`), with its own crossings.
    /// `forward_a` may hold each sample's clamped ā_f as the map's fill evaluated it (NaN, or
    /// missing: evaluated here, to the same bits). Reuses its memory.
    #[allow(clippy::too_many_arguments)]
    pub fn build(
        &mut self,
        input: &MapBuildInput,
        proj: &Projection,
        solids: &OccluderGrid,
        (lo, hi): (Vec2, Vec2),
        column_m: f32,
        bundle_radius_m: f32,
        forward_a: &[Vec3],
    ) {
        let width_m = ribbon_width_m(bundle_radius_m);
        let margin = Vec2::splat(width_m + column_m);
        let (lo, hi) = (lo - margin, hi + margin);
        let extent = (hi - lo).max(Vec2::ZERO);
        let mut texel_m = column_m / TEXELS_PER_COLUMN;
        let wanted = extent.max_element() / texel_m;
        if wanted.is_nan() || wanted > MAX_TEXELS_PER_AXIS as f32 {
            texel_m = extent.max_element() / MAX_TEXELS_PER_AXIS as f32;
        }
        if !(texel_m > 0.0 && texel_m.is_finite() && lo.is_finite()) {
            self.dims = [0, 0];
            self.sums.clear();
            return;
        }
        self.origin = lo;
        self.texel_m = texel_m;
        let dims = [
            ((extent.x / texel_m).ceil() as usize).clamp(1, MAX_TEXELS_PER_AXIS),
            ((extent.y / texel_m).ceil() as usize).clamp(1, MAX_TEXELS_PER_AXIS),
        ];
        self.dims = dims;
        let texels = dims[0] * dims[1];
        self.sums.clear();
        self.sums.resize(texels, Vec3::ZERO);
        // Where hair stops counting: the first solid along each texel's ray.
        self.limit.clear();
        self.limit.resize(texels, 0.0);
        let origin = self.origin;
        let tolerance = 2.0 * solids.texel_m();
        let centre = |k: usize| {
            let (x, y) = ((k / dims[1]) as f32 + 0.5, (k % dims[1]) as f32 + 0.5);
            origin + Vec2::new(x, y) * texel_m
        };
        self.entry.fill(solids, centre(0), centre(texels - 1));
        let entry = &self.entry;
        self.limit.par_iter_mut().enumerate().for_each(|(k, l)| {
            let m = centre(k);
            *l = entry.at(solids, Vec3::new(0.0, m.x, m.y)) + tolerance;
        });
        // Which texels any surface reads: a point on a solid reads the four texels around it
        // (bilinear), all within one texel of a texel whose ray meets that solid (its limit is
        // finite: `entry_depth` already looks 2 occluder texels around). A piece whose box,
        // widened by 2 texels, holds no such texel deposits only where nothing is read, so it
        // is skipped: the values every surface reads are the same bits, and hair with no solid
        // behind it (31% of smooth's samples under the default light) costs nothing.
        let (rows1, cols1) = (dims[0] + 1, dims[1] + 1);
        let sat = &mut self.solid_sat;
        sat.clear();
        sat.resize(rows1 * cols1, 0);
        for x in 0..dims[0] {
            let mut run = 0u32;
            for y in 0..dims[1] {
                run += u32::from(self.limit[x * dims[1] + y].is_finite());
                sat[(x + 1) * cols1 + y + 1] = sat[x * cols1 + y + 1] + run;
            }
        }
        // Which pieces lie behind the first solid at every texel they touch: such a piece
        // deposits nothing, so it is dropped before it is summed (46% of smooth's pieces
        // under the default light: hair behind the head as the light sees it).
        self.limit_tiles.build(&self.limit, dims);
        let tiles = &self.limit_tiles;
        let sat = &self.solid_sat;
        let reads_any = |p: &Piece| {
            let (x0, x1) = (
                (p.x0 as usize).saturating_sub(2),
                (p.x1 as usize + 2).min(dims[0]),
            );
            let (y0, y1) = (
                (p.y0 as usize).saturating_sub(2),
                (p.y1 as usize + 2).min(dims[1]),
            );
            sat[x1 * cols1 + y1] + sat[x0 * cols1 + y0]
                != sat[x0 * cols1 + y1] + sat[x1 * cols1 + y0]
        };
        // 1. Each sample's ribbon and its normalisation, in parallel.
        let r = input.fiber.params().radius_m;
        let count = input
            .positions
            .len()
            .min(input.tangents.len())
            .min(input.lengths_m.len());
        // The map's per-sample ā_f, if it was built from these samples (as it must be).
        let forward_a = if forward_a.len() == count {
            forward_a
        } else {
            &[]
        };
        let inv_texel = 1.0 / texel_m;
        let half_w = 0.5 * width_m * inv_texel;
        let piece_of = |s: usize| -> Option<Piece> {
            let (p, u, len) = (input.positions[s], input.tangents[s], input.lengths_m[s]);
            let share = input.fibre_share.get(s).copied().unwrap_or(1.0);
            if !(p.is_finite() && u.is_finite() && len.is_finite() && len > 0.0 && share > 0.0) {
                return None;
            }
            let piece_m = input.span_m(s);
            let (_, across, _) = proj.strand(p, u);
            let crossings = input.fibers_per_strand * 2.0 * r * len * across;
            let a_f = match forward_a.get(s) {
                Some(a) if !a.x.is_nan() => *a,
                _ => input
                    .fiber
                    .forward_scatter(u.dot(proj.toward_light(p)).clamp(-1.0, 1.0))
                    .a_f
                    .clamp(Vec3::ZERO, Vec3::ONE),
            };
            let loss = (Vec3::ONE - a_f) * crossings;
            if loss.max_element().is_nan() || loss.max_element() <= 0.0 {
                return None;
            }
            // Texel coordinates across the light, and depth along it.
            let lat = |q: Vec3| {
                let m = proj.point(q);
                ((Vec2::new(m.y, m.z) - origin) * inv_texel, m.x)
            };
            let ((a, depth_a), (b, depth_b)) =
                (lat(p - u * (0.5 * piece_m)), lat(p + u * (0.5 * piece_m)));
            if !(a.is_finite() && b.is_finite() && depth_a.is_finite() && depth_b.is_finite()) {
                return None;
            }
            let mut piece = Piece::new(a, b, (depth_a, depth_b), half_w, dims)?;
            if !reads_any(&piece) || tiles.behind_all(&piece) {
                return None;
            }
            piece.loss = loss;
            Some(piece)
        };
        // Each fixed chunk of samples keeps the pieces that draw, in sample order.
        let chunks = count.div_ceil(PIECE_CHUNK);
        if self.chunk_pieces.len() < chunks {
            self.chunk_pieces.resize_with(chunks, Vec::new);
        }
        self.chunk_pieces[..chunks]
            .par_iter_mut()
            .enumerate()
            .for_each(|(c, out)| {
                out.clear();
                // Exact, so the memory budget counts each chunk once.
                out.reserve_exact(PIECE_CHUNK);
                out.extend(
                    (c * PIECE_CHUNK..((c + 1) * PIECE_CHUNK).min(count)).filter_map(piece_of),
                );
            });
        // 2. Pieces by first row, then input order: keys of (first row, position), the
        // position (chunk, place in it) ascending in input order, sorted by radix; the pieces
        // gathered in that order. Per band, the first piece that may reach it.
        //
        // Rejected, measured (curly, 2 threads): one slot per sample (a `None` piece for a
        // sample that draws nothing, 60% of curly's) sorted by `par_sort_unstable_by_key`: 29 MB
        // of 72-byte pieces written, then sorted, 13–14 ms and 6–8 ms of the texture's 45.
        const _: () = assert!(PIECE_CHUNK == 1 << PIECE_CHUNK_BITS);
        let chunk_pieces = &self.chunk_pieces[..chunks];
        let keys = &mut self.keys;
        keys.clear();
        for (c, out) in chunk_pieces.iter().enumerate() {
            keys.extend(
                out.iter()
                    .enumerate()
                    .map(|(i, p)| (u64::from(p.x0) << 32) | ((c << PIECE_CHUNK_BITS) | i) as u64),
            );
        }
        sort_keys(keys, &mut self.key_tmp);
        let pieces = &mut self.pieces;
        pieces.clear();
        pieces.par_extend(keys.par_iter().map(|&k| {
            let pos = (k & 0xFFFF_FFFF) as usize;
            chunk_pieces[pos >> PIECE_CHUNK_BITS][pos & (PIECE_CHUNK - 1)]
        }));
        let bands = dims[0].div_ceil(BAND_ROWS);
        let tallest = pieces.iter().map(|p| p.x1 - p.x0).max().unwrap_or(0) as usize;
        self.band_first.clear();
        self.band_first.extend((0..=bands).map(|b| {
            let from = (b * BAND_ROWS).saturating_sub(tallest) as u32;
            pieces.partition_point(|p| p.x0 < from) as u32
        }));
        // 3. In waves of at most WAVE_PIECES pieces (in their order, so what a texel adds
        // keeps the pieces' order; a wave's texels are held at once, the whole texture's
        // would be: 14 M for the dense preset): each piece's texels gathered once, in parallel
        // over runs of pieces, each run into its own buffer (its overlaps in front of the
        // solids, and their sum, which turns its loss into what a unit of overlap deposits
        // per texel area); then each band adds the wave's pieces that reach it.
        let limit = &self.limit;
        let inv_texel_area = inv_texel * inv_texel;
        let band_first = &self.band_first;
        let gathered = &mut self.gathered;
        for wave in (0..pieces.len()).step_by(WAVE_PIECES) {
            let wave_end = (wave + WAVE_PIECES).min(pieces.len());
            let runs = (wave_end - wave).div_ceil(GATHER_RUN);
            if gathered.len() < runs {
                gathered.resize_with(runs, Vec::new);
            }
            pieces[wave..wave_end]
                .par_chunks_mut(GATHER_RUN)
                .zip(gathered.par_iter_mut())
                // One job per run or band: their work is uneven (`raster::lines` on rayon's
                // splitting).
                .with_max_len(1)
                .for_each(|(run, texels)| {
                    texels.clear();
                    for piece in run.iter_mut() {
                        let start = texels.len();
                        let sum = piece.gather(dims[1], limit, texels);
                        if sum > 0.0 {
                            piece.loss *= inv_texel_area / sum;
                            piece.texels = [start as u32, texels.len() as u32];
                        } else {
                            texels.truncate(start);
                            piece.texels = [start as u32; 2];
                        }
                    }
                });
            let (pieces, gathered) = (&*pieces, &*gathered);
            self.sums
                .par_chunks_mut(BAND_ROWS * dims[1])
                .enumerate()
                .with_max_len(1)
                .for_each(|(b, rows)| {
                    let (r0, r1) = (b * BAND_ROWS, ((b + 1) * BAND_ROWS).min(dims[0]));
                    let first = (band_first[b] as usize).max(wave);
                    let last = pieces[..wave_end].partition_point(|p| (p.x0 as usize) < r1);
                    for (i, piece) in pieces.iter().enumerate().take(last).skip(first) {
                        let [from, to] = piece.texels.map(|t| t as usize);
                        let texels = &gathered[(i - wave) / GATHER_RUN][from..to];
                        deposit(piece.loss, texels, r0..r1, dims[1], rows);
                    }
                });
        }
    }

    /// The optical depth (R, G, B) of the hair along the ray through map point `m`, bilinear
    /// between texel centres; 0 outside the texture.
    pub fn optical_depth(&self, m: Vec3) -> Vec3 {
        if self.dims[0] == 0 || !m.is_finite() {
            return Vec3::ZERO;
        }
        let t = (Vec2::new(m.y, m.z) - self.origin) / self.texel_m - Vec2::splat(0.5);
        let f = t.floor();
        let w = t - f;
        let (x0, y0) = (f.x as i64, f.y as i64);
        let mut out = Vec3::ZERO;
        for (dx, wx) in [(0, 1.0 - w.x), (1, w.x)] {
            for (dy, wy) in [(0, 1.0 - w.y), (1, w.y)] {
                let (x, y) = (x0 + dx, y0 + dy);
                if x < 0 || y < 0 || x as usize >= self.dims[0] || y as usize >= self.dims[1] {
                    continue;
                }
                out += self.sums[x as usize * self.dims[1] + y as usize] * (wx * wy);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests;
