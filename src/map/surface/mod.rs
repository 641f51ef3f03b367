//! The hair's shadow on surfaces (skin, clothes) at finer than the map's columns.
//!
//! Why: a surface shows the map's lateral reconstruction directly as a shadow. Long render
//! strands over a shoulder cast long thin streaks on the arm (ACCURACY.md §1, "skin": exact
//! rays draw them), while columns of ¾ of a strand spacing, blended between their centres,
//! draw blobs on the column grid, a stipple the eye reads as an artefact, whatever the blend.
//!
//! What: a light-space texture across the light, a few texels per map column (by default
//! [`DEFAULT_TEXELS_PER_COLUMN`]),
//! holding the optical depth Σ n(1 − ā_f) (RGB) of the hair along each texel's ray.
//! Each map sample (a piece of strand of length ℓ) is drawn into it as a ribbon: its image
//! across the light, [`ribbon_width_m`] wide (the spread of the fibres a render strand stands
//! for, as the exact reference places them), with the piece's crossings
//! F·2r·ℓ·sin ψ spread over the texels by their box-filtered overlap with the ribbon
//! (normalised, so each piece deposits exactly its crossings; `ribbon.rs`). Only hair before
//! the first solid along each ray is drawn (the occluder grid's entry depth, plus two of its
//! texels for hair resting on the surface; `limits.rs`): a lit surface point lies on that
//! first solid, so all the hair drawn is in front of it, and it receives
//!
//!   T_f = exp(−L) · V
//!
//! (the Poisson reading of the map, `map` module doc), with L the texture's optical depth
//! and V the solids' own visibility. A point in a solid's shadow has V = 0 whatever L says.
//!
//! How: the samples become ribbons in parallel over fixed chunks and are sorted by first row
//! (`pieces.rs`); then in waves, each piece's texels are visited once, in parallel over runs of
//! pieces (their overlaps, and the sum that normalises them), and the texture is filled in
//! parallel over bands of texel rows, each band adding the pieces that reach it in one fixed
//! order (by first row, then input order), so it is the same bits for any thread count; only
//! one wave's texels are held at once (`waves.rs`).

use super::entry_depths::EntryDepths;
use super::occluders::OccluderGrid;
use super::{LightMap, MapBuildInput};
use glam::{Vec2, Vec3};
use limits::{LimitTiles, SolidTexels};
use pieces::{PIECE_CHUNK, Ribbons};
use ribbon::Piece;
use waves::WAVE_PIECES;

mod limits;
mod pieces;
mod ribbon;
mod waves;

/// Texels per map column across the light, along each axis, unless the caller asks for
/// another density.
pub const DEFAULT_TEXELS_PER_COLUMN: f32 = 2.0;
/// Texels per axis at most; a larger extent gets coarser texels.
const MAX_TEXELS_PER_AXIS: usize = 1024;
/// Texel rows per parallel band.
const BAND_ROWS: usize = 16;

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

