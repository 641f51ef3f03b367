//! Skinned characters: the glTF's meshes posed by the clip every frame (glTF 2.0 §3.7.3
//! "Skins": linear blend skinning).
//!
//! # What
//! [`Character`] holds every triangle primitive of the file's meshes in bind space, with up to
//! four bone influences per vertex, and the base colour of its material (factor and, when the
//! material has one, a PNG texture). [`super::Motion::pose_character`] evaluates the clip's node
//! hierarchy once per frame (parent-first, each node once) and skins every vertex:
//!
//! `p = Σₖ wₖ · (Jₖ · IBMₖ) · v / Σₖ wₖ`, the normal by the cofactor of the blended matrix
//! (its inverse transpose up to a positive factor, so non-uniform node scales keep normals
//! perpendicular),
//!
//! with `Jₖ` the world matrix of joint k at the frame's time and `IBMₖ` its inverse bind
//! matrix. Weights are divided by their sum (real files have sums of 0.98–1.02). A mesh on a
//! node without a skin is rigid: one bone, the node itself, with an identity bind matrix
//! (RobotExpressive is built that way: 12 rigid parts and two skinned hands). Positions end in
//! the pose world (model metres divided by the fit's scale, as every other pose quantity).
//!
//! # Reading
//! `load.rs` reads the file's meshes into a [`Character`] (bones, materials, shared vertex
//! sets), `primitive.rs` one triangle primitive's vertices and triangles, each refusing a
//! broken file with the mesh, primitive and rule.
//!
//! # Why this design
//! Skinning per vertex with a blended matrix costs about 50 flops; a few thousand vertices take
//! well under a millisecond. The node evaluation walks each node once per frame (the head and
//! collider chains walk theirs on their own, as they are also sampled at the simulation's
//! 240 Hz, where the mesh is not needed).

mod load;
mod primitive;
mod static_mesh;

pub(crate) use load::load_character;

use glam::{Affine3A, Mat3A, Vec2, Vec3, Vec3A};
use rayon::prelude::*;

use super::texture::Texture;

/// Most vertices a character may have.
pub const MAX_VERTICES: usize = 1 << 20;
/// Most triangles a character may have.
pub const MAX_TRIANGLES: usize = 2 << 20;

/// A bone: the evaluated node it follows and its bind matrix (the inverse bind matrix of a skin
/// joint, identity for a rigid mesh's node).
#[derive(Clone, Debug)]
pub(crate) struct Bone {
    /// Index into `Motion::nodes`.
    pub(crate) slot: usize,
    /// glTF node index (for messages and the head test).
    pub(crate) node: usize,
    pub(crate) bind: Affine3A,
}

/// A material's base colour.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Linear RGB base colour factor (glTF `baseColorFactor`, alpha dropped).
    pub base_color: Vec3,
    /// Index into [`Character::textures`] of the base colour texture, if any.
    pub texture: Option<usize>,
    /// Both faces are drawn (glTF `doubleSided`); otherwise back faces are culled.
    pub double_sided: bool,
}

/// The character's meshes in bind space (see the module doc).
#[derive(Clone, Debug)]
pub struct Character {
    pub(crate) bones: Vec<Bone>,
    /// Bone is in the head joint's subtree (the head is the hairstyle's ellipsoid's job).
    pub(crate) bone_in_head: Vec<bool>,
    pub(crate) bind_pos: Vec<Vec3>,
    pub(crate) bind_nrm: Vec<Vec3>,
    /// Bone indices (into `bones`) of each vertex's four influences.
    pub(crate) joints: Vec<[u16; 4]>,
    /// Weights of the influences, summing to 1.
    pub(crate) weights: Vec<[f32; 4]>,
    /// Texture coordinates (0, 0 without a TEXCOORD_0).
    pub uv: Vec<Vec2>,
    /// Material of each triangle.
    pub triangle_material: Vec<u16>,
    /// Triangles (vertex indices, counter-clockwise front faces).
    pub triangles: Vec<[u32; 3]>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    /// Rest-pose positions in model metres (the bind pose posed by the nodes' rest transforms).
    pub(crate) rest_model: Vec<Vec3>,
    /// Primitives skipped because they are not triangles.
    pub skipped_primitives: usize,
    /// Base colour textures in a format wisp does not read (`motion::texture`): their
    /// materials keep their colour factor.
    pub unread_textures: usize,
}

