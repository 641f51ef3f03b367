//! Where the camera is: fixed in the world, or framing the settled hair from three-quarters
//! front and following the head's translation (`crate::scene::HeadFollowing`). It is placed
//! once the hair has settled and moved with the head before each render.

use crate::motion::Pose;
use crate::raster::Camera;
use crate::scene::{CameraSetup, HEAD_FOLLOWING_FOV_Y_RAD, HeadFollowing, Scene};
use glam::Vec3;

/// The camera of the frame, and the head-following framing when it follows the head.
#[derive(Clone, Debug)]
pub struct CameraPass {
    camera: Camera,
    follow: Option<HeadFollowing>,
}

impl CameraPass {
    /// A camera for an image of the scene's size; [`Self::place`] sets it before any render.
    pub fn new(scene: &Scene) -> Self {
        Self {
            camera: Camera::look_at(
                Vec3::Z,
                Vec3::ZERO,
                Vec3::Y,
                HEAD_FOLLOWING_FOV_Y_RAD,
                scene.width,
                scene.height,
            ),
            follow: None,
        }
    }

    /// Places the camera of `scene` for an image of its size: the fixed camera, or the
    /// head-following framing of `strand_positions` around `pose`'s head for hair up to
    /// `max_length_m` long.
    pub fn place(
        &mut self,
        scene: &Scene,
        strand_positions: &[Vec3],
        pose: &Pose,
        max_length_m: f32,
    ) {
        let (w, h) = (scene.width, scene.height);
        match scene.camera {
            CameraSetup::Fixed(spec) => {
                self.follow = None;
                self.camera = spec.camera(w, h);
            }
            CameraSetup::HeadFollowing => {
                let (rig, cam) =
                    HeadFollowing::frame(strand_positions, pose.head, max_length_m, w, h);
                self.follow = Some(rig);
                self.camera = cam;
            }
        }
    }

    /// Moves a head-following camera with `pose`'s head (a fixed one stays).
    pub fn follow(&mut self, scene: &Scene, pose: &Pose) {
        if let Some(rig) = &self.follow {
            self.camera = rig.camera(Vec3::from(pose.head.translation), scene.width, scene.height);
        }
    }

    pub fn camera(&self) -> &Camera {
        &self.camera
    }
}
