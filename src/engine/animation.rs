//! The animation pass: the motion sampled at a frame's time. It gives the head's and the body
//! colliders' pose (which the simulation, the interpolation and the solids follow) and the
//! character's skinned mesh (which the occluders and the raster draw).

use super::sizes::RunSizes;
use crate::budget::{MemoryPart, grouped};
use crate::motion::{Character, CharacterPose, Motion, Pose};
use glam::Vec3;

/// The motion and its pose at the last sampled time.
pub struct AnimationPass {
    motion: Motion,
    /// The last sampled time, seconds of the motion.
    time_s: f64,
    pose: Pose,
    /// The character's mesh posed at the last sampled time (empty without a character, or
    /// before the first sample).
    character: CharacterPose,
}

impl AnimationPass {
    /// The motion at rest at t = 0 (its mesh is posed by the first [`Self::run`]).
    pub fn new(motion: Motion) -> Self {
        Self {
            pose: motion.sample(0.0),
            motion,
            time_s: 0.0,
            character: CharacterPose::default(),
        }
    }

    /// Samples the motion at `t_s` (seconds of the motion): the pose and the posed mesh.
    pub fn run(&mut self, t_s: f64) {
        self.time_s = t_s;
        self.motion.sample_into(t_s as f32, &mut self.pose);
        self.motion.pose_character(t_s as f32, &mut self.character);
    }

    /// The last sampled time, seconds of the motion.
    pub fn time_s(&self) -> f64 {
        self.time_s
    }

    pub fn motion(&self) -> &Motion {
        &self.motion
    }

    /// The head and body colliders at the last sampled time.
    pub fn pose(&self) -> &Pose {
        &self.pose
    }

    /// The character's mesh at the last sampled time (pose world; empty without a character).
    pub fn character_pose(&self) -> &CharacterPose {
        &self.character
    }

    /// The character and its posed mesh, when the motion has one.
    pub fn character(&self) -> Option<(&Character, &CharacterPose)> {
        self.motion.character().map(|c| (c, &self.character))
    }

    /// The motion's keyframes and, with a character, its mesh and the posed copy.
    pub fn estimate(motion: &Motion, sizes: &RunSizes) -> Vec<MemoryPart> {
        let mut parts = vec![MemoryPart {
            what: "motion",
            product: format!("clip \"{}\" keyframes", motion.clip_name()),
            bytes: motion.held_bytes(),
            set_by: "the glTF clip",
        }];
        if sizes.character_vertices > 0 {
            parts.push(MemoryPart {
                what: "posed character",
                product: format!("{} vertices", grouped(sizes.character_vertices)),
                bytes: sizes.character_vertices * size_of::<Vec3>() as u64,
                set_by: "the glTF's meshes",
            });
        }
        parts
    }
}
