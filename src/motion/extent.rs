//! Where the character's figure reaches over its whole clip ([`Motion::figure_extent`]): the
//! box the camera frames when it shows the body, not the head alone (`crate::scene::Framing`).
//!
//! What: the character is posed (skinned, as the raster draws it) at evenly spaced clip times
//! from the first key to the last, and each time's posed vertices are taken into a box in the
//! pose world, measured along a camera's axes: the whole figure, and its upper half (the vertices in the top half of that time's
//! figure: a standing human's hip joints are at about half its height, so this is the head,
//! arms and trunk down to the hips, found without any joint names).
//!
//! Why the whole clip and not the current frame: a camera framed on each frame's pose would
//! move with every bob of the hips; framed once on the clip's whole range of motion it stands
//! still and the dance moves inside the picture, and it is the same for every frame, shard and
//! thread count (the samples' times depend only on the clip).

use glam::Vec3;

use super::playback::Motion;
use super::skin::CharacterPose;

/// Clip samples a second for the extent (the dance's fastest moves last a few tenths of a
/// second; the box is padded by the framing anyway).
const SAMPLES_PER_S: f32 = 30.0;
/// Most samples, and most posed vertices over all samples (a large character is sampled
/// more coarsely in time: 4 M vertices skin in well under a second).
const MAX_SAMPLES: usize = 241;
const MAX_POSED_VERTICES: usize = 4_000_000;
/// Posed vertices farther than this from the head centre (pose metres: a human-sized world)
/// are left out: a whole figure, arms raised, lies within 2.2 m of its head, and one stray
/// vertex of a broken rig must not move the camera out of sight of the rest.
const MAX_REACH_M: f32 = 3.0;
/// The upper body: the top fraction of the figure's height.
const UPPER_FRACTION: f32 = 0.5;
/// Slabs of height each sample's figure is cut into, each boxed on its own: at one instant
/// the head is shallow while the arms below it reach forward, and one box of the whole figure
/// would put the head's height at the arms' depth.
const SLABS: usize = 8;

/// Boxes in the coordinates along three axes (metres; see [`Motion::figure_extent`]),
/// `(lo, hi)` corners, a few per clip sample ([`SLABS`] of height): the figure at each
/// instant is much smaller than the box of all of them (a turn sweeps the arms round a box as
/// deep as it is wide), so a camera fitted to these boxes stands nearer than one fitted to
/// their union, and still sees every vertex.
#[derive(Clone, Debug, PartialEq)]
pub struct FigureExtent {
    /// Every posed vertex of each sample.
    pub full: Vec<(Vec3, Vec3)>,
    /// The vertices in the top half of each sample's figure (head to hips).
    pub upper: Vec<(Vec3, Vec3)>,
}

impl Motion {
    /// The character's extent over the clip (see the module doc), in the coordinates
    /// `(p·axes[0], p·axes[1], p·axes[2])` of pose-world points `p` (a camera's axes: the
    /// box a camera must see, tighter than a world box seen at an angle); the upper half is
    /// cut along world +Y. `None` without a character or with no finite posed vertex.
    pub fn figure_extent(&self, axes: [Vec3; 3]) -> Option<FigureExtent> {
        let ch = self.character.as_ref()?;
        let vertices = ch.vertex_count().max(1);
        let wanted = if self.duration_s > 0.0 {
            (self.duration_s * SAMPLES_PER_S).ceil() as usize + 1
        } else {
            1
        };
        let samples = wanted
            .min(MAX_SAMPLES)
            .min((MAX_POSED_VERTICES / vertices).max(2));
        let mut posed = CharacterPose::default();
        let mut head = super::Pose::default();
        let mut near: Vec<Vec3> = Vec::with_capacity(vertices);
        let mut full = Vec::with_capacity(samples * SLABS);
        let mut upper = Vec::with_capacity(samples * SLABS);
        for k in 0..samples {
            let f = if samples > 1 {
                k as f32 / (samples - 1) as f32
            } else {
                0.0
            };
            let clip_t = self.start_s + f * self.duration_s;
            self.pose_character_at_clip_time(clip_t, &mut posed);
            self.pose_at_clip_time(clip_t, &mut head);
            let centre = Vec3::from(head.head.translation);
            near.clear();
            near.extend(
                posed
                    .positions
                    .iter()
                    .filter(|p| p.is_finite() && p.distance(centre) <= MAX_REACH_M),
            );
            let (bottom_y, top_y) = near
                .iter()
                .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(p.y), hi.max(p.y))
                });
            if bottom_y > top_y || bottom_y.is_nan() {
                continue;
            }
            let cut_y = top_y - UPPER_FRACTION * (top_y - bottom_y);
            full.extend(slab_boxes(&near, (bottom_y, top_y), axes));
            upper.extend(slab_boxes(&near, (cut_y, top_y), axes));
        }
        (!full.is_empty()).then_some(FigureExtent { full, upper })
    }

    /// Whether the motion has a character with more than a head (a vertex of the body).
    pub fn has_body(&self) -> bool {
        self.character
            .as_ref()
            .is_some_and(|ch| (0..ch.vertex_count()).any(|v| !ch.is_head_vertex(v)))
    }
}

/// The boxes (along `axes`) of the `points` in each of [`SLABS`] equal slabs of world
/// height between `lo_y` and `hi_y` (points outside are left out), the empty ones left out.
fn slab_boxes(points: &[Vec3], (lo_y, hi_y): (f32, f32), axes: [Vec3; 3]) -> Vec<(Vec3, Vec3)> {
    let mut slabs = [empty_box(); SLABS];
    let per_m = SLABS as f32 / (hi_y - lo_y).max(1e-6);
    for p in points
        .iter()
        .filter(|p| p.is_finite() && p.y >= lo_y && p.y <= hi_y)
    {
        let k = (((p.y - lo_y) * per_m) as usize).min(SLABS - 1);
        let q = Vec3::new(p.dot(axes[0]), p.dot(axes[1]), p.dot(axes[2]));
        slabs[k] = (slabs[k].0.min(q), slabs[k].1.max(q));
    }
    slabs.into_iter().filter(|(lo, hi)| lo.x <= hi.x).collect()
}

/// An empty box (lo above hi on every axis).
fn empty_box() -> (Vec3, Vec3) {
    (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY))
}
