//! Segment set-up: a world segment becomes a clipped screen segment ready to rasterise
//! ([`Seg`]), with its colours at its clipped ends ([`SegColors`]).
//!
//! What: [`setup_segment`] takes segment `k` of a [`Polylines`] to view space, clips it to the
//! near plane, sizes it (`params.rs`; a bundle's fibres, `fibers.rs`), projects it, clips it
//! to a guard rectangle around the image and precomputes what the row walk and the pixel loop
//! need: its axis, the rows it covers, the span of each row around the axis.
//!
//! How and why: the near-plane clip happens in view space, before the perspective division,
//! which would mirror points behind the eye and blow up points near it. The screen clip
//! (Liang–Barsky, skipped when both ends are inside) happens in float *before* anything
//! becomes an index: huge, infinite or NaN coordinates are rejected or cut down to a few image
//! sizes here, so no later `as` conversion can overflow and the per-pixel arithmetic (offsets
//! from the segment's first end) keeps its precision. Colour at a clip point is
//! perspective-correct (c/z and 1/z are linear in screen space); the clipped end loses its
//! end cap, which is off-screen or at the near plane anyway.

use glam::Vec3;

use super::fibers::{Blend, Fibers, Joints, Mitres, blend, mitres};
use super::params::Params;
use super::polyline::{LineWidth, Polylines};
use super::samples::{SAMPLE_REACH, sample_reach};

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
    /// Where its [`Fibers`] are in the draw call's table (the segment's index), or
    /// [`NO_FIBERS`] for a line drawn as a plain band.
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

/// [`Seg::fibers`] of a plain line.
pub(super) const NO_FIBERS: u32 = u32::MAX;

/// A segment's colours at its two (clipped) ends, linear RGB: its fragments are composited
/// with `c0 + (c1 − c0)·t`, t their place along it. Kept apart from [`Seg`] (by segment
/// index), so fragments can be emitted before the hair is shaded.
pub(super) type SegColors = [Vec3; 2];

/// Clips and projects segment `k` of `lines`; `None` when nothing of it can be seen. A
/// bundle's segment drawn as its fibres comes with its [`Fibers`] (and [`Seg::fibers`] = k);
/// every segment with its colours at its clipped ends.
#[inline]
pub(super) fn setup_segment(
    p: &Params,
    lines: &Polylines,
    k: usize,
) -> Option<(Seg, Fibers, SegColors)> {
    let (place, ends) = view_ends(p, lines, k)?;
    let e = clip_near(ends, p.view.near_m)?;
    let (band_hw, band_opacity) = p.drawn_width(e.wm0 / e.v0.z, e.wm1 / e.v1.z)?;
    let fib = lines.bundle.and_then(|b| {
        let (z, wm) = ((e.v0.z, e.v1.z), (e.wm0, e.wm1));
        blend(p, &b, place.line, z, wm, (band_hw, band_opacity))
    });
    let (half_w, opacity, inv_r) = match fib {
        Some(f) => (f.half_w, f.opacity, f.inv_r),
        None => (band_hw, band_opacity, 0.0),
    };
    let s = project_and_clip(p, &e, half_w)?;

    let (dx, dy) = (s.x1 - s.x0, s.y1 - s.y0);
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
    let m = if inv_r > 0.0 && len > 0.0 {
        let joints = Joints {
            ends: [(s.x0, s.y0), (s.x1, s.y1)],
            u: (ux, uy),
            half_w,
            before: (!s.cap0 && s.whole0 && place.i > 0).then(|| place.a - 1),
            after: (!s.cap1 && s.whole1 && place.i + 1 < place.segs_per_line)
                .then_some(place.a + 2),
        };
        mitres(&p.view, lines.points, joints)
    } else {
        Mitres::square((ux, uy))
    };
    let (row_lo, row_hi) = covered_rows(p, &s, reach + m.ext0.max(m.ext1))?;
    let (dxdy, half_span) = if uy.abs() > 1e-6 {
        (ux / uy, reach / uy.abs())
    } else {
        (0.0, f32::INFINITY)
    };
    let inv_ux = if ux.abs() > 1e-6 { 1.0 / ux } else { 0.0 };
    let fibers = fibers_of(fib, band_hw, m, (s.x1 - s.x0, s.y1 - s.y0));
    let seg = Seg {
        x0: s.x0,
        y0: s.y0,
        ux,
        uy,
        len,
        inv_len,
        dxdy,
        half_span,
        inv_ux,
        iz0: s.iz0,
        iz1: s.iz1,
        half_w,
        opacity,
        fibers: if inv_r > 0.0 { k as u32 } else { NO_FIBERS },
        cap0: s.cap0,
        cap1: s.cap1,
        row_lo,
        row_hi,
        k: k as u32,
    };
    Some((seg, fibers, [s.c0, s.c1]))
}

