//! What a frame is looked at with and lit by, apart from the hair and the motion: the camera
//! and the scene file, each validated into the types the engine takes.
//!
//! - [`camera`]: a fixed camera ([`CameraSpec`]) or the engine's own framing.
//! - [`framing`]: how much of the figure the engine's camera shows ([`Framing`]: head, upper
//!   body, whole figure).
//! - [`file`](mod@file): the scene file (camera, lights, ambient, background, exposure, image size) and
//!   its validation into a [`file::Scene`].

pub mod camera;
pub mod file;
pub mod framing;

pub use camera::{CameraError, CameraSetup, CameraSpec, HEAD_FOLLOWING_FOV_Y_RAD, HeadFollowing};
pub use file::{Scene, SceneError, SceneFile};
pub use framing::{Framing, ViewAxes, frame_boxes};
