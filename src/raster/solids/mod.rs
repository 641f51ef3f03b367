//! Opaque solids (temporary hub).

mod ellipsoid;
mod mesh;

pub use ellipsoid::draw_ellipsoid;
pub use mesh::{Mesh, MeshScratch, Surface, Texture, draw_mesh};
