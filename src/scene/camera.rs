//! Where the camera is: a validated fixed camera ([`CameraSpec`]) or the engine's own framing
//! (close on the head and following it, [`HeadFollowing`], or the figure's upper half or
//! whole, `super::framing`), chosen by [`CameraSetup`].
//!
//! What: the user-facing camera description, checked once when it is made, so every later
//! stage can take it as given; [`crate::raster::Camera`] is the raster's plain-data pinhole
//! that both choices produce per frame.
//!
//! Why two choices: the default view frames the settled hair at a three-quarter front view and
//! follows the head's translation (not its rotation), so the dance stays in frame while its
//! turns stay visible. A comparison with another renderer needs the opposite: a camera fixed in
//! the world, given by eye, target, up and vertical field of view, exactly as a path tracer's
//! `perspective` sensor with `fov_axis = "y"` takes it.

// `!(a > b)` on purpose: unlike `a <= b` it is also true for NaN, so one test rejects both.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::Framing;
use crate::raster::Camera;
use glam::{Affine3A, Vec3};

/// Vertical field of view of the head-following camera, radians (30°).
pub const HEAD_FOLLOWING_FOV_Y_RAD: f32 = std::f32::consts::PI / 6.0;

/// Why a camera description was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CameraError {
    #[error("camera {field} must be finite (got {value})")]
    NonFinite { field: &'static str, value: Vec3 },
    #[error(
        "camera {field} {} is {distance_m:.3e} m from the origin: the eye and the target must \
         lie within {max_m} m of it, where 32-bit positions still resolve 1 mm (the figure is \
         held within it too)",
        super::shown(*.value)
    )]
    TooFar {
        field: &'static str,
        value: Vec3,
        distance_m: f64,
        max_m: f32,
    },
    #[error("camera eye and target must differ (both {0})")]
    EyeAtTarget(Vec3),
    #[error("camera up {up} must be non-zero and not parallel to the view direction {forward}")]
    UpAlongView { up: Vec3, forward: Vec3 },
    #[error("camera vertical field of view must be in (0, 180) degrees (got {fov_y_deg} degrees)")]
    FieldOfView { fov_y_deg: f32 },
}

/// A camera fixed in the world: eye, target, up (world metres, Y up) and vertical field of view.
/// Fields are private so that every value has passed [`CameraSpec::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSpec {
    eye: Vec3,
    target: Vec3,
    up: Vec3,
    fov_y_rad: f32,
}

impl CameraSpec {
    /// Checks that everything is finite, that eye and target lie within
    /// [`MAX_POSE_DISTANCE_M`](crate::motion::MAX_POSE_DISTANCE_M) of the origin (beyond, the
    /// view direction is lost to rounding, and the figure is held within it), that eye and
    /// target differ (by more than 1 µm), that
    /// `up` is not parallel to the view direction (sine of the angle above 1e-4) and that the
    /// vertical field of view is in (0, π) radians.
    pub fn new(eye: Vec3, target: Vec3, up: Vec3, fov_y_rad: f32) -> Result<Self, CameraError> {
        for (field, value) in [("eye", eye), ("target", target), ("up", up)] {
            if !value.is_finite() {
                return Err(CameraError::NonFinite { field, value });
            }
        }
        let max_m = crate::motion::MAX_POSE_DISTANCE_M;
        for (field, value) in [("eye", eye), ("target", target)] {
            let distance_m = value.as_dvec3().length();
            if distance_m > f64::from(max_m) {
                return Err(CameraError::TooFar {
                    field,
                    value,
                    distance_m,
                    max_m,
                });
            }
        }
        let view = target - eye;
        if !(view.length() > 1e-6) {
            return Err(CameraError::EyeAtTarget(eye));
        }
        let forward = view.normalize();
        let up_len = up.length();
        if !(up_len > 0.0) || !(forward.cross(up / up_len).length() > 1e-4) {
            return Err(CameraError::UpAlongView { up, forward });
        }
        if !(fov_y_rad > 0.0 && fov_y_rad < std::f32::consts::PI) {
            return Err(CameraError::FieldOfView {
                fov_y_deg: fov_y_rad.to_degrees(),
            });
        }
        Ok(Self {
            eye,
            target,
            up,
            fov_y_rad,
        })
    }

