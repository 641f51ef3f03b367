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

use super::bundle::Profiles;
use super::polyline::{LineWidth, MAX_WIDTH_PX, Polylines};
use super::samples::{SAMPLE_REACH, sample_reach};
use crate::raster::camera::View;

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
    /// Half the drawn width in pixels, and the coverage multiplier (opacity).
    pub(super) half_w: f32,
    pub(super) opacity: f32,
    /// Where its [`Fibres`] are in the draw call's table (the segment's index), or
    /// [`NO_FIBRES`] for a line drawn as a plain band.
    pub(super) fibers: u32,
    /// Free end of a polyline (box-filtered end) at the start / end.
    pub(super) cap0: bool,
    pub(super) cap1: bool,
    /// Covered rows, inclusive.
    pub(super) row_lo: u32,
    pub(super) row_hi: u32,
    /// Its index in the draw call (`k` of [`setup_segment`]).
    pub(super) k: u32,
}

/// Projected bundle radius (pixels) from which a bundle's fibres are drawn, blended in until
/// they are drawn alone from `BUNDLE_FULL_PX`: below, 2r is under a twentieth of a pixel for
/// the presets (r/R ≈ 0.017) and the fibres would average to the band anyway.
const BUNDLE_FROM_PX: f32 = 3.0;
const BUNDLE_FULL_PX: f32 = 6.0;

/// Sharpest joint mitred: a turn of at most 60° (cosine 0.5); a sharper one is cut square, so
/// its mitre never reaches more than tan 30° ≈ 0.58 widths past the joint.
const MITRE_MIN_COS: f32 = 0.5;

/// [`Seg::fibres`] of a plain line.
pub(super) const NO_FIBRES: u32 = u32::MAX;

/// How a bundle's segment is drawn as its fibres (`bundle.rs`); kept beside the segments, one
/// per segment, only in a draw call with bundles, so plain lines stay small.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Fibers {
    /// 1 / the bundle's projected radius R in pixels, the scale from its profile to coverage
    /// (k·`w_px / A(+∞)`, k the blend from the band), and its pattern's first sample.
    pub(super) inv_r: f32,
    pub(super) cov_scale: f32,
    pub(super) pattern: u32,
    /// The band it is blended from: half width in pixels, and its weight (1 − k, times its
    /// opacity relative to the segment's).
    pub(super) band_hw: f32,
    pub(super) band_scale: f32,
    /// Mitred joints: a pixel belongs to the segment where `b0·r ≥ 0` and `b1·(r − e) < 0`, r
    /// from the first end, e = end − first end, b0 and b1 the mean unit directions of the
    /// joints (the segment's own direction at a free end or a sharp bend); `ext0`, `ext1` how
    /// far the mitre reaches past each end along the axis, pixels.
    pub(super) b0: (f32, f32),
    pub(super) b1: (f32, f32),
    pub(super) e: (f32, f32),
    pub(super) ext0: f32,
    pub(super) ext1: f32,
}

/// Per-frame constants of the set-up and raster passes.
pub(super) struct Params<'a> {
    pub(super) view: View,
    /// How wide segments are drawn.
    pub(super) width_model: LineWidth,
    /// Coverage multiplier of the style, in (0, 1].
    pub(super) opacity: f32,
    pub(super) width: usize,
    pub(super) height: usize,
    /// The lines' bundle profiles, when they stand for bundles (width model `Projected` only).
    pub(super) bundle: Option<&'a Profiles>,
}

/// A segment's colours at its two (clipped) ends, linear RGB: its fragments are composited
/// with `c0 + (c1 − c0)·t`, t their place along it. Kept apart from [`Seg`] (by segment
/// index), so fragments can be emitted before the hair is shaded.
pub(super) type SegColors = [Vec3; 2];

