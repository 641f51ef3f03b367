//! Rasterisation: 3D polylines with per-vertex colours and opaque ellipsoids into a linear-RGB
//! framebuffer with depth. Knows nothing of hair.
//!
//! - [`camera`]: pinhole camera; pixel centres at +0.5, x right, y down, depth in metres along
//!   the view direction.
//! - [`framebuffer`]: linear-RGB colour + depth, conversion to 8-bit sRGB at the edge.
//! - [`solid`]: opaque ellipsoids by per-pixel ray casting (exact screen box, anti-aliased
//!   silhouette); draw these first, they fill the depth buffer.
//! - [`mesh`]: opaque triangle meshes (a character), depth-tested with four visibility samples
//!   per pixel and shaded once per pixel; drawn with the solids, before the lines.
//! - [`lines`]: anti-aliased polylines, depth-tested against the opaque depth, composited back
//!   to front per band of rows, in parallel and bit-identical for any thread count;
//!   `segment` clips and projects each segment (near plane in view space, then a screen guard
//!   rectangle in float, before anything becomes an index), `fragment` turns a band's
//!   segments into per-pixel fragments (on the sub-samples of `samples`) and composites them,
//!   `hiding` drops the fragments nearer hair hides before they are stored, and `bundle`
//!   draws a line that stands for a bundle of fibres as its fibres where they are wide enough
//!   to see.
//! - `seen`: the lines in two passes around shading: [`seen_points`] emits without colour,
//!   keeps the fragments and marks the points whose segments keep one, so a caller shades
//!   only those; [`draw_seen_polylines`] composites the kept fragments with the shaded
//!   colours (the picture of [`draw_polylines`]).
//!
//! A frame: [`Framebuffer::clear`], [`draw_ellipsoid`] for each solid and [`draw_mesh`] for a
//! mesh, then [`draw_polylines`] (or [`seen_points`], shading, [`draw_seen_polylines`]) with a
//! [`LineScratch`] kept across frames.

// `!(a > b)` is used on purpose throughout: unlike `a <= b` it is also true for NaN, so one
// test rejects both out-of-range and NaN values.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod budget;
mod bundle;
pub mod camera;
mod cull;
mod fragment;
pub mod framebuffer;
mod hiding;
pub mod lines;
pub mod mesh;
pub mod polyline;
mod samples;
mod seen;
mod segment;
pub mod solid;

pub use camera::{Camera, DEFAULT_NEAR_M, View};
pub use framebuffer::Framebuffer;
pub use lines::{LineScratch, MAX_SEGMENTS, draw_polylines};
pub use mesh::{Mesh, MeshScratch, Surface, Texture, draw_mesh};
pub use polyline::{Bundle, LineStyle, LineWidth, MAX_WIDTH_PX, Polylines};
pub use seen::{draw_seen_polylines, seen_points};
pub use solid::draw_ellipsoid;
