//! The solids' raster: opaque surfaces that write depth, drawn before the hair so the hair
//! is hidden behind them and drawn over them in front.
//!
//! - [`draw_ellipsoid`] (`ellipsoid`): an ellipsoid (the head, body spheres) ray cast per
//!   pixel over its exact screen box, with an anti-aliased silhouette.
//! - [`draw_mesh`] (`mesh`): a triangle mesh (a character), four visibility samples a pixel
//!   and one shade a pixel and layer (the surfaces its samples see).
//!
//! Both shade through a caller's closure, blend colour and coverage by the covered fraction
//! with "over", and write depth only where a pixel is at least about half covered (the
//! ellipsoid: its centre inside the silhouette; the mesh: two of its four samples): the
//! hair's raster (`raster::lines`) tests against that depth.

mod ellipsoid;
mod mesh;

pub use ellipsoid::draw_ellipsoid;
pub use mesh::{Mesh, MeshScratch, Surface, Texture, draw_mesh};
