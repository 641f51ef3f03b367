//! Rasterisation into a linear-RGB framebuffer with depth and coverage: the opaque solids,
//! then the hair's anti-aliased lines over them. Knows nothing of hair physics or light.
//!
//! - [`camera`]: pinhole camera; pixel centres at +0.5, x right, y down, depth in metres
//!   along the view direction. Shared by both rasters.
//! - [`framebuffer`]: linear-RGB colour, depth and coverage, converted to 8- or 16-bit sRGB or
//!   premultiplied linear at the edge. Shared by both rasters.
//! - [`solids`]: opaque ellipsoids (ray cast) and triangle meshes (multisampled); drawn
//!   first, they fill the depth buffer.
//! - [`lines`]: the hair, anti-aliased polylines depth-tested against the solids' depth and
//!   composited per pixel in depth order and per sub-sample, in parallel and bit-identical
//!   for any thread count; in one pass ([`draw_polylines`]) or two around shading
//!   ([`seen_points`], then [`draw_seen_polylines`]), so only the points the picture can
//!   show are shaded.
//!
//! `lines` and `solids` share only the camera and the framebuffer: neither imports the other.
//!
//! A frame: [`Framebuffer::clear`], [`draw_ellipsoid`] for each solid and [`draw_mesh`] for a
//! mesh, then [`draw_polylines`] (or [`seen_points`], shading, [`draw_seen_polylines`]) with a
//! [`LineScratch`] kept across frames.

// `!(a > b)` is used on purpose throughout: unlike `a <= b` it is also true for NaN, so one
// test rejects both out-of-range and NaN values.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod camera;
pub mod framebuffer;
pub mod lines;
pub mod solids;

pub use camera::{Camera, DEFAULT_NEAR_M, View};
pub use framebuffer::Framebuffer;
pub use lines::{
    Bundle, LineScratch, LineStyle, LineWidth, MAX_SEGMENTS, MAX_WIDTH_PX, Polylines,
    draw_polylines, draw_seen_polylines, seen_points,
};
pub use solids::{Mesh, MeshScratch, Surface, Texture, draw_ellipsoid, draw_mesh};
