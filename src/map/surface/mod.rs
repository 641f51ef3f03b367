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
use super::{LightMap, MapBuildInput, Projection};
use crate::keysort::sort_keys;
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use ribbon::{LimitTiles, Piece, deposit};

mod ribbon;

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

/// How wide a render strand's shadow is across the light: its fibres' spread. The exact
/// reference places F fibres uniformly in a disc of radius R (half the strand spacing); the
/// crossings across such a disc have the variance of a box √3·R wide.
pub fn ribbon_width_m(bundle_radius_m: f32) -> f32 {
    3f32.sqrt() * bundle_radius_m
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
    /// (`dims[0]` + 1) × (`dims[1]` + 1), so a piece can ask in O(1) whether any surface will read
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
    /// Scratch: per run of [`GATHER_RUN`] sorted pieces of a wave, their gathered texels
    /// (row-major index, overlap), each piece's at its `texels` range: two sets, the wave
    /// being deposited's and the next's.
    gathered: [Vec<Vec<(u32, f32)>>; 2],
}

/// What step 3 of [`SurfaceShadow::build`] works with: the texture's size, each texel's
/// limit, a texel's inverse area (m⁻²) and per band the first piece that may reach it.
struct Wave<'a> {
    cols: usize,
    rows: usize,
    limit: &'a [f32],
    inv_texel_area: f32,
    band_first: &'a [u32],
}

impl Wave<'_> {
    /// Gathers each of a wave's `pieces`' texels into `gathered` (one buffer per run of
    /// [`GATHER_RUN`]), in parallel over runs, and turns its loss into what a unit of overlap
    /// deposits per texel area.
    fn gather(&self, pieces: &mut [Piece], gathered: &mut Vec<Vec<(u32, f32)>>) {
        let runs = pieces.len().div_ceil(GATHER_RUN);
        if gathered.len() < runs {
            gathered.resize_with(runs, Vec::new);
        }
        pieces
            .par_chunks_mut(GATHER_RUN)
            .zip(gathered.par_iter_mut())
            // One job per run or band: their work is uneven (`raster::lines` on rayon's
            // splitting).
            .with_max_len(1)
            .for_each(|(run, texels)| {
                texels.clear();
                for piece in run.iter_mut() {
                    let start = texels.len();
                    let sum = piece.gather(self.cols, self.limit, texels);
                    if sum > 0.0 {
                        piece.loss *= self.inv_texel_area / sum;
                        piece.texels = [start as u32, texels.len() as u32];
                    } else {
                        texels.truncate(start);
                        piece.texels = [start as u32; 2];
                    }
                }
            });
    }

    /// Adds the wave of pieces from `wave` to the end of `pieces` (sorted, earlier waves
    /// before it; its texels in `gathered`) to `sums`, in parallel over bands of texel rows,
    /// each band its pieces in their order.
    fn deposit(
        &self,
        pieces: &[Piece],
        wave: usize,
        gathered: &[Vec<(u32, f32)>],
        sums: &mut [Vec3],
    ) {
        let cols = self.cols;
        sums.par_chunks_mut(BAND_ROWS * cols)
            .enumerate()
            .with_max_len(1)
            .for_each(|(b, rows)| {
                let (r0, r1) = (b * BAND_ROWS, ((b + 1) * BAND_ROWS).min(self.rows));
                let first = (self.band_first[b] as usize).max(wave);
                let last = pieces.partition_point(|p| (p.x0 as usize) < r1);
                for (i, piece) in pieces.iter().enumerate().take(last).skip(first) {
                    let [from, to] = piece.texels.map(|t| t as usize);
                    let texels = &gathered[(i - wave) / GATHER_RUN][from..to];
                    deposit(piece.loss, texels, r0..r1, cols, rows);
                }
            });
    }
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
        // The gathered texels of two waves of pieces (one deposited while the next is
        // gathered), in buffers that grow by `push` (so up to twice their length).
        let gathered = samples
            .min(2 * WAVE_PIECES as u64)
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

    /// The texture of `map`'s hair in front of `solids` (call after the map's build and the
    /// solids' grid in its frame: it uses the frame, the hair's extent and the entry depths),
    /// for render strands whose fibres spread over `bundle_radius_m`; `None` when the map
    /// holds no hair. `texture` is reused when it has one.
    pub fn build_for(
        texture: &mut Option<SurfaceShadow>,
        map: &LightMap,
        solids: &OccluderGrid,
        input: &MapBuildInput,
        bundle_radius_m: f32,
    ) {
        let Some(extent) = map.hair_extent_m() else {
            *texture = None;
            return;
        };
        texture.get_or_insert_with(Default::default).build(
            input,
            map.projection(),
            solids,
            extent,
            map.geometry().column_m(),
            bundle_radius_m,
            map.sample_forward_a(),
        );
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
            let share = input.fiber_share.get(s).copied().unwrap_or(1.0);
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
        //
        // A wave's pieces lie in a few bands (they are sorted by first row), so its deposit
        // runs on about one thread (curly: 4.2-4.9 ms on 2 threads, 5.1-5.5 on 1). It runs
        // beside the next wave's gather, which has its own buffers; the deposits still go
        // wave after wave, so each texel adds in the pieces' order.
        let count = pieces.len();
        let waves = count.div_ceil(WAVE_PIECES);
        let range = |k: usize| k * WAVE_PIECES..((k + 1) * WAVE_PIECES).min(count);
        let wave = Wave {
            cols: dims[1],
            rows: dims[0],
            limit: &self.limit,
            inv_texel_area: inv_texel * inv_texel,
            band_first: &self.band_first,
        };
        let [even, odd] = &mut self.gathered;
        if waves > 0 {
            wave.gather(&mut pieces[range(0)], even);
        }
        for k in 0..waves {
            let w = range(k);
            let (done, rest) = pieces.split_at_mut(w.end);
            let (this, next) = if k % 2 == 0 {
                (&*even, &mut *odd)
            } else {
                (&*odd, &mut *even)
            };
            let sums = &mut self.sums;
            rayon::join(
                || wave.deposit(done, w.start, this, sums),
                || {
                    if k + 1 < waves {
                        wave.gather(&mut rest[..range(k + 1).len()], next);
                    }
                },
            );
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
