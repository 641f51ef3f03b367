//! The hair's line raster: anti-aliased, depth-tested polylines, composited per pixel in
//! depth order and per sub-sample, into a [`Framebuffer`](crate::raster::Framebuffer) whose
//! opaque depth the solids wrote. Knows nothing of hair.
//!
//! What: [`draw_polylines`] draws every segment of equally long polylines ([`Polylines`])
//! with per-vertex colours, a width (fixed in pixels, or a physical per-vertex width
//! projected at its depth, [`LineWidth`]) and an opacity ([`LineStyle`]), hidden where the
//! opaque depth is nearer, composited over whatever the colour buffer holds; the coverage
//! channel gets one minus the light the hair lets through. [`seen_points`] and
//! [`draw_seen_polylines`] split the same draw around shading, so a caller shades only the
//! points the picture can show. A line that stands for a [`Bundle`] of fibres is drawn as
//! its fibres where they are wide enough to tell apart.
//!
//! How, in two parallel passes, bit-identical for any thread count:
//! 1. **Set-up and binning** (`bins`, parallel over fixed chunks of segments): each segment
//!    is clipped to the near plane in view space, projected, clipped in float to a guard
//!    rectangle around the image and sized (`segment`, `params`, `fibers`), then appended to
//!    its chunk's list for every band of 16 rows it touches.
//! 2. **Raster** (`band`, parallel over bands): a band gathers its segments from every
//!    chunk, leaving out those behind the solids at every pixel they could touch (`cull`),
//!    radix-sorts them far to near by mid-point 1/depth (ties in input order), and emits them
//!    near to far (`fragment`, `cover`): one fragment per covered pixel in front of the
//!    opaque depth and not behind nearer hair that already hides the pixel (`hiding`).
//!    The fragments are grouped by pixel, each pixel's run put in depth order
//!    (`pixel_runs`) and composited front to back (`composite`).
//!
//! Coverage is counted on 16 sub-samples a pixel (`samples`): a fragment carries which of
//! them its line covers, and each sub-sample keeps its own transmittance, so fibres side by
//! side hide what is behind them as their summed width does. Depth is 1/depth interpolated
//! linearly in screen space (exact for perspective); colour is interpolated linearly in
//! screen space within a segment (segments are a few pixels long) and perspective-correctly
//! at clip points.
//!
//! Hair over hair: hair does not write depth. Each pixel composites the fragments that cover
//! it front to back by 1/depth at the pixel centre, ties in input order, so nearer hair is on
//! top at every pixel whatever the input order, and the result depends only on the input.
//! Why per pixel: whole segments composited in mid-point depth order (as Sintorn & Assarsson
//! 2008 sort hair segments) misorder any two segments whose depths cross where they overlap,
//! which dense hair does all the time (a fibre weaves over and under its neighbours within a
//! segment): against a path tracer's first-hit fibres, side-lit dense hair read 0.964 of the
//! raster's own vertex values with segment order and 0.990 with pixel order, for about 14 ms
//! more on smooth at 1280×720 on 2 threads (ACCURACY.md §2, BENCHMARKS.md).
//!
//! Rejected: a hair z-buffer (depth write, then "over" in input order) drops hair behind the
//! anti-aliased fringe of nearer hair, leaving dark halos, and makes the picture depend on
//! strand order; weighted blended order-independent transparency does not make near hair
//! opaque over far hair, so dense hair turns into an average colour.
//!
//! Known approximation: the head's anti-aliased edge pixels (centre outside the silhouette)
//! hold no depth, so hair behind the head shows through that one-pixel fringe.

mod band;
mod bins;
mod budget;
mod bundle;
mod composite;
mod cover;
mod cull;
mod draw;
mod fast_float;
mod fibers;
mod fragment;
mod hiding;
mod params;
mod pixel_runs;
mod polyline;
mod samples;
mod scratch;
mod seen;
mod segment;

pub use bins::MAX_SEGMENTS;
pub use draw::draw_polylines;
pub use polyline::{Bundle, LineStyle, LineWidth, MAX_WIDTH_PX, Polylines};
pub use scratch::LineScratch;
pub use seen::{draw_seen_polylines, seen_points};
