//! Rasterisation (temporary hub).
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
