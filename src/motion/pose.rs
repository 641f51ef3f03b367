//! Sampling a motion: where the head and the body colliders are at a wall time, and the
//! character's skinning matrices.
//!
//! Wall time `t_s` plays clip time `start + (t_s · speed) mod duration` (`rem_euclid`, so the
//! clip loops seamlessly and a negative speed plays it backwards). A joint's frame is its world
//! matrix `W` (the product of its chain's local transforms, see [`super::chain`]) made rigid
//! (scale and shear removed, `chain::rigid_rotation`) and turned by the joint's rest alignment, so
//! its axes are the model's world axes at rest. The head frame is then
//! `x_pose = (R · (fit.scale · x_hair + fit.offset_m) + W.translation) / fit.scale`, rigid in
//! the pose world; every collider is carried into the same world (model units / `fit.scale`).
//! Sampling allocates nothing once a [`Pose`] has held the motion's colliders.

use glam::{Affine3A, Mat3A, Quat, Vec3, Vec3A};

use super::chain::{JointChain, rigid_rotation};
use super::playback::Motion;
use super::skin::CharacterPose;

/// A body collision sphere in the pose world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre in the pose world, metres.
    pub center: Vec3,
    /// Radius in metres.
    pub radius_m: f32,
}

/// A body collision capsule in the pose world: the points within `radius_m` of the segment
/// from `a` to `b`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Capsule {
    /// Segment ends, pose metres.
    pub a: Vec3,
    pub b: Vec3,
    /// Radius in metres.
    pub radius_m: f32,
}

/// Where the head and the body colliders are at one instant.
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    /// Hairstyle head frame (metres, +Y up, +Z face, origin = head centre) -> pose world.
    /// Rigid: rotation and translation only.
    pub head: Affine3A,
    /// Body colliders in the pose world (metres).
    pub spheres: Vec<Sphere>,
    /// Body capsules fitted to the character's mesh, pose world (see
    /// [`MotionOptions`](super::MotionOptions)).
    pub capsules: Vec<Capsule>,
    /// Head frame → pose world of each bone that carries a groom's roots
    /// ([`Motion::carry_by_nearest_bones`], `carriers.rs`); empty for hair on a head.
    pub carriers: Vec<Affine3A>,
}

impl Default for Pose {
    fn default() -> Self {
        Self {
            head: Affine3A::IDENTITY,
            spheres: Vec::new(),
            capsules: Vec::new(),
            carriers: Vec::new(),
        }
    }
}

impl Motion {
    /// Clip time (seconds, within the key range) played at wall time `t_s`.
    pub fn clip_time_s(&self, t_s: f32) -> f32 {
        let t = t_s * self.speed;
        if self.duration_s > 0.0 && t.is_finite() {
            self.start_s + t.rem_euclid(self.duration_s).min(self.duration_s)
        } else {
            self.start_s
        }
    }

    /// The pose at wall time `t_s` (looped).
    pub fn sample(&self, t_s: f32) -> Pose {
        let mut pose = Pose {
            head: Affine3A::IDENTITY,
            spheres: Vec::with_capacity(self.spheres.len()),
            capsules: Vec::with_capacity(self.capsules.len()),
            carriers: Vec::with_capacity(self.carriers.len()),
        };
        self.sample_into(t_s, &mut pose);
        pose
    }

    /// The pose at wall time `t_s` (looped), written into `pose` without allocating once
    /// `pose.spheres` has the capacity.
    pub fn sample_into(&self, t_s: f32, pose: &mut Pose) {
        self.pose_at_clip_time(self.clip_time_s(t_s), pose);
    }

    /// Poses the character at wall time `t_s` (looped) into `out`: positions and normals in
    /// the pose world. Allocation-free once `out` has held this character. Does nothing
    /// without a character.
    pub fn pose_character(&self, t_s: f32, out: &mut CharacterPose) {
        self.pose_character_at_clip_time(self.clip_time_s(t_s), out);
    }

    /// [`Self::pose_character`] at clip time `clip_t` (seconds within the key range).
    pub(super) fn pose_character_at_clip_time(&self, clip_t: f32, out: &mut CharacterPose) {
        let Some(ch) = &self.character else {
            return;
        };
        out.node_worlds.clear();
        for node in &self.nodes {
            let local = node.local(clip_t);
            let world = match node.parent {
                Some(p) => out.node_worlds[p] * local,
                None => local,
            };
            out.node_worlds.push(world);
        }
        let to_pose = Affine3A::from_scale(Vec3::splat(1.0 / self.fit.scale));
        out.bone_mats.clear();
        out.bone_mats.extend(
            ch.bones
                .iter()
                .map(|b| to_pose * out.node_worlds[b.slot] * b.bind),
        );
        ch.skin(out);
    }

    /// The pose at clip time `clip_t` (seconds within the key range).
    pub(super) fn pose_at_clip_time(&self, clip_t: f32, pose: &mut Pose) {
        let inv_scale = 1.0 / self.fit.scale;
        pose.head = self.head_frame_of(&self.world(&self.head, clip_t), &self.head);
        pose.spheres.clear();
        for (joint, offset_m, radius_m) in &self.spheres {
            let (rot, origin) = self.joint_frame(joint, clip_t);
            let center = origin * inv_scale + rot * Vec3A::from(*offset_m);
            pose.spheres.push(Sphere {
                center: center.into(),
                radius_m: *radius_m,
            });
        }
        pose.capsules.clear();
        for c in &self.capsules {
            let m = self.world(&c.chain, clip_t) * c.bind;
            pose.capsules.push(Capsule {
                a: m.transform_point3(c.a) * inv_scale,
                b: m.transform_point3(c.b) * inv_scale,
                radius_m: c.radius_m,
            });
        }
        self.write_carriers(clip_t, &mut pose.carriers);
    }

    /// The head frame (head frame → pose world) when the head joint's world matrix is `w`:
    /// the joint's rest-aligned rotation, at the fitted head centre.
    pub(super) fn head_frame_of(&self, w: &Affine3A, head: &JointChain) -> Affine3A {
        let rot = rigid_rotation(w) * head.rest_align;
        let center_model = w.translation + rot * Vec3A::from(self.fit.offset_m);
        Affine3A {
            matrix3: Mat3A::from_quat(rot),
            translation: center_model / self.fit.scale,
        }
    }

    /// World matrix of a joint at clip time (model units, including node scales).
    pub(super) fn world(&self, joint: &JointChain, clip_t: f32) -> Affine3A {
        let mut m = Affine3A::IDENTITY;
        for &i in &joint.chain {
            m *= self.nodes[i].local(clip_t);
        }
        m
    }

    /// Rigid joint frame at clip time: rotation (rest-aligned) and origin (model metres).
    fn joint_frame(&self, joint: &JointChain, clip_t: f32) -> (Quat, Vec3A) {
        let m = self.world(joint, clip_t);
        (rigid_rotation(&m) * joint.rest_align, m.translation)
    }
}
