//! Bones that carry a groom kept as authored on its own character: each root pinned to the
//! nearest bone of the character at rest.
//!
//! What: a groom authored on a character (an animal's fur, a game character's own groom) is
//! bound to the character's skeleton as a rigid skin with one influence per root, the bone
//! that passes nearest the root at rest. A bone is the segment from a joint to each of its
//! child joints, moved by that joint (its rotation swings the segment); a joint without a
//! child joint is a point. Joints are the character's bones (skin joints, or the nodes of
//! rigidly attached meshes).
//!
//! How: the guides' rest shape is in the head frame, like every groom's; a root on bone `b`
//! moves by `C_b(t) = F_b(t) · F_b(rest)⁻¹ · H_rest` (head frame → pose world), where `F` is
//! the joint's rigid frame in the pose world (scale removed, `chain::rigid_rotation`) and
//! `H_rest` the head frame at rest. For the head's own joint this is the head transform
//! itself, so hair on the head moves exactly as on any head. [`Pose::carriers`] holds `C_b`
//! for every bone that carries a root, in the order of the indices
//! [`Motion::carry_by_nearest_bones`] returned.
//!
//! Why the nearest bone: it needs only the skeleton (no skin weights painted for the groom,
//! which groom files do not carry), it is what a fur tool binds before weights are painted,
//! and a root between two bones moves with one of them rigidly instead of being averaged
//! into the body. Roots near a joint that bends much (an elbow) may see their neighbours on
//! the other bone part: the groom's strands are pinned, not stretched.
//!
//! [`Pose::carriers`]: super::Pose::carriers

use glam::{Affine3A, Mat3A, Vec3, Vec3A};

use super::chain::{JointChain, rigid_rotation};
use super::playback::Motion;

/// A bone that carries roots: the chain of its joint and `F(rest)⁻¹ · H_rest`.
#[derive(Clone, Debug)]
pub(crate) struct Carrier {
    pub(crate) chain: JointChain,
    pub(crate) from_rest: Affine3A,
}

/// A bone at rest, pose metres: the segment `a`–`b` moved by the joint at `slot`.
struct Bone {
    slot: usize,
    a: Vec3,
    b: Vec3,
}

/// Why roots cannot be carried by bones.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum CarryError {
    #[error("the motion has no character's skeleton to pin the roots to (no skin and no mesh)")]
    NoBones,
}

impl Motion {
    /// The head frame at the rest pose (the nodes' own transforms, no clip): head frame →
    /// pose world.
    pub fn head_at_rest(&self) -> Affine3A {
        let worlds = self.rest_worlds();
        let w = self
            .head
            .chain
            .last()
            .map_or(Affine3A::IDENTITY, |&s| worlds[s]);
        self.head_frame_of(&w, &self.head)
    }

    /// The turn the model was given to stand along +Y (identity for a Y-up file, or with
    /// `keep_axes`): what was done to the file's coordinates.
    pub fn file_turn(&self) -> glam::Quat {
        super::up_axis::turn_to_y(self.file_up)
    }

    /// Pins each of `roots_head_m` (head frame at rest, metres) to the nearest bone of the
    /// character (see the module doc): returns each root's carrier index and keeps the
    /// carriers, so every pose from now on has their transforms in [`super::Pose::carriers`].
    pub fn carry_by_nearest_bones(
        &mut self,
        roots_head_m: &[Vec3],
    ) -> Result<Vec<u32>, CarryError> {
        let worlds = self.rest_worlds();
        let bones = self.rest_bones(&worlds);
        if bones.is_empty() {
            return Err(CarryError::NoBones);
        }
        let head_rest = self.head_at_rest();
        let mut carrier_of_slot: Vec<Option<u32>> = vec![None; self.nodes.len()];
        let mut carriers = Vec::new();
        let mut out = Vec::with_capacity(roots_head_m.len());
        for r in roots_head_m {
            let p = head_rest.transform_point3(*r);
            let slot = nearest_bone(&bones, p);
            let index = *carrier_of_slot[slot].get_or_insert_with(|| {
                let chain = self.chain_of_slot(slot);
                let frame = self.rigid_frame(&worlds[slot]);
                carriers.push(Carrier {
                    chain,
                    from_rest: frame.inverse() * head_rest,
                });
                (carriers.len() - 1) as u32
            });
            out.push(index);
        }
        self.carriers = carriers;
        Ok(out)
    }

    /// How many bones carry roots (0 for hair on a head).
    pub fn carrier_count(&self) -> usize {
        self.carriers.len()
    }

    /// Head frame → pose world of every carrier at clip time `clip_t`, into `out`.
    pub(super) fn write_carriers(&self, clip_t: f32, out: &mut Vec<Affine3A>) {
        out.clear();
        out.extend(self.carriers.iter().map(|c| {
            let w = self.world(&c.chain, clip_t);
            self.rigid_frame(&w) * c.from_rest
        }));
    }