    /// Eye position, world metres.
    pub fn eye(&self) -> Vec3 {
        self.eye
    }
    /// The point looked at, world metres.
    pub fn target(&self) -> Vec3 {
        self.target
    }
    /// World up hint (the image's up is its part orthogonal to the view direction).
    pub fn up(&self) -> Vec3 {
        self.up
    }
    /// Vertical field of view, radians.
    pub fn fov_y_rad(&self) -> f32 {
        self.fov_y_rad
    }

    /// The raster camera for a `width` x `height` image (default near plane).
    pub fn camera(&self, width: u32, height: u32) -> Camera {
        Camera::look_at(
            self.eye,
            self.target,
            self.up,
            self.fov_y_rad,
            width,
            height,
        )
    }

    /// The same description read back from a raster camera (for exporting the camera a frame
    /// was drawn with). `None` when the camera would not pass [`CameraSpec::new`].
    pub fn from_camera(cam: &Camera) -> Option<Self> {
        Self::new(cam.eye, cam.target, cam.up, cam.fov_y_rad).ok()
    }
}

/// How the engine places its camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraSetup {
    /// The engine's own camera, at a three-quarter front view of the first pose, showing as
    /// much of the figure as the [`Framing`] says (`None`: [`Framing::default_for`] the
    /// motion); `head` follows the head's translation ([`HeadFollowing`]), `upper` and `full`
    /// stand still. The default.
    Framed(Option<Framing>),
    /// A camera fixed in the world.
    Fixed(CameraSpec),
}

impl Default for CameraSetup {
    fn default() -> Self {
        CameraSetup::Framed(None)
    }
}

/// The head-following framing: the target and eye as offsets from the head's position, fixed
/// when the hair is framed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeadFollowing {
    /// Camera target relative to the head centre (world metres).
    target_offset: Vec3,
    /// Camera eye relative to the target (world metres).
    eye_offset: Vec3,
}

impl HeadFollowing {
    /// Frames the hair (`strand_positions`, non-finite points ignored) and the head (`head`
    /// transform, its translation is the head centre) from three-quarters front of the head's
    /// orientation. `max_length_m` leaves room for the hair to swing by about a tenth of it.
    /// Returns the framing and the camera of this first pose (whose near plane is scaled to the
    /// framed sphere).
    pub fn frame(
        strand_positions: &[Vec3],
        head: Affine3A,
        max_length_m: f32,
        width: u32,
        height: u32,
    ) -> (HeadFollowing, Camera) {
        let (lo, hi) = strand_positions.iter().fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(lo, hi), p| {
                if p.is_finite() {
                    (lo.min(*p), hi.max(*p))
                } else {
                    (lo, hi)
                }
            },
        );
        let head0: Vec3 = head.translation.into();
        let (lo, hi) = if lo.x <= hi.x {
            (lo.min(head0), hi.max(head0))
        } else {
            (head0, head0)
        };
        let centre = 0.5 * (lo + hi);
        // Half the largest extent (a tall, thin head of hair fills the frame's height), plus room
        // for the hair to swing by about a tenth of its length.
        let radius = 0.55 * (hi - lo).max_element() + 0.1 * max_length_m;
        let view = head
            .transform_vector3(Vec3::new(0.55, 0.12, 1.0))
            .normalize_or(Vec3::Z);
        let cam = Camera::framing(
            centre,
            radius.max(0.05),
            view,
            HEAD_FOLLOWING_FOV_Y_RAD,
            width,
            height,
        );
        let rig = HeadFollowing {
            target_offset: centre - head0,
            eye_offset: cam.eye() - centre,
        };
        (rig, cam)
    }

    /// The camera with the head centre at `head_translation` (world metres).
    pub fn camera(&self, head_translation: Vec3, width: u32, height: u32) -> Camera {
        let target = head_translation + self.target_offset;
        Camera::look_at(
            target + self.eye_offset,
            target,
            Vec3::Y,
            HEAD_FOLLOWING_FOV_Y_RAD,
            width,
            height,
        )
    }
}

#[cfg(test)]
mod tests;
