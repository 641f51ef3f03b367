//! Segment set-up: world segment -> clipped screen segment ready to rasterise.
//!
//! What: [`setup_segment`] takes segment `k` of a [`Polylines`] to view space, clips it to the
//! near plane, projects it, clips it to a guard rectangle around the image and precomputes what
//! the per-row and per-pixel loops of `lines.rs` need ([`Seg`]).
//!
//! How and why: the near-plane clip happens in view space, before the perspective division,
//! which would mirror points behind the eye and blow up points near it. The screen clip
//! (Liang-Barsky, skipped when both ends are inside) happens in float *before* anything
//! becomes an index: huge, infinite or NaN coordinates are rejected or cut down to a few image
//! sizes here, so no later `as` conversion can overflow and the per-pixel arithmetic (offsets
//! from the segment's first end) keeps its precision. Colour at a clip point is
//! perspective-correct (c/z and 1/z are linear in screen space); the clipped end loses its
//! end-cap, which is off-screen or at the near plane anyway.

use glam::Vec3;

use super::camera::View;
use super::polyline::{LineWidth, MAX_WIDTH_PX, Polylines};

/// A segment ready to rasterise, in pixel coordinates.
#[derive(Clone, Copy, Debug)]
pub(super) struct Seg {
    pub(super) x0: f32,
    pub(super) y0: f32,
    /// Unit direction on screen, `(1, 0)` for a zero-length segment.
    pub(super) ux: f32,
    pub(super) uy: f32,
    pub(super) len: f32,
    /// `1 / len`, 0 for a zero-length segment.
    pub(super) inv_len: f32,
    /// Row spans: the axis crosses row centre y at `x0 + (y − y0)·ux/uy`, the strip of
    /// half-width `reach` is `reach/|uy|` wide either side; 0 and +inf when `uy` ≈ 0.
    pub(super) dxdy: f32,
    pub(super) half_span: f32,
    /// `1/ux`, 0 when `ux` ≈ 0.
    pub(super) inv_ux: f32,
    /// 1 / view depth at the two ends, 1/m.
    pub(super) iz0: f32,
    pub(super) iz1: f32,
    pub(super) c0: Vec3,
    pub(super) c1: Vec3,
    /// Half the drawn width in pixels, and the coverage multiplier (opacity).
    pub(super) half_w: f32,
    pub(super) opacity: f32,
    /// Free end of a polyline (box-filtered end) at the start / end.
    pub(super) cap0: bool,
    pub(super) cap1: bool,
    /// Covered rows, inclusive.
    pub(super) row_lo: u32,
    pub(super) row_hi: u32,
}

/// Per-frame constants of the set-up and raster passes.
pub(super) struct Params {
    pub(super) view: View,
    /// How wide segments are drawn.
    pub(super) width_model: LineWidth,
    /// Coverage multiplier of the style, in (0, 1].
    pub(super) opacity: f32,
    pub(super) width: usize,
    pub(super) height: usize,
}