    /// The rigid frame of a joint whose world matrix is `w` (model units): its rotation
    /// without scale, at its origin in the pose world.
    fn rigid_frame(&self, w: &Affine3A) -> Affine3A {
        Affine3A {
            matrix3: Mat3A::from_quat(rigid_rotation(w)),
            translation: w.translation / self.fit.scale,
        }
    }

    /// Every evaluated node's world matrix at rest (the nodes' own transforms), model units.
    fn rest_worlds(&self) -> Vec<Affine3A> {
        let mut worlds: Vec<Affine3A> = Vec::with_capacity(self.nodes.len());
        for node in &self.nodes {
            let local =
                Affine3A::from_scale_rotation_translation(node.rest_s, node.rest_r, node.rest_t);
            let world = match node.parent {
                Some(p) => worlds[p] * local,
                None => local,
            };
            worlds.push(world);
        }
        worlds
    }

    /// The character's bones at rest in the pose world (see the module doc).
    fn rest_bones(&self, worlds: &[Affine3A]) -> Vec<Bone> {
        let Some(ch) = &self.character else {
            return Vec::new();
        };
        let mut is_joint = vec![false; self.nodes.len()];
        for b in &ch.bones {
            is_joint[b.slot] = true;
        }
        let at = |slot: usize| Vec3::from(worlds[slot].translation) / self.fit.scale;
        let mut bones = Vec::new();
        for slot in (0..self.nodes.len()).filter(|&s| is_joint[s]) {
            bones.push(Bone {
                slot,
                a: at(slot),
                b: at(slot),
            });
            // The bone from this joint's nearest joint ancestor down to it.
            let mut up = self.nodes[slot].parent;
            while let Some(p) = up {
                if is_joint[p] {
                    bones.push(Bone {
                        slot: p,
                        a: at(p),
                        b: at(slot),
                    });
                    break;
                }
                up = self.nodes[p].parent;
            }
        }
        bones
    }

    /// The chain from a root to the evaluated node `slot`.
    fn chain_of_slot(&self, slot: usize) -> JointChain {
        let mut chain = vec![slot];
        let mut at = slot;
        while let Some(p) = self.nodes[at].parent {
            chain.push(p);
            at = p;
        }
        chain.reverse();
        JointChain {
            chain,
            rest_align: glam::Quat::IDENTITY,
        }
    }
}

/// The joint slot of the bone nearest `p` (the first of equals, so ties are resolved the
/// same way every run).
fn nearest_bone(bones: &[Bone], p: Vec3) -> usize {
    let mut best = (f32::INFINITY, bones[0].slot);
    for bone in bones {
        let d = distance_to_segment_sq(Vec3A::from(p), Vec3A::from(bone.a), Vec3A::from(bone.b));
        if d < best.0 {
            best = (d, bone.slot);
        }
    }
    best.1
}

/// Squared distance from `p` to the segment `a`–`b` (a point when `a == b`).
fn distance_to_segment_sq(p: Vec3A, a: Vec3A, b: Vec3A) -> f32 {
    let ab = b - a;
    let len_sq = ab.length_squared();
    let t = if len_sq > 0.0 {
        ((p - a).dot(ab) / len_sq).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * t)).length_squared()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_distance_is_to_the_nearest_point_of_the_segment() {
        let (a, b) = (Vec3A::ZERO, Vec3A::X);
        // Beside the middle: the perpendicular distance 2; past an end: to that end.
        assert_eq!(distance_to_segment_sq(Vec3A::new(0.5, 2.0, 0.0), a, b), 4.0);
        assert_eq!(distance_to_segment_sq(Vec3A::new(3.0, 0.0, 0.0), a, b), 4.0);
        assert_eq!(
            distance_to_segment_sq(Vec3A::new(-1.0, 1.0, 0.0), a, b),
            2.0
        );
        // A degenerate segment is its point.
        assert_eq!(distance_to_segment_sq(Vec3A::new(0.0, 0.0, 3.0), a, a), 9.0);
    }

    #[test]
    fn the_nearest_bone_wins_and_ties_go_to_the_first() {
        let bones = [
            Bone {
                slot: 4,
                a: Vec3::ZERO,
                b: Vec3::Y,
            },
            Bone {
                slot: 7,
                a: Vec3::X,
                b: Vec3::new(1.0, 1.0, 0.0),
            },
        ];
        assert_eq!(nearest_bone(&bones, Vec3::new(0.2, 0.5, 0.0)), 4);
        assert_eq!(nearest_bone(&bones, Vec3::new(0.9, 0.5, 0.0)), 7);
        assert_eq!(nearest_bone(&bones, Vec3::new(0.5, 0.5, 0.0)), 4);
    }
}