/// Where a segment lies in its polylines: its line, its index within the line, the index of
/// its first point, and the line's segment count.
#[derive(Clone, Copy, Debug)]
struct Place {
    line: usize,
    i: usize,
    a: usize,
    segs_per_line: usize,
}

/// A segment's ends in view space with what is interpolated along it (colour; physical width
/// in metres, 0 where the width model does not read it), and whether each is a free end of
/// its polyline.
#[derive(Clone, Copy, Debug)]
struct ViewEnds {
    v0: Vec3,
    v1: Vec3,
    c0: Vec3,
    c1: Vec3,
    wm0: f32,
    wm1: f32,
    cap0: bool,
    cap1: bool,
}

/// Segment `k` of `lines` in view space; `None` where its points, colours or widths are
/// missing or its points or colours are not finite.
#[inline]
fn view_ends(p: &Params, lines: &Polylines, k: usize) -> Option<(Place, ViewEnds)> {
    let n = lines.points_per_line;
    let segs_per_line = n.checked_sub(1).filter(|&s| s > 0)?;
    let (line, i) = (k / segs_per_line, k % segs_per_line);
    let a = line * n + i;
    let (w0, w1) = (*lines.points.get(a)?, *lines.points.get(a + 1)?);
    let (c0, c1) = (*lines.colors.get(a)?, *lines.colors.get(a + 1)?);
    if !(c0.is_finite() && c1.is_finite()) {
        return None;
    }
    let (v0, v1) = (p.view.to_view(w0), p.view.to_view(w1));
    if !(v0.is_finite() && v1.is_finite()) {
        return None;
    }
    let (wm0, wm1) = match p.width_model {
        LineWidth::Pixels(_) => (0.0, 0.0),
        LineWidth::Projected { .. } => (*lines.widths_m.get(a)?, *lines.widths_m.get(a + 1)?),
    };
    let place = Place {
        line,
        i,
        a,
        segs_per_line,
    };
    let ends = ViewEnds {
        v0,
        v1,
        c0,
        c1,
        wm0,
        wm1,
        cap0: i == 0,
        cap1: i + 1 == segs_per_line,
    };
    Some((place, ends))
}

/// `e` clipped to the near plane at depth `near`, in view space (the perspective division is
/// only meaningful for depth > 0); `None` when all of it is nearer.
#[inline]
fn clip_near(mut e: ViewEnds, near: f32) -> Option<ViewEnds> {
    if e.v0.z < near && e.v1.z < near {
        return None;
    }
    if e.v0.z < near || e.v1.z < near {
        let t = (near - e.v0.z) / (e.v1.z - e.v0.z);
        let v = e.v0.lerp(e.v1, t);
        let c = e.c0.lerp(e.c1, t);
        let wm = e.wm0 + (e.wm1 - e.wm0) * t;
        let v = Vec3::new(v.x, v.y, near);
        if e.v0.z < near {
            (e.v0, e.c0, e.wm0, e.cap0) = (v, c, wm, false);
        } else {
            (e.v1, e.c1, e.wm1, e.cap1) = (v, c, wm, false);
        }
    }
    Some(e)
}

/// A segment's ends on screen after the guard clip: pixel coordinates, 1/depth and colours,
/// whether each is a free end of its polyline, and whether each is the unclipped end.
#[derive(Clone, Copy, Debug)]
struct ScreenEnds {
    x0: f32,
    y0: f32,
    x1: f32,
    y1: f32,
    iz0: f32,
    iz1: f32,
    c0: Vec3,
    c1: Vec3,
    cap0: bool,
    cap1: bool,
    whole0: bool,
    whole1: bool,
}

