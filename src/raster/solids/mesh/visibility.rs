//! Mesh visibility, per band of rows: four samples per pixel in a rotated grid (offsets 1/8,
//! 3/8, 5/8, 7/8, the pattern of 4× multisampling) keep the nearest triangle and its depth
//! (1/z interpolated linearly on screen, exact under perspective), with strict depth tests
//! in input order, so the first triangle wins a tie.
//!
//! Each row of a triangle visits only the columns its strip can reach ([`row_columns`], not
//! its whole screen box: half of it for a typical triangle, nearly all of it for a sliver),
//! and a pixel's four samples are tested side by side in one vector, lane by lane the same
//! arithmetic as one sample at a time (`screen_tri::edges`): the same bits (the tests hold the
//! per-sample loop over the whole box as reference), and the frame's raster stage
//! 13.9 → 12.4 ms on 2 threads at 1280×720 (BENCHMARKS.md).

use glam::{Vec2, Vec4};

use super::screen_tri::{ScreenTri, screen_box};
use crate::tri_span;

/// Samples per pixel, and their offsets inside the pixel (rotated grid).
pub(super) const SAMPLES: usize = 4;
pub(super) const SAMPLE_OFFSETS: [(f32, f32); SAMPLES] = [
    (0.375, 0.125),
    (0.875, 0.375),
    (0.125, 0.625),
    (0.625, 0.875),
];
/// A sample that no triangle covers.
pub(super) const NONE: u32 = u32::MAX;

/// One band of rows of the image.
pub(super) struct Band {
    pub(super) y0: usize,
    pub(super) rows: usize,
    pub(super) w: usize,
    /// The columns `span.0 .. span.1` that its triangles can touch.
    pub(super) span: (usize, usize),
}

/// The columns of pixel row `y` (within `x0..x1`) whose samples the triangle with corners
/// `p` (as (y, x)) can cover: the pixels meeting its span over the row's strip
/// (`crate::tri_span::span`); the whole `x0..x1` when it cannot narrow.
fn row_columns(p: [Vec2; 3], narrow: bool, y: usize, (x0, x1): (usize, usize)) -> (usize, usize) {
    if !narrow {
        return (x0, x1);
    }
    let Some((lo, hi)) = tri_span::span(p, (y as f32, y as f32 + 1.0)) else {
        return (x0, x0);
    };
    let xa = (lo.floor().max(x0 as f32) as usize).max(x0);
    let xb = ((hi.floor() + 1.0).max(0.0) as usize).min(x1);
    (xa, xb.max(xa))
}

impl Band {
    /// The columns `x0 .. x1` whose samples a triangle with screen box `(lo, hi)` can cover.
    #[inline]
    pub(super) fn columns(&self, (lo, hi): (Vec2, Vec2)) -> (usize, usize) {
        let x0 = lo.x.max(0.0).floor() as usize;
        let x1 = (hi.x.min(self.w as f32).max(0.0).ceil() as usize).min(self.w);
        (x0, x1)
    }

    /// Keeps, per sample of the band, the nearest triangle: triangle `t` (number `index`)
    /// where it covers a sample nearer than `s_depth` holds, which then takes its depth.
    ///
    /// Each row visits only the columns its strip of the triangle can reach
    /// ([`row_columns`]), and a pixel's four samples are tested side by side, each lane with
    /// the operations of [`edges`](super::screen_tri::edges) in the same order, so a sample's verdict and depth are the
    /// bits the one-sample-at-a-time loop gives.
    pub(super) fn rasterise(
        &self,
        t: &ScreenTri,
        index: u32,
        s_depth: &mut [f32],
        s_tri: &mut [u32],
    ) {
        let (lo, hi) = screen_box(t);
        let (x0, x1) = self.columns((lo, hi));
        let r0 = (lo.y.max(self.y0 as f32).floor() as usize).max(self.y0);
        let r1 = (hi.y.min((self.y0 + self.rows) as f32).ceil() as usize).min(self.y0 + self.rows);
        let inv_area = 1.0 / t.area2;
        let [p0, p1, p2] = t.p;
        let p_yx = t.p.map(|q| Vec2::new(q.y, q.x));
        let narrow = tri_span::narrowable(p_yx);
        let (ox, oy) = (
            Vec4::from(SAMPLE_OFFSETS.map(|o| o.0)),
            Vec4::from(SAMPLE_OFFSETS.map(|o| o.1)),
        );
        for y in r0..r1 {
            let row = (y - self.y0) * self.w;
            let (xa, xb) = row_columns(p_yx, narrow, y, (x0, x1));
            let qy = Vec4::splat(y as f32) + oy;
            // (pᵢ − q).y for the three corners, shared by the row.
            let dy = [
                Vec4::splat(p0.y) - qy,
                Vec4::splat(p1.y) - qy,
                Vec4::splat(p2.y) - qy,
            ];
            for x in xa..xb {
                let qx = Vec4::splat(x as f32) + ox;
                let dx = [
                    Vec4::splat(p0.x) - qx,
                    Vec4::splat(p1.x) - qx,
                    Vec4::splat(p2.x) - qx,
                ];
                // `edges` lane-wise: (pa − q).perp_dot(pb − q) = dxa·dyb − dya·dxb.
                let e0 = dx[1] * dy[2] - dy[1] * dx[2];
                let e1 = dx[2] * dy[0] - dy[2] * dx[0];
                let e2 = dx[0] * dy[1] - dy[0] * dx[1];
                let (l0, l1, l2) = (e0 * inv_area, e1 * inv_area, e2 * inv_area);
                let inside = l0.cmpge(Vec4::ZERO) & l1.cmpge(Vec4::ZERO) & l2.cmpge(Vec4::ZERO);
                if !inside.any() {
                    continue;
                }
                let inv_z = l0 * t.inv_z[0] + l1 * t.inv_z[1] + l2 * t.inv_z[2];
                let mask = inside.bitmask();
                let inv_z = inv_z.to_array();
                let k0 = (row + x) * SAMPLES;
                for (s, &iz) in inv_z.iter().enumerate() {
                    let k = k0 + s;
                    // Nearer: 1/z larger. `inv_z·depth > 1` also holds for an infinite depth.
                    if mask & (1 << s) != 0 && iz > 0.0 && iz * s_depth[k] > 1.0 {
                        s_depth[k] = 1.0 / iz;
                        s_tri[k] = index;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests;
