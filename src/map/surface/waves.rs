//! The pieces deposited into the texture in waves of at most [`WAVE_PIECES`], in their order
//! (so what a texel adds keeps the pieces' order; a wave's texels are held at once, the whole
//! texture's would be 14 M for the dense preset).
//!
//! Per wave: each piece's texels gathered once, in parallel over runs of [`GATHER_RUN`] pieces,
//! each run into its own buffer (its overlaps in front of the solids, and their sum, which
//! turns its loss into what a unit of overlap deposits per texel area); then each band of
//! texel rows adds the wave's pieces that reach it, in order. A wave's pieces lie in a few
//! bands (they are sorted by first row), so its deposit runs on about one thread (curly:
//! 4.2–4.9 ms on 2 threads, 5.1–5.5 on 1); it runs beside the next wave's gather, which has
//! its own buffers. The deposits still go wave after wave, so each texel adds in the pieces'
//! order and the texture is the same bits for any thread count.

use super::ribbon::{Piece, deposit};
use super::{BAND_ROWS, SurfaceShadow};
use glam::Vec3;
use rayon::prelude::*;

/// Sorted pieces whose texels one parallel task gathers.
const GATHER_RUN: usize = 256;
/// Pieces whose texels are gathered and deposited at a time (a multiple of [`GATHER_RUN`]).
pub(super) const WAVE_PIECES: usize = 64 * GATHER_RUN;

/// What the waves work with: the texture's size, each texel's
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
    /// Deposits the sorted pieces into the texture, wave after wave (see the module doc).
    pub(super) fn deposit_waves(&mut self) {
        let pieces = &mut self.pieces;
        let count = pieces.len();
        let waves = count.div_ceil(WAVE_PIECES);
        let range = |k: usize| k * WAVE_PIECES..((k + 1) * WAVE_PIECES).min(count);
        let inv_texel = 1.0 / self.texel_m;
        let wave = Wave {
            cols: self.dims[1],
            rows: self.dims[0],
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
}
