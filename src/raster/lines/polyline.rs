//! What the raster draws as hair: polylines with per-vertex colours and widths ([`Polylines`]),
//! and how wide and opaque they are drawn ([`LineStyle`], [`LineWidth`]): the line raster's
//! input.

use glam::Vec3;

pub use super::bundle::Bundle;

/// Widest line drawn, pixels; the coverage model is meant for thin lines.
pub const MAX_WIDTH_PX: f32 = 64.0;

/// Polylines sharing one point count: line `l` is `points[l*n .. (l+1)*n]` with
/// `n = points_per_line`. Points in world metres, colours linear RGB, one per point. Trailing
/// points that do not make a whole line, and lines without a colour for every point, are
/// ignored.
#[derive(Clone, Copy, Debug)]
pub struct Polylines<'a> {
    /// Vertices in world metres, line after line.
    pub points: &'a [Vec3],
    /// Linear RGB per vertex (same indexing as `points`); values above 1 are allowed.
    pub colors: &'a [Vec3],
    /// Physical width per vertex in world metres (same indexing as `points`), read only by
    /// [`LineWidth::Projected`]; may be empty otherwise. A segment whose end has no width
    /// there draws nothing.
    pub widths_m: &'a [f32],
    /// Vertices per line, `n` (every line has the same count); below 2 draws nothing.
    pub points_per_line: usize,
    /// What each line stands for, read only by [`LineWidth::Projected`]: `None`, a plain line
    /// of its width; a [`Bundle`], its fibres spread over the bundle's disc (the same
    /// coverage, drawn where the fibres are).
    pub bundle: Option<Bundle<'a>>,
}

impl Polylines<'_> {
    /// Number of whole lines that have a point and a colour for every vertex.
    pub fn line_count(&self) -> usize {
        match self.points_per_line {
            0 => 0,
            n => self.points.len().min(self.colors.len()) / n,
        }
    }

    /// Number of segments drawn: `line_count() * (points_per_line − 1)`.
    pub fn segment_count(&self) -> usize {
        self.line_count() * self.points_per_line.saturating_sub(1)
    }
}

/// How wide lines are drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LineWidth {
    /// Every line this many pixels wide on screen, whatever its depth; at most
    /// [`MAX_WIDTH_PX`]; ≤ 0 or NaN draws nothing. [`Polylines::widths_m`] is not read.
    Pixels(f32),
    /// Physical width: each point's [`Polylines::widths_m`] (world metres) projected at its
    /// depth, `w_px = width_m · focal_px / depth`, averaged over the segment's two ends. A
    /// segment narrower than `min_px` is drawn `min_px` wide at opacity `w_px / min_px`, so
    /// its coverage (summed α = length × w_px) is conserved while thin lines stay smooth; a
    /// wider one is drawn `w_px` wide (at most [`MAX_WIDTH_PX`]) at full opacity. `min_px`
    /// ≤ 0 or NaN draws nothing, and so does a point without a finite width > 0.
    Projected {
        /// Narrowest drawn width in pixels (1 px covers a full row of a pixel's sub-samples
        /// across the line, so thin lines stay smooth; narrower keeps more of their shape).
        min_px: f32,
    },
}

/// How lines look.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineStyle {
    /// Width model, default `Pixels(1.0)`.
    pub width: LineWidth,
    /// Coverage multiplier in (0, 1], default 1; ≤ 0 or NaN draws nothing, > 1 acts as 1.
    pub opacity: f32,
}

impl LineStyle {
    /// Every line `width_px` wide on screen at `opacity`.
    pub const fn pixels(width_px: f32, opacity: f32) -> LineStyle {
        LineStyle {
            width: LineWidth::Pixels(width_px),
            opacity,
        }
    }

    /// Physical width from [`Polylines::widths_m`] with a minimum of `min_px` pixels.
    pub const fn projected(min_px: f32) -> LineStyle {
        LineStyle {
            width: LineWidth::Projected { min_px },
            opacity: 1.0,
        }
    }
}

impl Default for LineStyle {
    fn default() -> Self {
        LineStyle::pixels(1.0, 1.0)
    }
}
