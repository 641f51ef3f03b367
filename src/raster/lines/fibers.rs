//! A bundle's segment drawn as its fibres (`bundle.rs` has the profile across the line): how
//! much of the fibres is blended in, how far the bundle narrows toward a tapered tip, and the
//! mitred joints that carry its stripes round a bend. The set-up writes one [`Fibers`] per
//! such segment; the pixel loop reads it (`cover.rs`).
//!
//! Blend: where the bundle's projected radius R is under [`BUNDLE_FROM_PX`], 2r is under a
//! twentieth of a pixel for the presets (r/R ≈ 0.017) and the fibres would average back to the
//! band of their summed width, so the band is drawn. From there to [`BUNDLE_FULL_PX`] the
//! fibres are blended in with weight k = (R − 3)/3 and the band out with 1 − k: both have the
//! same coverage, so nothing pops as the camera moves.
//!
//! Tip: where a share s of the bundle's fibres is left (its width over the full bundle's
//! fibres, w_px / (R·A(+∞))), the ones left are the innermost (the placement's spiral fills
//! the disc from its centre), so the bundle is drawn at √s of its radius; the coverage stays
//! the width's whatever the radius.
//!
//! Mitres: the parallel stripes of consecutive segments meet on the bisector of their joint,
//! so cutting each segment there, instead of square to its axis, tiles the joint without the
//! notch outside and the overlap inside that a wide line would show. A turn sharper than 60°
//! is cut square, so no mitre reaches past tan 30° ≈ 0.58 widths. Only segments drawn as
//! fibres are mitred: a band a pixel or two wide has no notch to speak of, and the mitre's
//! longer reach would cost every thin segment. Where a strand crosses R = [`BUNDLE_FROM_PX`],
//! the band's side of that one joint is cut square: a sliver of at most 3 px × tan(turn/2)
//! overlaps or stays open there.

use glam::Vec3;

use super::bundle::Profiles;
use super::params::Params;
use super::polyline::{Bundle, MAX_WIDTH_PX};
use crate::raster::camera::View;

/// Projected bundle radius (pixels) from which a bundle's fibres are blended in, and from
/// which they are drawn alone.
const BUNDLE_FROM_PX: f32 = 3.0;
const BUNDLE_FULL_PX: f32 = 6.0;

/// Sharpest joint mitred: a turn of at most 60° (cosine 0.5).
const MITRE_MIN_COS: f32 = 0.5;

/// How a bundle's segment is drawn as its fibres; kept beside the segments, one per segment,
/// only in a draw call with bundles, so plain lines stay small.
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

/// What a bundle's segment drawn as its fibres is drawn with: its half width and opacity
/// (those of the fibres, wider than the band's), and its [`Fibers`]' blend.
#[derive(Clone, Copy, Debug)]
pub(super) struct Blend {
    pub(super) half_w: f32,
    pub(super) opacity: f32,
    pub(super) inv_r: f32,
    pub(super) cov_scale: f32,
    pub(super) pattern: u32,
    pub(super) band_scale: f32,
}

/// How line `line`'s segment, a `bundle`, blends its fibres in (module doc): `z` its ends'
/// view depths, `wm` their physical widths in metres, `band` the half width and opacity its
/// band is drawn with. `None` where it is drawn as the band alone (a bundle under
/// [`BUNDLE_FROM_PX`], no profiles, non-finite sizes).
#[inline]
pub(super) fn blend(
    p: &Params,
    bundle: &Bundle,
    line: usize,
    z: (f32, f32),
    wm: (f32, f32),
    (band_hw, band_opacity): (f32, f32),
) -> Option<Blend> {
    let prof = p.bundle?;
    // The bundle's projected radius, at most half the widest line.
    let w_px = p.projected_px(wm.0 / z.0, wm.1 / z.1);
    let r_px = p.view.focal_px * bundle.radius_m * 0.5 * (1.0 / z.0 + 1.0 / z.1);
    let r_px = r_px.min(0.5 * MAX_WIDTH_PX);
    let k = ((r_px - BUNDLE_FROM_PX) / (BUNDLE_FULL_PX - BUNDLE_FROM_PX)).clamp(0.0, 1.0);
    if !(k > 0.0 && r_px.is_finite() && w_px.is_finite() && p.opacity > 0.0) {
        return None;
    }
    // The band's part keeps its own width and opacity (relative to the style's); the
    // fibres' radius narrows toward a tip.
    let share = (w_px / (prof.total * r_px)).clamp(0.0, 1.0);
    let r_draw = (r_px * share.sqrt()).max(0.5);
    Some(Blend {
        half_w: band_hw.max(r_draw * (1.0 + prof.rho)),
        opacity: p.opacity,
        inv_r: 1.0 / r_draw,
        cov_scale: k * w_px / prof.total,
        pattern: Profiles::pattern_of(line),
        band_scale: (1.0 - k) * band_opacity / p.opacity,
    })
}

/// A segment's joints: its cut at each end (the unit direction the pixels are tested
/// against) and how far past each end the cut reaches along its axis, pixels.
#[derive(Clone, Copy, Debug)]
pub(super) struct Mitres {
    pub(super) b0: (f32, f32),
    pub(super) b1: (f32, f32),
    pub(super) ext0: f32,
    pub(super) ext1: f32,
}

impl Mitres {
    /// Both ends cut square to the axis of unit direction `u`.
    #[inline]
    pub(super) fn square(u: (f32, f32)) -> Mitres {
        Mitres {
            b0: u,
            b1: u,
            ext0: 0.0,
            ext1: 0.0,
        }
    }
}

/// The screen segment whose joints [`mitres`] cuts: its ends (pixels), unit direction and
/// half width, and the points of its neighbours' far ends (`before`: the one before its
/// first end, `after`: the one after its last), where that end is a joint left unclipped.
#[derive(Clone, Copy, Debug)]
pub(super) struct Joints {
    pub(super) ends: [(f32, f32); 2],
    pub(super) u: (f32, f32),
    pub(super) half_w: f32,
    pub(super) before: Option<usize>,
    pub(super) after: Option<usize>,
}

/// The mitres of a segment drawn as fibres (module doc): each joint with a neighbour on
/// screen, in front of the near plane and turning at most 60°, is cut on its bisector;
/// every other end square. `points` are the lines' world points, which `j.before` and
/// `j.after` index.
#[inline]
pub(super) fn mitres(view: &View, points: &[Vec3], j: Joints) -> Mitres {
    let [(x0, y0), (x1, y1)] = j.ends;
    let (ux, uy) = j.u;
    let mut m = Mitres::square(j.u);
    let neighbour = |idx: usize| -> Option<(f32, f32)> {
        let v = view.to_view(*points.get(idx)?);
        (v.is_finite() && v.z >= view.near_m).then(|| view.view_to_pixel(v))
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
        let len = (mx * mx + my * my).sqrt();
        // |tan(turn/2)| = |sin| / (1 + cos), the mitre's reach per pixel of width.
        let tan_half = (nx * uy - ny * ux).abs() / (1.0 + cos_turn);
        Some(((mx / len, my / len), tan_half))
    };
    if let Some((b, t)) = j.before.and_then(neighbour).and_then(|q| joint(q, true)) {
        (m.b0, m.ext0) = (b, j.half_w * t + 0.5);
    }
    if let Some((b, t)) = j.after.and_then(neighbour).and_then(|q| joint(q, false)) {
        (m.b1, m.ext1) = (b, j.half_w * t + 0.5);
    }
    m
}