/// Clips and projects segment `k` of `lines`; `None` when nothing of it can be seen.
#[inline]
pub(super) fn setup_segment(p: &Params, lines: &Polylines, k: usize) -> Option<Seg> {
    let n = lines.points_per_line;
    let segs_per_line = n.checked_sub(1).filter(|&s| s > 0)?;
    let (line, i) = (k / segs_per_line, k % segs_per_line);
    let a = line * n + i;
    let (w0, w1) = (*lines.points.get(a)?, *lines.points.get(a + 1)?);
    let (mut c0, mut c1) = (*lines.colors.get(a)?, *lines.colors.get(a + 1)?);
    if !(c0.is_finite() && c1.is_finite()) {
        return None;
    }
    let view = &p.view;
    let (mut v0, mut v1) = (view.to_view(w0), view.to_view(w1));
    if !(v0.is_finite() && v1.is_finite()) {
        return None;
    }
    let (mut cap0, mut cap1) = (i == 0, i + 1 == segs_per_line);
    // Physical widths (metres) at the two ends, when the width model reads them.
    let (mut wm0, mut wm1) = match p.width_model {
        LineWidth::Pixels(_) => (0.0, 0.0),
        LineWidth::Projected { .. } => (*lines.widths_m.get(a)?, *lines.widths_m.get(a + 1)?),
    };

    // Near plane, in view space: the perspective division is only meaningful for depth > 0.
    let near = view.near_m;
    if v0.z < near && v1.z < near {
        return None;
    }
    if v0.z < near || v1.z < near {
        let t = (near - v0.z) / (v1.z - v0.z);
        let v = v0.lerp(v1, t);
        let c = c0.lerp(c1, t);
        let wm = wm0 + (wm1 - wm0) * t;
        let v = Vec3::new(v.x, v.y, near);
        if v0.z < near {
            (v0, c0, wm0, cap0) = (v, c, wm, false);
        } else {
            (v1, c1, wm1, cap1) = (v, c, wm, false);
        }
    }
    let (half_w, opacity) = drawn_width(p, wm0 / v0.z, wm1 / v1.z)?;
    let reach = half_w + 0.5;
    let (mut x0, mut y0) = view.view_to_pixel(v0);
    let (mut x1, mut y1) = view.view_to_pixel(v1);
    let (mut iz0, mut iz1) = (1.0 / v0.z, 1.0 / v1.z);
    let (dx, dy) = (x1 - x0, y1 - y0);
    // A projection that overflows f32 (points ~1e30 m off axis) is dropped here.
    if !(dx.is_finite() && dy.is_finite() && iz0.is_finite() && iz1.is_finite()) {
        return None;
    }

    // Guard rectangle, in float, before anything becomes an integer (Liang-Barsky).
    let g = reach + 2.0;
    let (lo_x, hi_x) = (-g, p.width as f32 + g);
    let (lo_y, hi_y) = (-g, p.height as f32 + g);
    let inside = |x: f32, y: f32| x >= lo_x && x <= hi_x && y >= lo_y && y <= hi_y;
    let (mut t0, mut t1) = (0.0_f32, 1.0_f32);
    let clip_edges = if inside(x0, y0) && inside(x1, y1) {
        [(0.0, 0.0); 4]
    } else {
        [
            (-dx, x0 - lo_x),
            (dx, hi_x - x0),
            (-dy, y0 - lo_y),
            (dy, hi_y - y0),
        ]
    };
    for (q, r) in clip_edges {
        if q == 0.0 {
            if r < 0.0 {
                return None;
            }
        } else {
            let t = r / q;
            if q < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    if !(t0 <= t1) {
        return None;
    }
    if t0 > 0.0 || t1 < 1.0 {
        // Colour is perspective-correct at the clip points: c/z and 1/z are screen-linear.
        let at = |t: f32| {
            let iz = iz0 + (iz1 - iz0) * t;
            let c = (c0 * iz0).lerp(c1 * iz1, t) / iz;
            (x0 + dx * t, y0 + dy * t, iz, c)
        };
        let (ax, ay, aiz, ac) = at(t0);
        let (bx, by, biz, bc) = at(t1);
        cap0 &= t0 <= 0.0;
        cap1 &= t1 >= 1.0;
        (x0, y0, iz0, c0, x1, y1, iz1, c1) = (ax, ay, aiz, ac, bx, by, biz, bc);
        if !(c0.is_finite() && c1.is_finite() && iz0 > 0.0 && iz1 > 0.0) {
            return None;
        }
    }

    let (dx, dy) = (x1 - x0, y1 - y0);
    let len = (dx * dx + dy * dy).sqrt();
    let (ux, uy, len, inv_len) = if len > 1e-6 {
        (dx / len, dy / len, len, 1.0 / len)
    } else {
        (1.0, 0.0, 0.0, 0.0)
    };
    let r = reach;
    let (dxdy, half_span) = if uy.abs() > 1e-6 {
        (ux / uy, r / uy.abs())
    } else {
        (0.0, f32::INFINITY)
    };
    let inv_ux = if ux.abs() > 1e-6 { 1.0 / ux } else { 0.0 };

    // Rows whose centre (j + 0.5) lies within `reach` of the segment's y extent.
    let (ymin, ymax) = (y0.min(y1) - r, y0.max(y1) + r);
    let (xmin, xmax) = (x0.min(x1) - r, x0.max(x1) + r);
    let last_row = (p.height - 1) as f32;
    let row_lo = (ymin - 0.5).ceil().max(0.0);
    let row_hi = (ymax - 0.5).floor().min(last_row);
    if !(row_lo <= row_hi) || xmax < 0.0 || xmin > p.width as f32 {
        return None;
    }
    Some(Seg {
        x0,
        y0,
        ux,
        uy,
        len,
        inv_len,
        dxdy,
        half_span,
        inv_ux,
        iz0,
        iz1,
        c0,
        c1,
        half_w,
        opacity,
        cap0,
        cap1,
        row_lo: row_lo as u32,
        row_hi: row_hi as u32,
    })
}

/// Half the drawn width in pixels and the coverage multiplier of a segment whose ends have
/// physical width over depth `w_over_z0`, `w_over_z1` (metres per metre; read only by
/// [`LineWidth::Projected`]). `None` when the segment has no width to draw.
///
/// Projected width `w_px = f·(w0/z0 + w1/z1)/2` (f the focal length in pixels): the mean of
/// the ends' projected widths, exact for the area of the screen trapezoid a segment of
/// linearly varying projected width covers. Below `min_px`, the segment is drawn `min_px`
/// wide with its opacity scaled by `w_px / min_px`, which conserves length × width × opacity.
#[inline]
fn drawn_width(p: &Params, w_over_z0: f32, w_over_z1: f32) -> Option<(f32, f32)> {
    match p.width_model {
        LineWidth::Pixels(w) => Some((0.5 * w.min(MAX_WIDTH_PX), p.opacity)),
        LineWidth::Projected { min_px } => {
            let w_px = p.view.focal_px * 0.5 * (w_over_z0 + w_over_z1);
            // `!(a > 0)` also rejects NaN; +inf (a point at the eye) is capped below.
            if !(w_px > 0.0) {
                return None;
            }
            if w_px < min_px {
                Some((0.5 * min_px.min(MAX_WIDTH_PX), p.opacity * (w_px / min_px)))
            } else {
                Some((0.5 * w_px.min(MAX_WIDTH_PX), p.opacity))
            }
        }
    }
}
