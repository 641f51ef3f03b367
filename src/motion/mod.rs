//! Motion: the head (and body-collider) transforms of a dancing character at any time, read
//! from a glTF 2.0 animation clip (`.glb` or `.gltf`).
//!
//! # What it does
//! [`Motion::load`] parses a glTF file (by content, not extension), picks a clip (by name;
//! default "Dance" if present, else the first) and a head joint (by name or node index;
//! default: a skin joint named like "head"), and precomputes, for every node on the path from
//! the scene root to the head joint (and to each body-sphere joint), its rest transform and
//! the clip's translation / rotation / scale tracks ([`sampler::Track`]). [`Motion::sample_into`]
//! then evaluates the joint's world matrix through the hierarchy (parent · local, root first)
//! with binary search on key times: no allocation, no hash map in the hot path.
//!
//! # Frames and the scale convention
//! - The **hairstyle head frame**: metres, origin at the head centre, +Y up, +Z toward the face.
//! - The **joint frame**: origin at the head joint, axes equal to the model's world axes when
//!   the model stands in its rest pose (glTF: +Y up, the model faces +Z), and then carried
//!   rigidly by the joint's rotation. Orienting by the rest pose makes the hairstyle upright and
//!   facing forward whatever local axis convention the rig uses (Blender bones point along +Y,
//!   Mixamo ones differ, Z-up exports carry a −90° root rotation).
//! - A [`Fit`] maps the hairstyle head frame into the joint frame: `x_joint = scale·x_hair +
//!   offset_m` (model metres). `None` estimates it (see [`fit`]).
//! - The engine simulates a real 0.09 m-radius head. So the **world of a [`Pose`] is the
//!   model's world divided by `fit.scale`**: a cartoon robot whose head is 5× too big is seen
//!   as a 5× smaller scene around a human-sized head. `pose.head` is therefore rigid (rotation
//!   and translation only; node scales such as a centimetre-to-metre ×100 are part of the world
//!   matrix but stripped from the head frame), and body-sphere centres and all translations are
//!   in the same scaled world (metres of the hair simulation).
//!
//! # Why this design
//! Only the few nodes that lead to the head and collider joints are evaluated (about ten for a
//! humanoid rig), each by walking its own root-to-joint chain, so `sample_into` needs no
//! scratch buffer; skinning and meshes are used only once, at load time, for the automatic fit.
//!
//! # Time
//! Clip time is `t_s · speed`, wrapped into the clip's key range `[first key, last key]`
//! (`rem_euclid`), so `sample(t) == sample(t + duration / speed)`; a seamless clip has equal
//! poses at both ends. Morph-target `weights` channels are ignored.
//!
//! # Where
//! Loading (`load.rs` sequences it): the container, buffers and accessors (`gltf_io/`), the
//! hierarchy at rest (`skeleton.rs`), the clip (`clip.rs`), the head and collider joints
//! (`joints.rs`), the character's meshes ([`skin`], [`texture`]), the fit ([`fit`]), the
//! colliders ([`colliders`], `capsules.rs`), the evaluated nodes (`chain.rs`) and the reach
//! check (`reach.rs`). Sampling: `pose.rs` over the [`sampler`] tracks. Options and errors:
//! `options.rs`, `error.rs`.

mod capsules;
mod chain;
mod clip;
pub mod colliders;
pub mod dance;
mod error;
pub mod fit;
mod gltf_io;
mod joints;
mod load;
mod options;
mod pose;
mod reach;
pub mod sampler;
pub mod scalp;
mod skeleton;
pub mod skin;
pub mod texture;

pub use error::MotionError;
pub use gltf_io::{MAX_BUFFER_BYTES, MAX_DECODED_VALUES, MAX_FILE_BYTES, MAX_JSON_CONTAINERS};
pub use options::{Fit, JointRef, MotionOptions, SphereSpec};
pub use pose::{Capsule, Pose, Sphere};
pub use scalp::RootsOnHead;
pub use skin::{Character, CharacterPose, Material};
pub use texture::Texture;

use std::path::Path;

use glam::{Affine3A, Quat, Vec3};

use chain::{CapsuleSpec, ChainNode, JointChain};

/// Farthest a head or body collider may be from the world origin, pose metres. Positions are
/// f32: at 10 km their spacing is 1 mm, the collision margin, and beyond it the hair simulation
/// and the camera lose the hair (keyframes of 1e30 give blank frames).
pub const MAX_POSE_DISTANCE_M: f32 = 10_000.0;

/// Head radius in metres that hairstyles are made for (the fit maps a head of this size onto
/// the model's head).
pub const HAIRSTYLE_HEAD_RADIUS_M: f32 = 0.09;