/// A posed character (reused every frame): positions and unit normals in the pose world.
#[derive(Clone, Debug, Default)]
pub struct CharacterPose {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    /// Scratch: world matrix of every evaluated node, then each bone's skinning matrix.
    pub(crate) node_worlds: Vec<Affine3A>,
    pub(crate) bone_mats: Vec<Affine3A>,
}

impl Character {
    /// Vertex positions at the rest pose (the bind pose posed by the nodes' own transforms),
    /// model metres: where a groom authored on the character was made.
    pub fn rest_positions(&self) -> &[Vec3] {
        &self.rest_model
    }

    /// Vertices.
    pub fn vertex_count(&self) -> usize {
        self.bind_pos.len()
    }

    /// Whether vertex `v`'s strongest influence is a bone of the head (the head joint or below).
    pub fn is_head_vertex(&self, v: usize) -> bool {
        let k = dominant(&self.weights[v]);
        self.bone_in_head[self.joints[v][k] as usize]
    }

    /// Whether any vertex belongs to the head.
    pub fn has_head(&self) -> bool {
        (0..self.vertex_count()).any(|v| self.is_head_vertex(v))
    }

    /// Heap bytes held.
    pub fn held_bytes(&self) -> u64 {
        let per_vertex = 2 * size_of::<Vec3>()
            + size_of::<[u16; 4]>()
            + size_of::<[f32; 4]>()
            + size_of::<Vec2>()
            + size_of::<Vec3>();
        (self.bind_pos.len() * per_vertex
            + self.triangles.len() * (size_of::<[u32; 3]>() + size_of::<u16>())
            + self.bones.len() * size_of::<Bone>()) as u64
            + self.textures.iter().map(Texture::held_bytes).sum::<u64>()
    }

    /// Bytes a [`CharacterPose`] of this character holds (positions, normals, matrices).
    pub fn pose_bytes(&self, nodes: usize) -> u64 {
        (2 * self.bind_pos.len() * size_of::<Vec3>()
            + (nodes + self.bones.len()) * size_of::<Affine3A>()) as u64
    }

    /// Skins every vertex with the bone matrices in `pose.bone_mats` (pose world).
    pub(crate) fn skin(&self, pose: &mut CharacterPose) {
        const CHUNK: usize = 2048;
        let n = self.bind_pos.len();
        pose.positions.resize(n, Vec3::ZERO);
        pose.normals.resize(n, Vec3::Y);
        let mats = &pose.bone_mats;
        pose.positions
            .par_chunks_mut(CHUNK)
            .zip(pose.normals.par_chunks_mut(CHUNK))
            .enumerate()
            .for_each(|(c, (pos, nrm))| {
                for (k, (p, nn)) in pos.iter_mut().zip(nrm.iter_mut()).enumerate() {
                    let v = c * CHUNK + k;
                    let m = blend(mats, &self.joints[v], &self.weights[v]);
                    *p = m.transform_point3(self.bind_pos[v]);
                    *nn = normal_map(&m.matrix3, self.bind_nrm[v]);
                }
            });
    }
}

/// The blended matrix Σ wₖ Mₖ (weights sum to 1).
#[inline]
fn blend(mats: &[Affine3A], j: &[u16; 4], w: &[f32; 4]) -> Affine3A {
    let mut m = Affine3A {
        matrix3: Mat3A::ZERO,
        translation: Vec3A::ZERO,
    };
    for k in 0..4 {
        if w[k] != 0.0 {
            let b = &mats[j[k] as usize];
            m.matrix3 += b.matrix3 * w[k];
            m.translation += b.translation * w[k];
        }
    }
    m
}

/// Unit normal under the linear map `m`: its cofactor matrix (det · m⁻ᵀ, columns c1×c2,
/// c2×c0, c0×c1) with the sign of the determinant, so mirrored nodes keep outward normals.
#[inline]
fn normal_map(m: &Mat3A, n: Vec3) -> Vec3 {
    let (c0, c1, c2) = (m.x_axis, m.y_axis, m.z_axis);
    let cof = Mat3A::from_cols(c1.cross(c2), c2.cross(c0), c0.cross(c1));
    let sign = if c0.dot(c1.cross(c2)) < 0.0 {
        -1.0
    } else {
        1.0
    };
    Vec3::from(cof * Vec3A::from(n) * sign).normalize_or(Vec3::Y)
}

/// Index of the largest of four weights (the first on ties).
#[inline]
pub(crate) fn dominant(w: &[f32; 4]) -> usize {
    let mut k = 0;
    for i in 1..4 {
        if w[i] > w[k] {
            k = i;
        }
    }
    k
}