impl SurfaceShadow {
    /// Bytes the texture keeps for an extent of `columns` map columns per axis and `samples`
    /// map samples, each gathering at most `ribbon_texels` texels
    /// ([`SurfaceShadow::ribbon_texel_bound`]).
    pub fn estimated_bytes(
        columns: u64,
        texels_per_column: f32,
        samples: u64,
        ribbon_texels: u64,
    ) -> u64 {
        let per_axis =
            ((columns as f32 * texels_per_column) as u64).min(MAX_TEXELS_PER_AXIS as u64) + 4;
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
    /// over `texels_per_column`), which holds at most ab + a + b + 1 = (a + 1)(b + 1) lattice
    /// points (a convex set of area A and perimeter P holds at most A + P/2 + 1).
    pub fn ribbon_texel_bound(
        column_m: f32,
        texels_per_column: f32,
        bundle_radius_m: f32,
        sample_len_m: f32,
    ) -> u64 {
        let texel_m = column_m / texels_per_column;
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
    /// for render strands whose fibres spread over `bundle_radius_m`, with
    /// `texels_per_column` texels per map column along each axis; `None` when the map holds no
    /// hair. `texture` is reused when it has one.
    pub fn build_for(
        texture: &mut Option<SurfaceShadow>,
        map: &LightMap,
        solids: &OccluderGrid,
        input: &MapBuildInput,
        bundle_radius_m: f32,
        texels_per_column: f32,
    ) {
        let Some(extent) = map.hair_extent_m() else {
            *texture = None;
            return;
        };
        let texel_m = map.geometry().column_m() / texels_per_column;
        texture.get_or_insert_with(Default::default).build(
            input,
            map,
            solids,
            extent,
            (bundle_radius_m, texel_m),
        );
    }

    /// Fills the texture from `input`'s samples in `map`'s light frame, over the lateral extent
    /// `lo..hi` (map metres, Y and Z) widened by a ribbon and a column, for render strands
    /// whose fibres spread over `bundle_radius_m`, in texels of `texel_m`. Each sample's ā_f is the map's fill's
    /// (`LightMap::sample_forward_a`) where it has one, else evaluated here, to the same bits.
    /// Reuses its memory.
    fn build(
        &mut self,
        input: &MapBuildInput,
        map: &LightMap,
        solids: &OccluderGrid,
        (lo, hi): (Vec2, Vec2),
        (bundle_radius_m, texel_m): (f32, f32),
    ) {
        let column_m = map.geometry().column_m();
        let width_m = ribbon_width_m(bundle_radius_m);
        if !self.lay_out(lo, hi, width_m + column_m, texel_m) {
            return;
        }
        self.fill_limits(solids);
        self.index_limits();
        let count = input
            .positions
            .len()
            .min(input.tangents.len())
            .min(input.lengths_m.len());
        // The map's per-sample ā_f, if it was built from these samples (as it must be).
        let forward_a = map.sample_forward_a();
        let forward_a = if forward_a.len() == count {
            forward_a
        } else {
            &[]
        };
        let inv_texel = 1.0 / self.texel_m;
        let ribbons = Ribbons {
            input,
            proj: map.projection(),
            forward_a,
            origin: self.origin,
            inv_texel,
            half_w: 0.5 * width_m * inv_texel,
            dims: self.dims,
            solid_texels: SolidTexels {
                sat: &self.solid_sat,
                dims: self.dims,
            },
            tiles: &self.limit_tiles,
        };
        let chunks = ribbons.collect(count, &mut self.chunk_pieces);
        self.sort_pieces(chunks);
        self.deposit_waves();
    }

    /// Sizes the texture over `lo..hi` widened by `margin_m` each side, with texels of
    /// `texel_m` (coarser where that would take more than [`MAX_TEXELS_PER_AXIS`]), every sum
    /// 0. Returns `false`, leaving the texture empty, when
    /// the extent gives no finite texel.
    fn lay_out(&mut self, lo: Vec2, hi: Vec2, margin_m: f32, texel_m: f32) -> bool {
        let margin = Vec2::splat(margin_m);
        let (lo, hi) = (lo - margin, hi + margin);
        let extent = (hi - lo).max(Vec2::ZERO);
        let mut texel_m = texel_m;
        let wanted = extent.max_element() / texel_m;
        if wanted.is_nan() || wanted > MAX_TEXELS_PER_AXIS as f32 {
            texel_m = extent.max_element() / MAX_TEXELS_PER_AXIS as f32;
        }
        if !(texel_m > 0.0 && texel_m.is_finite() && lo.is_finite()) {
            self.dims = [0, 0];
            self.sums.clear();
            return false;
        }
        self.origin = lo;
        self.texel_m = texel_m;
        let dims = [
            ((extent.x / texel_m).ceil() as usize).clamp(1, MAX_TEXELS_PER_AXIS),
            ((extent.y / texel_m).ceil() as usize).clamp(1, MAX_TEXELS_PER_AXIS),
        ];
        self.dims = dims;
        self.sums.clear();
        self.sums.resize(dims[0] * dims[1], Vec3::ZERO);
        true
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
