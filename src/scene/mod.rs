//! What a frame is looked at with: the scene description that is not hair, motion or light,
//! as validated types that a scene file can later be built on.
//!
//! - [`camera`]: a fixed camera ([`CameraSpec`]) or the engine's head-following framing.
//! - [`file`]: the scene file (camera, lights, ambient, background, exposure, image size) and
//!   its validation into a [`file::Scene`].

pub mod camera;
pub mod file;

pub use camera::{CameraError, CameraSetup, CameraSpec, HEAD_FOLLOWING_FOV_Y_RAD, HeadFollowing};
pub use file::{Scene, SceneError, SceneFile};