/// Clips and projects segment `k` of `lines`; `None` when nothing of it can be seen. A
/// bundle's segment drawn as its fibres comes with its [`Fibres`] (and [`Seg::fibres`] = k);
/// every segment with its colours at its clipped ends.
#[inline]
pub(super) fn setup_segment(
    p: &Params,
    lines: &Polylines,
    k: usize,
) -> Option<(Seg, Fibers, SegColors)> {
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
    let (mut half_w, mut opacity) = drawn_width(p, wm0 / v0.z, wm1 / v1.z)?;
    let (mut inv_r, mut cov_scale, mut pattern) = (0.0, 0.0, 0);
    let (band_hw, mut band_scale) = (half_w, 1.0);
    if let (Some(prof), Some(b)) = (p.bundle, lines.bundle) {
        // The bundle's projected radius (at most half the widest line). Its fibres are drawn
        // where they can be told apart: blended in from BUNDLE_FROM_PX to BUNDLE_FULL_PX, the
        // band of their summed width below (the same coverage, so nothing pops).
        let w_px = projected_px(p, wm0 / v0.z, wm1 / v1.z);
        let r_px = p.view.focal_px * b.radius_m * 0.5 * (1.0 / v0.z + 1.0 / v1.z);
        let r_px = r_px.min(0.5 * MAX_WIDTH_PX);
        let k = ((r_px - BUNDLE_FROM_PX) / (BUNDLE_FULL_PX - BUNDLE_FROM_PX)).clamp(0.0, 1.0);
        if k > 0.0 && r_px.is_finite() && w_px.is_finite() && p.opacity > 0.0 {
            // The band's part keeps its own width and opacity (relative to the style's).
            band_scale = (1.0 - k) * opacity / p.opacity;
            // Toward a tip, where a share s of the fibres is left (its width over the full
            // bundle's fibres, r·T = 2Fr in pixels), the ones left are the innermost (the
            // placement's spiral fills the disc from its centre), so the bundle narrows to
            // √s of its radius; the coverage stays the width's whatever the radius.
            let share = (w_px / (prof.total * r_px)).clamp(0.0, 1.0);
            let r_draw = (r_px * share.sqrt()).max(0.5);
            half_w = half_w.max(r_draw * (1.0 + prof.rho));
            opacity = p.opacity;
            inv_r = 1.0 / r_draw;
            cov_scale = k * w_px / prof.total;
            pattern = Profiles::pattern_of(line);
        }
    }
    let (mut x0, mut y0) = view.view_to_pixel(v0);
    let (mut x1, mut y1) = view.view_to_pixel(v1);
    let (mut iz0, mut iz1) = (1.0 / v0.z, 1.0 / v1.z);
    let (dx, dy) = (x1 - x0, y1 - y0);
    // A projection that overflows f32 (points ~1e30 m off axis) is dropped here.
    if !(dx.is_finite() && dy.is_finite() && iz0.is_finite() && iz1.is_finite()) {
        return None;
    }

    // Guard rectangle, in float, before anything becomes an integer (Liang-Barsky).
    let g = half_w + SAMPLE_REACH + 2.0;
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
    // How far from the axis a pixel centre can be covered: a plain line covers sub-samples
    // up to `sample_reach` from its centre, a bundle's fibres a box half a pixel wide.
    let reach = half_w
        + if inv_r > 0.0 {
            0.5
        } else {
            sample_reach(ux, uy)
        };
    // Mitred joints for bundles: the parallel stripes of consecutive segments meet on the
    // bisector of their joint, so cutting each segment there (instead of square to its axis)
    // tiles the joint without the notch outside and overlap inside a wide line would show.
    let (mut b0, mut b1, mut ext0, mut ext1) = ((ux, uy), (ux, uy), 0.0f32, 0.0f32);
    // (Only where the fibres are drawn: a band of a pixel or two has no notch to speak of,
    // and the mitre's longer reach would cost every thin segment. Where a strand crosses
    // R = BUNDLE_FROM_PX, the band's side of that one joint is cut square: a sliver of at most
    // 3 px × tan(turn/2) overlaps or stays open there.)
    if inv_r > 0.0 && len > 0.0 {
        let neighbour = |idx: usize| -> Option<(f32, f32)> {
            let v = view.to_view(*lines.points.get(idx)?);
            (v.is_finite() && v.z >= near).then(|| view.view_to_pixel(v))
        };
        let joint = |q: (f32, f32), toward: bool| -> Option<((f32, f32), f32)> {
            // Unit direction of the neighbouring segment, on screen.
            let (ex, ey) = if toward {
                (x0 - q.0, y0 - q.1)
            } else {
                (q.0 - x1, q.1 - y1)
            };
            let l = (ex * ex + ey * ey).sqrt();
            if !(l > 1e-6) {
                return None;
            }
            let (nx, ny) = (ex / l, ey / l);
            let cos_turn = nx * ux + ny * uy;
            if !(cos_turn > MITRE_MIN_COS) {
                return None;
            }
            let (mx, my) = (nx + ux, ny + uy);
            let m = (mx * mx + my * my).sqrt();
            // |tan(turn/2)| = |sin| / (1 + cos), the mitre's reach per pixel of width.
            let tan_half = (nx * uy - ny * ux).abs() / (1.0 + cos_turn);
            Some(((mx / m, my / m), tan_half))
        };
        if !cap0
            && t0 <= 0.0
            && i > 0
            && let Some((b, t)) = neighbour(a - 1).and_then(|q| joint(q, true))
        {
            (b0, ext0) = (b, half_w * t + 0.5);
        }
        if !cap1
            && t1 >= 1.0
            && i + 1 < segs_per_line
            && let Some((b, t)) = neighbour(a + 2).and_then(|q| joint(q, false))
        {
            (b1, ext1) = (b, half_w * t + 0.5);
        }
    }
    let r = reach + ext0.max(ext1);
    let (dxdy, half_span) = if uy.abs() > 1e-6 {
        (ux / uy, reach / uy.abs())
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
    let fibers = Fibers {
        inv_r,
        cov_scale,
        pattern,
        band_hw,
        band_scale,
        b0,
        b1,
        e: (x1 - x0, y1 - y0),
        ext0,
        ext1,
    };
    let seg = Seg {
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
        half_w,
        opacity,
        fibers: if inv_r > 0.0 { k as u32 } else { NO_FIBRES },
        cap0,
        cap1,
        row_lo: row_lo as u32,
        row_hi: row_hi as u32,
        k: k as u32,
    };
    Some((seg, fibers, [c0, c1]))
}

/// A segment's projected width in pixels, from its ends' physical widths over their depths
/// (metres per metre): the mean of the ends' `f·w/z`.
#[inline]
fn projected_px(p: &Params, w_over_z0: f32, w_over_z1: f32) -> f32 {
    p.view.focal_px * 0.5 * (w_over_z0 + w_over_z1)
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
            let w_px = projected_px(p, w_over_z0, w_over_z1);
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
