//! What the mesh raster draws: a triangle mesh in world space ([`Mesh`]) and how each group of
//! its triangles looks ([`Surface`]).

use glam::{Vec2, Vec3};

use super::texture::Texture;

/// How a group of triangles looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// Linear RGB albedo (multiplied by the texture when there is one).
    pub albedo: Vec3,
    /// Index into [`Mesh::textures`].
    pub texture: Option<u32>,
    /// Draw back faces too (their normal is flipped toward the eye).
    pub double_sided: bool,
}

/// A triangle mesh in world space.
#[derive(Clone, Copy, Debug)]
pub struct Mesh<'a> {
    pub positions: &'a [Vec3],
    /// Unit vertex normals.
    pub normals: &'a [Vec3],
    /// Texture coordinates per vertex (may be empty when no surface has a texture).
    pub uv: &'a [Vec2],
    /// Vertex indices; counter-clockwise seen from the front.
    pub triangles: &'a [[u32; 3]],
    /// Index into `surfaces` per triangle.
    pub triangle_surface: &'a [u16],
    pub surfaces: &'a [Surface],
    pub textures: &'a [Texture],
}