/// A clip ready to be sampled. See the module doc.
#[derive(Clone, Debug)]
pub struct Motion {
    pub(crate) clip_name: String,
    pub(crate) start_s: f32,
    pub(crate) duration_s: f32,
    pub(crate) speed: f32,
    pub(crate) fit: Fit,
    pub(crate) fit_method: fit::FitMethod,
    pub(crate) nodes: Vec<ChainNode>,
    pub(crate) head: JointChain,
    /// Body spheres: joint, offset (pose metres, joint frame), radius (pose metres).
    pub(crate) spheres: Vec<(JointChain, Vec3, f32)>,
    /// Body capsules: the bone's chain and bind matrix, the segment ends in bind space (model
    /// units) and the radius in pose metres.
    pub(crate) capsules: Vec<CapsuleSpec>,
    /// The character's meshes, if the file has any (and they were asked for).
    pub(crate) character: Option<Character>,
    /// Half extents of the head mesh's bounding box in the head joint frame, pose metres
    /// (`None` without a head mesh).
    pub(crate) head_half_extents_m: Option<Vec3>,
    pub(crate) head_joint_name: String,
    pub(crate) head_joint_index: usize,
}

impl Motion {
    /// Loads a glTF 2.0 motion from a `.glb` or `.gltf` file (recognised by content). Relative
    /// buffer URIs are resolved next to the file; `data:` base64 URIs are decoded.
    pub fn load(path: &Path, opts: &MotionOptions) -> Result<Motion, MotionError> {
        let name = path.display().to_string();
        let bytes =
            crate::input::read_capped(path, MAX_FILE_BYTES, "a glTF file").map_err(|error| {
                MotionError::Io {
                    file: name.clone(),
                    error,
                }
            })?;
        load::from_bytes(&bytes, &name, path.parent(), opts)
    }

    /// Loads a motion from the bytes of a `.glb` (or a self-contained `.gltf` whose buffers
    /// are `data:` URIs). `name_for_errors` is the file name used in error messages.
    pub fn from_glb_bytes(
        bytes: &[u8],
        name_for_errors: &str,
        opts: &MotionOptions,
    ) -> Result<Motion, MotionError> {
        load::from_bytes(bytes, name_for_errors, None, opts)
    }

    /// The project's own dance (`animations/dance.glb`, made by `examples/make_dance.rs`), with
    /// default options: a human-sized rig, so the automatic fit is scale 1.
    pub fn default_dance() -> Motion {
        dance::default_dance()
    }

    /// A motionless pose: `head` at all times, no body spheres, duration 0.
    pub fn still(head: Affine3A) -> Motion {
        Motion {
            clip_name: "still".to_string(),
            start_s: 0.0,
            duration_s: 0.0,
            speed: 1.0,
            fit: Fit::IDENTITY,
            fit_method: fit::FitMethod::Given,
            nodes: vec![ChainNode {
                parent: None,
                rest_matrix: Some(head),
                rest_t: Vec3::ZERO,
                rest_r: Quat::IDENTITY,
                rest_s: Vec3::ONE,
                translation: None,
                rotation: None,
                scale: None,
            }],
            head: JointChain {
                chain: vec![0],
                rest_align: Quat::IDENTITY,
            },
            spheres: Vec::new(),
            capsules: Vec::new(),
            character: None,
            head_half_extents_m: None,
            head_joint_name: "still".to_string(),
            head_joint_index: 0,
        }
    }

    /// Heap bytes held: the key times and values of the evaluated nodes' tracks.
    pub fn held_bytes(&self) -> u64 {
        let tracks = self
            .nodes
            .iter()
            .flat_map(|n| [&n.translation, &n.rotation, &n.scale])
            .flatten()
            .map(|t| t.held_bytes())
            .sum::<u64>();
        let character = self
            .character
            .as_ref()
            .map_or(0, |c| c.held_bytes() + c.pose_bytes(self.nodes.len()));
        tracks + (self.nodes.len() * size_of::<ChainNode>()) as u64 + character
    }

    /// The character's meshes (bind space), if the motion has any.
    pub fn character(&self) -> Option<&Character> {
        self.character.as_ref()
    }

    /// Half extents of the head mesh's bounding box in the head joint frame (rest-pose world
    /// axes), pose metres; `None` when the file has no head mesh.
    pub fn head_half_extents_m(&self) -> Option<Vec3> {
        self.head_half_extents_m
    }

    /// Clip length in seconds of clip time (last key − first key; 0 for [`Motion::still`]).
    pub fn duration_s(&self) -> f32 {
        self.duration_s
    }

    /// Name of the clip being played.
    pub fn clip_name(&self) -> &str {
        &self.clip_name
    }

    /// The fit in use (given or estimated).
    pub fn fit(&self) -> Fit {
        self.fit
    }

    /// How the fit was obtained (given, or which automatic estimate).
    pub fn fit_method(&self) -> fit::FitMethod {
        self.fit_method
    }

    /// Playback rate.
    pub fn speed(&self) -> f32 {
        self.speed
    }

    /// Head joint: glTF node index and name.
    pub fn head_joint(&self) -> (usize, &str) {
        (self.head_joint_index, &self.head_joint_name)
    }
}
