//! Where the camera is: fixed in the world, or the engine's own framing from three-quarters
//! front: close on the settled hair and following the head's translation
//! (`crate::scene::HeadFollowing`), or the figure's upper half or whole over the clip, still
//! (`crate::scene::framing`). It is placed once the hair has settled; a head-following one is
//! moved with the head before each render.

use crate::motion::{Motion, Pose};
use crate::raster::Camera;
use crate::scene::{
    CameraSetup, Framing, HEAD_FOLLOWING_FOV_Y_RAD, HeadFollowing, Scene, ViewAxes, frame_boxes,
};
use glam::Vec3;

/// The camera of the frame, and the head-following framing when it follows the head.
#[derive(Clone, Debug)]
pub struct CameraPass {
    camera: Camera,
    follow: Option<HeadFollowing>,
}

/// What the engine's own camera is framed on: the settled hair, the pose at time 0, the
/// motion (its character's extent) and the hair's longest strand.
#[derive(Clone, Copy)]
pub struct FramingInput<'a> {
    pub strand_positions: &'a [Vec3],
    pub pose: &'a Pose,
    pub motion: &'a Motion,
    pub max_length_m: f32,
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
    /// engine's framing of `input` ([`Framing`]; unset, `upper` when the motion has a body
    /// and the scene draws solids, else `head`). `upper` and `full` without a character
    /// frame as `head` does.
    pub fn place(&mut self, scene: &Scene, input: FramingInput) {
        let (w, h) = (scene.width, scene.height);
        let framing = match scene.camera {
            CameraSetup::Fixed(spec) => {
                self.follow = None;
                self.camera = spec.camera(w, h);
                return;
            }
            CameraSetup::Framed(framing) => framing.unwrap_or_else(|| {
                Framing::default_for(scene.draw_solids && input.motion.has_body())
            }),
        };
        let axes = ViewAxes::looking_back_along(three_quarter_view(input.pose));
        let figure = match framing {
            Framing::Head => None,
            Framing::Upper | Framing::Full => {
                input
                    .motion
                    .figure_extent([axes.right, axes.up, axes.forward])
            }
        };
        match figure {
            Some(extent) => {
                let mut boxes = if framing == Framing::Full {
                    extent.full
                } else {
                    extent.upper
                };
                with_hair(&mut boxes, axes, &input);
                self.follow = None;
                self.camera = frame_boxes(&boxes, axes, HEAD_FOLLOWING_FOV_Y_RAD, w, h);
            }
            None => {
                let (rig, cam) = HeadFollowing::frame(
                    input.strand_positions,
                    input.pose.head,
                    input.max_length_m,
                    w,
                    h,
                );
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

    /// Whether the camera moves with the head (the `head` framing).
    pub fn follows_head(&self) -> bool {
        self.follow.is_some()
    }

    pub fn camera(&self) -> &Camera {
        &self.camera
    }
}

/// The direction from the target toward the eye: three-quarters front of the head at time 0,
/// slightly above (the head-following camera's view).
fn three_quarter_view(pose: &Pose) -> Vec3 {
    pose.head
        .transform_vector3(Vec3::new(0.55, 0.12, 1.0))
        .normalize_or(Vec3::Z)
}

/// The figure's boxes (in `axes`) with the settled hair and the head's box added (the parts
/// above the figure's lowest point: hair below the hips is left out of the upper framing),
/// each grown by a tenth of the longest strand on every side: room for the hair to swing, as
/// the head framing leaves.
fn with_hair(boxes: &mut Vec<(Vec3, Vec3)>, axes: ViewAxes, input: &FramingInput) {
    let floor = boxes.iter().map(|b| b.0.y).fold(f32::INFINITY, f32::min);
    let head = Vec3::from(input.pose.head.translation);
    let hair = input
        .strand_positions
        .iter()
        .chain([&head])
        .filter(|p| p.is_finite())
        .map(|p| axes.coords(*p))
        .filter(|q| q.y >= floor)
        .fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), q| (lo.min(q), hi.max(q)),
        );
    boxes.push(hair);
    let room = Vec3::splat(0.1 * input.max_length_m.max(0.0));
    for b in boxes.iter_mut() {
        *b = (b.0 - room, b.1 + room);
    }
}
