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
//! check (`reach.rs`). The loaded motion and what it says of itself: `playback.rs`. Sampling:
//! `pose.rs` over the [`sampler`] tracks. Options and errors: `options.rs`, `error.rs`.

mod capsules;
mod carriers;
mod chain;
mod clip;
pub mod colliders;
pub mod dance;
mod error;
mod extent;
pub mod fit;
mod gltf_io;
mod joints;
mod load;
mod options;
mod playback;
mod pose;
mod reach;
pub mod sampler;
pub mod scalp;
mod skeleton;
pub mod skin;
pub mod texture;
pub mod up_axis;

pub use carriers::CarryError;
pub use error::MotionError;
pub use extent::FigureExtent;
pub use fit::HAIRSTYLE_HEAD_RADIUS_M;
pub use gltf_io::{MAX_BUFFER_BYTES, MAX_DECODED_VALUES, MAX_FILE_BYTES, MAX_JSON_CONTAINERS};
pub use options::{Fit, JointRef, MotionOptions, SphereSpec};
pub use playback::Motion;
pub use pose::{Capsule, Pose, Sphere};
pub use reach::MAX_POSE_DISTANCE_M;
pub use scalp::RootsOnHead;
pub use skin::{Character, CharacterPose, Material};
pub use texture::Texture;