/// `e` projected and clipped to the guard rectangle, the image widened by the segment's
/// reach (`half_w` and the sub-samples') and 2 px; `None` when nothing of it is left or a
/// projection overflows f32 (points ~1e30 m off axis).
#[inline]
fn project_and_clip(p: &Params, e: &ViewEnds, half_w: f32) -> Option<ScreenEnds> {
    let (x0, y0) = p.view.view_to_pixel(e.v0);
    let (x1, y1) = p.view.view_to_pixel(e.v1);
    let (iz0, iz1) = (1.0 / e.v0.z, 1.0 / e.v1.z);
    let (dx, dy) = (x1 - x0, y1 - y0);
    if !(dx.is_finite() && dy.is_finite() && iz0.is_finite() && iz1.is_finite()) {
        return None;
    }
    let (t0, t1) = guard_clip(p, (x0, y0), (x1, y1), half_w + SAMPLE_REACH + 2.0)?;
    let mut s = ScreenEnds {
        x0,
        y0,
        x1,
        y1,
        iz0,
        iz1,
        c0: e.c0,
        c1: e.c1,
        cap0: e.cap0,
        cap1: e.cap1,
        whole0: t0 <= 0.0,
        whole1: t1 >= 1.0,
    };
    if t0 > 0.0 || t1 < 1.0 {
        // Colour is perspective-correct at the clip points: c/z and 1/z are screen-linear.
        let at = |t: f32| {
            let iz = iz0 + (iz1 - iz0) * t;
            let c = (e.c0 * iz0).lerp(e.c1 * iz1, t) / iz;
            (x0 + dx * t, y0 + dy * t, iz, c)
        };
        (s.x0, s.y0, s.iz0, s.c0) = at(t0);
        (s.x1, s.y1, s.iz1, s.c1) = at(t1);
        s.cap0 &= s.whole0;
        s.cap1 &= s.whole1;
        if !(s.c0.is_finite() && s.c1.is_finite() && s.iz0 > 0.0 && s.iz1 > 0.0) {
            return None;
        }
    }
    Some(s)
}

/// The part `t0 ..= t1` of the screen segment from `a` to `b` inside the image widened by
/// `g` pixels each side (Liang–Barsky, in float, before anything becomes an integer); the
/// whole `0 ..= 1` when both ends are inside, `None` when nothing is.
#[inline]
fn guard_clip(
    p: &Params,
    (x0, y0): (f32, f32),
    (x1, y1): (f32, f32),
    g: f32,
) -> Option<(f32, f32)> {
    let (dx, dy) = (x1 - x0, y1 - y0);
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
    (t0 <= t1).then_some((t0, t1))
}

/// The rows, first and last, whose centre (j + 0.5) lies within `r` pixels of the screen
/// segment `s`'s y extent; `None` when there are none or it lies beyond the image's sides.
#[inline]
fn covered_rows(p: &Params, s: &ScreenEnds, r: f32) -> Option<(u32, u32)> {
    let (ymin, ymax) = (s.y0.min(s.y1) - r, s.y0.max(s.y1) + r);
    let (xmin, xmax) = (s.x0.min(s.x1) - r, s.x0.max(s.x1) + r);
    let last_row = (p.height - 1) as f32;
    let row_lo = (ymin - 0.5).ceil().max(0.0);
    let row_hi = (ymax - 0.5).floor().min(last_row);
    if !(row_lo <= row_hi) || xmax < 0.0 || xmin > p.width as f32 {
        return None;
    }
    Some((row_lo as u32, row_hi as u32))
}

/// A segment's [`Fibers`] from its blend (none: a plain band of half width `band_hw`), its
/// mitres and its screen extent `e` (last end − first end).
#[inline]
fn fibers_of(fib: Option<Blend>, band_hw: f32, m: Mitres, e: (f32, f32)) -> Fibers {
    let (inv_r, cov_scale, pattern, band_scale) = fib.map_or((0.0, 0.0, 0, 1.0), |f| {
        (f.inv_r, f.cov_scale, f.pattern, f.band_scale)
    });
    Fibers {
        inv_r,
        cov_scale,
        pattern,
        band_hw,
        band_scale,
        b0: m.b0,
        b1: m.b1,
        e,
        ext0: m.ext0,
        ext1: m.ext1,
    }
}
