//! The map's samples as ribbons across the texture, in the order the texture adds them.
//!
//! A sample at p with tangent u stands for a piece of strand ℓ_s long (`MapBuildInput::span_m`,
//! the whole piece also where a tapered tip has fewer fibres) carrying F·2r·ℓ·sin ψ crossings
//! (ℓ its fibre length; sin ψ, or the lateral scale of a point light, from
//! `Projection::strand`) and the loss Σ n(1 − ā_f). Its ribbon runs between the images of
//! p ± u·ℓ_s/2 across the light, [`super::ribbon_width_m`] wide. Samples that draw nothing
//! (non-finite, no loss, off the texture, no surface reads them, wholly behind the first
//! solid: `limits.rs`) make no piece.
//!
//! Samples are turned into pieces in parallel over fixed chunks, each keeping its pieces in
//! sample order, and the pieces sorted by (first row, input order) with a radix sort of keys,
//! so the order, and with it every texel's sum, does not depend on the thread count.
//! Rejected, measured (curly, 2 threads): one slot per sample (a `None` piece for a sample that
//! draws nothing, 60% of curly's) sorted by `par_sort_unstable_by_key` writes 29 MB of 72-byte
//! pieces and sorts them: 13–14 ms and 6–8 ms of the texture's 45.

use super::limits::{LimitTiles, SolidTexels};
use super::ribbon::Piece;
use super::{BAND_ROWS, SurfaceShadow};
use crate::keysort::sort_keys;
use crate::map::{MapBuildInput, Projection};
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// Samples per parallel job turned into pieces (fixed, so their order does not depend on the
/// thread count), and the bits of a piece's position that hold its place in its job's list.
pub(super) const PIECE_CHUNK: usize = 4096;
const PIECE_CHUNK_BITS: usize = 12;
const _: () = assert!(PIECE_CHUNK == 1 << PIECE_CHUNK_BITS);

/// How samples become ribbons in the texture: its frame, size and texel, the ribbons'
/// half-width, and what decides that a ribbon draws nothing.
pub(super) struct Ribbons<'a> {
    pub(super) input: &'a MapBuildInput<'a>,
    pub(super) proj: &'a Projection,
    /// Each sample's clamped ā_f as the map's fill evaluated it, or empty.
    pub(super) forward_a: &'a [Vec3],
    /// Texel (0, 0)'s corner (map metres across the light), and texels per metre.
    pub(super) origin: Vec2,
    pub(super) inv_texel: f32,
    /// Half the ribbon's width, texels.
    pub(super) half_w: f32,
    pub(super) dims: [usize; 2],
    pub(super) solid_texels: SolidTexels<'a>,
    pub(super) tiles: &'a LimitTiles,
}

impl Ribbons<'_> {
    /// Sample `s`'s ribbon with its loss, or `None` when it draws nothing.
    fn piece(&self, s: usize) -> Option<Piece> {
        let input = self.input;
        let (p, u, len) = (input.positions[s], input.tangents[s], input.lengths_m[s]);
        let share = input.fiber_share.get(s).copied().unwrap_or(1.0);
        if !(p.is_finite() && u.is_finite() && len.is_finite() && len > 0.0 && share > 0.0) {
            return None;
        }
        let piece_m = input.span_m(s);
        let (_, across, _) = self.proj.strand(p, u);
        let r = input.fiber.params().radius_m;
        let crossings = input.fibers_per_strand * 2.0 * r * len * across;
        let a_f = match self.forward_a.get(s) {
            Some(a) if !a.x.is_nan() => *a,
            _ => input
                .fiber
                .forward_scatter(u.dot(self.proj.toward_light(p)).clamp(-1.0, 1.0))
                .a_f
                .clamp(Vec3::ZERO, Vec3::ONE),
        };
        let loss = (Vec3::ONE - a_f) * crossings;
        if loss.max_element().is_nan() || loss.max_element() <= 0.0 {
            return None;
        }
        // Texel coordinates across the light, and depth along it.
        let lat = |q: Vec3| {
            let m = self.proj.point(q);
            ((Vec2::new(m.y, m.z) - self.origin) * self.inv_texel, m.x)
        };
        let ((a, depth_a), (b, depth_b)) =
            (lat(p - u * (0.5 * piece_m)), lat(p + u * (0.5 * piece_m)));
        if !(a.is_finite() && b.is_finite() && depth_a.is_finite() && depth_b.is_finite()) {
            return None;
        }
        let mut piece = Piece::new(a, b, (depth_a, depth_b), self.half_w, self.dims)?;
        if !self.solid_texels.reads_any(&piece) || self.tiles.behind_all(&piece) {
            return None;
        }
        piece.loss = loss;
        Some(piece)
    }

    /// The pieces of samples `0..count` that draw, per fixed chunk of [`PIECE_CHUNK`] samples
    /// in sample order, into `chunk_pieces` (grown as needed); returns the chunks used.
    pub(super) fn collect(&self, count: usize, chunk_pieces: &mut Vec<Vec<Piece>>) -> usize {
        let chunks = count.div_ceil(PIECE_CHUNK);
        if chunk_pieces.len() < chunks {
            chunk_pieces.resize_with(chunks, Vec::new);
        }
        chunk_pieces[..chunks]
            .par_iter_mut()
            .enumerate()
            .for_each(|(c, out)| {
                out.clear();
                // Exact, so the memory budget counts each chunk once.
                out.reserve_exact(PIECE_CHUNK);
                out.extend(
                    (c * PIECE_CHUNK..((c + 1) * PIECE_CHUNK).min(count))
                        .filter_map(|s| self.piece(s)),
                );
            });
        chunks
    }
}

impl SurfaceShadow {
    /// The pieces of the first `chunks` of `chunk_pieces` into `pieces`, by first row then
    /// input order: keys of (first row, position), the position (chunk, place in it) ascending
    /// in input order, sorted by radix. Then per band of texel rows, the first piece that may
    /// reach it (`band_first`).
    pub(super) fn sort_pieces(&mut self, chunks: usize) {
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
        let bands = self.dims[0].div_ceil(BAND_ROWS);
        let tallest = pieces.iter().map(|p| p.x1 - p.x0).max().unwrap_or(0) as usize;
        self.band_first.clear();
        self.band_first.extend((0..=bands).map(|b| {
            let from = (b * BAND_ROWS).saturating_sub(tallest) as u32;
            pieces.partition_point(|p| p.x0 < from) as u32
        }));
    }
}
