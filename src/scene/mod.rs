//! What a frame is looked at with and lit by, apart from the hair and the motion: the camera
//! and the scene file, each validated into the types the engine takes.
//!
//! - [`camera`]: a fixed camera ([`CameraSpec`]) or the engine's own framing.
//! - [`framing`]: how much of the figure the engine's camera shows ([`Framing`]: head, upper
//!   body, whole figure).
//! - [`file`](mod@file): the scene file (camera, lights, ambient, background, exposure, image size) and
//!   its validation into a [`file::Scene`].
//! - [`far_light`]: a point light too far for its map drawn as the directional light it is.

pub mod camera;
pub mod far_light;
pub mod file;
pub mod framing;

pub use camera::{CameraError, CameraSetup, CameraSpec, HEAD_FOLLOWING_FOV_Y_RAD, HeadFollowing};
pub use file::{Scene, SceneError, SceneFile};
pub use framing::{Framing, ViewAxes, frame_boxes};

/// `v` for a message, large components in scientific notation (`[3e38, 1.6, inf]`).
pub(crate) fn shown(v: glam::Vec3) -> String {
    let one = |x: f32| {
        if x.is_finite() && x.abs() >= 1e6 {
            format!("{x:e}")
        } else {
            format!("{x}")
        }
    };
    format!("[{}, {}, {}]", one(v.x), one(v.y), one(v.z))
}
