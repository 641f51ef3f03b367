//! What a frame is looked at with and lit by, apart from the hair and the motion: the camera
//! and the scene file, each validated into the types the engine takes.
//!
//! - [`camera`]: a fixed camera ([`CameraSpec`]) or the engine's head-following framing.
//! - [`file`](mod@file): the scene file (camera, lights, ambient, background, exposure, image size) and
//!   its validation into a [`file::Scene`].

pub mod camera;
pub mod file;

pub use camera::{CameraError, CameraSetup, CameraSpec, HEAD_FOLLOWING_FOV_Y_RAD, HeadFollowing};
pub use file::{Scene, SceneError, SceneFile};
