//! Rasterising a triangle mesh across the light into the grid: each texel centre inside a
//! triangle's (y, z) projection takes the depth of the triangle's plane there,
//!
//!   d = Σ λₖ·xₖ,  λ₀ = (q₁ − p) × (q₂ − p) / (2A), and cyclically,
//!
//! and the texel keeps the smallest depth of all solids and triangles (the entry point; front
//! and back faces alike, so the mesh need not be closed or consistently wound). A texel row
//! visits only the columns its part of the triangle can reach (`crate::tri_span`), four
//! centres to a vector. O(texels covered × layers), in parallel over bands of texel rows.

use crate::tri_span;
use glam::{Vec2, Vec3, Vec4};
use rayon::prelude::*;

/// Texel rows per parallel band of the triangle raster.
pub(super) const RASTER_BAND_ROWS: usize = 16;

/// A triangle across the light, ready to rasterise into a grid: its corners in texel
/// coordinates (texel centres at integers), their depths, the inverse of twice its signed
/// area, and the texel centres its box holds (rows `i0..=i1`, columns `j0..=j1`).
#[derive(Clone, Copy, Debug)]
pub(super) struct TriangleSetup {
    pub(super) q: [Vec2; 3],
    pub(super) depth: [f32; 3],
    pub(super) inv: f32,
    pub(super) i0: i64,
    pub(super) i1: i64,
    pub(super) j0: i64,
    pub(super) j1: i64,
}

impl TriangleSetup {
    /// The columns of texel row `i` within the box whose centres the triangle can cover:
    /// those inside its span at that row (`crate::tri_span::span`); an empty range
    /// (`j0 > j1`) where it has no part there.
    fn columns(&self, i: i64) -> (i64, i64) {
        match tri_span::span(self.q, (i as f32, i as f32)) {
            Some((lo, hi)) => (
                (lo.ceil() as i64).max(self.j0),
                (hi.floor() as i64).min(self.j1),
            ),
            None => (self.j0, self.j0 - 1),
        }
    }

    /// The triangle with light-frame corners `c` in a grid of `dims` texels of `texel` metres
    /// from `origin`, or `None` when it is edge-on to the light (no area to cover: its
    /// neighbours cover the silhouette) or covers no texel centre.
    pub(super) fn new(c: [Vec3; 3], origin: Vec2, texel: f32, dims: [usize; 2]) -> Option<Self> {
        let q = c.map(|p| (Vec2::new(p.y, p.z) - origin) / texel - 0.5);
        let area2 = (q[1] - q[0]).perp_dot(q[2] - q[0]);
        if area2.is_nan() || area2.abs() <= 1e-9 {
            return None;
        }
        let lo = q[0].min(q[1]).min(q[2]).ceil().max(Vec2::ZERO);
        let hi = q[0].max(q[1]).max(q[2]).floor();
        let (i1, j1) = (
            (hi.x.min(dims[0] as f32 - 1.0)) as i64,
            (hi.y.min(dims[1] as f32 - 1.0)) as i64,
        );
        let (i0, j0) = (lo.x as i64, lo.y as i64);
        (i0 <= i1 && j0 <= j1).then_some(TriangleSetup {
            q,
            depth: c.map(|p| p.x),
            inv: 1.0 / area2,
            i0,
            i1,
            j0,
            j1,
        })
    }

    /// Lowers each texel of rows `band` (`rows`: those rows, `cols` texels each) whose centre
    /// lies inside the triangle to the depth of the triangle's plane there. A row visits only
    /// the columns its part of the triangle can reach (`crate::tri_span`), the same texels
    /// the whole box gave.
    pub(super) fn rasterise(&self, band: std::ops::Range<usize>, cols: usize, rows: &mut [f32]) {
        let (i0, i1) = (
            self.i0.max(band.start as i64),
            self.i1.min(band.end as i64 - 1),
        );
        let q = &self.q;
        let narrow = i0 <= i1 && tri_span::narrowable(*q);
        let (inv, lanes) = (Vec4::splat(self.inv), Vec4::new(0.0, 1.0, 2.0, 3.0));
        for i in i0..=i1 {
            let (j0, j1) = if narrow {
                self.columns(i)
            } else {
                (self.j0, self.j1)
            };
            // Four centres of the row side by side, each lane the arithmetic of one centre
            // p = (i, j) in the order the scalar test had: (qₐ − p).perp_dot(q_b − p) × inv,
            // then the depth as Σ lₖ·depthₖ left to right: the same bits.
            let fi = i as f32;
            let ax = [q[0].x - fi, q[1].x - fi, q[2].x - fi].map(Vec4::splat);
            let mut j = j0;
            while j <= j1 {
                let pj = Vec4::splat(j as f32) + lanes;
                let ay = [
                    Vec4::splat(q[0].y) - pj,
                    Vec4::splat(q[1].y) - pj,
                    Vec4::splat(q[2].y) - pj,
                ];
                let l0 = (ax[1] * ay[2] - ay[1] * ax[2]) * inv;
                let l1 = (ax[2] * ay[0] - ay[2] * ax[0]) * inv;
                let l2 = (ax[0] * ay[1] - ay[0] * ax[1]) * inv;
                let inside =
                    (l0.cmpge(Vec4::ZERO) & l1.cmpge(Vec4::ZERO) & l2.cmpge(Vec4::ZERO)).bitmask();
                if inside != 0 {
                    let d =
                        (l0 * self.depth[0] + l1 * self.depth[1] + l2 * self.depth[2]).to_array();
                    let row = (i as usize - band.start) * cols;
                    for (k, d) in d.iter().enumerate() {
                        let jk = j + k as i64;
                        if inside & (1 << k) != 0 && jk <= j1 {
                            let texel = &mut rows[row + jk as usize];
                            *texel = texel.min(*d);
                        }
                    }
                }
                j += 4;
            }
        }
    }
}
/// Lowers each texel of `depth` (row-major, `cols` texels a row) under a triangle of `setups`
/// to the depth of its plane, in parallel over bands of texel rows, each band taking the
/// triangles that reach it. A texel keeps the minimum depth, which does not depend on the order
/// or the split: the same bits for any thread count.
pub(super) fn rasterise_all(depth: &mut [f32], cols: usize, setups: &[TriangleSetup]) {
    depth
        .par_chunks_mut(RASTER_BAND_ROWS * cols)
        .enumerate()
        // One job per band, as the solids cover few of them (`raster::lines` says why).
        .with_max_len(1)
        .for_each(|(b, rows)| {
            let band = b * RASTER_BAND_ROWS..(b * RASTER_BAND_ROWS + rows.len() / cols);
            for t in setups {
                t.rasterise(band.clone(), cols, rows);
            }
        });
}
