//! A line draw call's constants ([`Params`]: the view, the width model, the opacity, the
//! image's size, the bundle profiles) and the width model: how wide and how opaque each
//! segment is drawn.
//!
//! Physical width ([`LineWidth::Projected`]): a segment's projected width is the mean of its
//! ends' `f·w/z` (f the focal length in pixels), exact for the area of the screen trapezoid a
//! segment of linearly varying projected width covers. A segment under the minimum is drawn
//! at the minimum with its opacity lowered in proportion, which conserves its summed coverage
//! (length × projected width × opacity) while sub-pixel lines stay smooth: dense thin lines
//! accumulate toward full coverage (`tests/lib/raster_coverage.rs`), and lines side by side
//! hide what is behind them as their summed width does (`tests/lib/raster_lines.rs`). The 16
//! sub-samples count one line's coverage within max(2%, 0.2 px / drawn width): they alias on
//! slopes near 1/2 (25% at 0.7 px drawn, 8% at 1 px; the coverage test's sweep).

use super::bundle::Profiles;
use super::polyline::{LineStyle, LineWidth, MAX_WIDTH_PX, Polylines};
use crate::raster::camera::{Camera, View};
use crate::raster::framebuffer::Framebuffer;

/// Per-call constants of the set-up and raster passes.
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

impl<'a> Params<'a> {
    /// The constants of drawing `lines` into `fb`, with the bundle profiles prepared in
    /// `profiles`; `None` when nothing would be drawn (an empty or inconsistent framebuffer,
    /// no width or opacity, a camera that projects nowhere).
    pub(super) fn new(
        fb: &Framebuffer,
        cam: &Camera,
        lines: &Polylines,
        style: &LineStyle,
        profiles: &'a mut Profiles,
    ) -> Option<Params<'a>> {
        let (width, height) = (fb.width as usize, fb.height as usize);
        if width == 0 || height == 0 || !fb.is_consistent() {
            return None;
        }
        let width_ok = match style.width {
            LineWidth::Pixels(w) => w > 0.0,
            LineWidth::Projected { min_px } => min_px > 0.0,
        };
        if !width_ok || !(style.opacity > 0.0) {
            return None;
        }
        let view = cam.view_for(fb.width, fb.height)?;
        let bundles = matches!(style.width, LineWidth::Projected { .. })
            && lines.bundle.is_some_and(|b| profiles.prepare(&b));
        Some(Params {
            view,
            width_model: style.width,
            opacity: style.opacity.min(1.0),
            width,
            height,
            bundle: bundles.then_some(&*profiles),
        })
    }

    /// A segment's projected width in pixels, from its ends' physical widths over their
    /// depths (metres per metre): the mean of the ends' `f·w/z`.
    #[inline]
    pub(super) fn projected_px(&self, w_over_z0: f32, w_over_z1: f32) -> f32 {
        self.view.focal_px * 0.5 * (w_over_z0 + w_over_z1)
    }

    /// Half the drawn width in pixels and the coverage multiplier of a segment whose ends
    /// have physical width over depth `w_over_z0`, `w_over_z1` (metres per metre; read only
    /// by [`LineWidth::Projected`]); `None` when the segment has no width to draw. Below
    /// `min_px` the segment is drawn `min_px` wide with its opacity scaled by
    /// `w_px / min_px` (module doc).
    #[inline]
    pub(super) fn drawn_width(&self, w_over_z0: f32, w_over_z1: f32) -> Option<(f32, f32)> {
        match self.width_model {
            LineWidth::Pixels(w) => Some((0.5 * w.min(MAX_WIDTH_PX), self.opacity)),
            LineWidth::Projected { min_px } => {
                let w_px = self.projected_px(w_over_z0, w_over_z1);
                // `!(a > 0)` also rejects NaN; +inf (a point at the eye) is capped below.
                if !(w_px > 0.0) {
                    return None;
                }
                if w_px < min_px {
                    Some((
                        0.5 * min_px.min(MAX_WIDTH_PX),
                        self.opacity * (w_px / min_px),
                    ))
                } else {
                    Some((0.5 * w_px.min(MAX_WIDTH_PX), self.opacity))
                }
            }
        }
    }
}
