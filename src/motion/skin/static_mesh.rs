//! A character made of one mesh that never moves: the surface a groom kept as authored was
//! made on, when the groom brings it (a TressFX `.tfxmesh`) instead of a rigged character.
//! One bone at the origin carries every vertex; the mesh stands in for the head (no head
//! ellipsoid is drawn over it); it is a mid grey, drawn from both sides.

use glam::{Affine3A, Vec2, Vec3};

use super::{Bone, Character, MAX_TRIANGLES, MAX_VERTICES, Material};
use crate::motion::Motion;

/// The grey of a groom's own mesh (linear RGB).
const MESH_GREY: Vec3 = Vec3::splat(0.35);

impl Character {
    /// The static mesh of `positions` and unit `normals` (pose metres) and `triangles`
    /// (vertex indices in range, checked by the caller's reader); `None` when it is empty
    /// or over the character's caps.
    pub fn from_static_mesh(
        positions: Vec<Vec3>,
        normals: Vec<Vec3>,
        triangles: Vec<[u32; 3]>,
    ) -> Option<Character> {
        let n = positions.len();
        if n == 0
            || normals.len() != n
            || triangles.is_empty()
            || n > MAX_VERTICES
            || triangles.len() > MAX_TRIANGLES
            || triangles.iter().flatten().any(|&i| i as usize >= n)
            || !positions.iter().all(|p| p.is_finite())
        {
            return None;
        }
        Some(Character {
            bones: vec![Bone {
                slot: 0,
                node: 0,
                bind: Affine3A::IDENTITY,
            }],
            bone_in_head: vec![true],
            rest_model: positions.clone(),
            bind_pos: positions,
            bind_nrm: normals,
            joints: vec![[0; 4]; n],
            weights: vec![[1.0, 0.0, 0.0, 0.0]; n],
            uv: vec![Vec2::ZERO; n],
            triangle_material: vec![0; triangles.len()],
            triangles,
            materials: vec![Material {
                base_color: MESH_GREY,
                texture: None,
                double_sided: true,
            }],
            textures: Vec::new(),
            skipped_primitives: 0,
            unread_textures: 0,
        })
    }
}

impl Motion {
    /// A motionless pose with `character` standing still in the world: the head frame is the
    /// world's ([`Motion::still`] at the identity), and the character is drawn as it is.
    pub fn still_with(character: Character) -> Motion {
        let mut motion = Motion::still(Affine3A::IDENTITY);
        motion.character = Some(character);
        motion
    }
}
