//! A loaded motion ([`Motion`]): the clip's evaluated nodes and tracks, the head joint and the
//! fit, the body colliders and the character, with what it says of itself (clip, fit,
//! duration, memory), its simplest constructor (a head alone, still) and the clip's first pose
//! held still ([`Motion::held_still`]). Building one from a file is
//! `load.rs` ([`Motion::load`]), the embedded dance `dance.rs`, sampling one `pose.rs`.

use glam::{Affine3A, Quat, Vec3};

use super::chain::{CapsuleSpec, ChainNode, JointChain};
use super::fit::FitMethod;
use super::options::Fit;
use super::skin::Character;

/// A clip ready to be sampled. See the module doc.
#[derive(Clone, Debug)]
pub struct Motion {
    pub(crate) clip_name: String,
    pub(crate) start_s: f32,
    pub(crate) duration_s: f32,
    pub(crate) speed: f32,
    pub(crate) fit: Fit,
    pub(crate) fit_method: FitMethod,
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
    /// The world axis the model stood along in the file (+Y unless it was turned upright,
    /// see [`super::up_axis`]).
    pub(crate) file_up: Vec3,
    /// The head joint was found as the topmost joint (no joint is named like "head").
    pub(crate) head_is_topmost: bool,
    /// Bones that carry a groom's roots (`carriers.rs`); empty for hair on a head.
    pub(crate) carriers: Vec<super::carriers::Carrier>,
}

impl Motion {
    /// A motionless pose: `head` at all times, no body spheres, duration 0.
    pub fn still(head: Affine3A) -> Motion {
        Motion {
            clip_name: "still".to_string(),
            start_s: 0.0,
            duration_s: 0.0,
            speed: 1.0,
            fit: Fit::IDENTITY,
            fit_method: FitMethod::Given,
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
            file_up: Vec3::Y,
            head_is_topmost: false,
            carriers: Vec::new(),
        }
    }

    /// The clip's first pose held still: every evaluated node keeps its transform at the
    /// clip's first key, and the whole figure is moved so that the head centre is at the
    /// origin (the head frame is the first pose's rotation and no translation, up to rounding),
    /// as [`Motion::still`] puts the head there. The character, its colliders and the fit stay,
    /// so hair sits on a standing body instead of a head alone. Duration 0.
    ///
    /// The first key rather than the bind pose: a rig's bind pose is often a T-pose with the
    /// arms through the hair's fall, while the first key is a pose the clip was made to start
    /// from and the one the moving run settles its hair on.
    pub fn held_still(mut self) -> Motion {
        let clip_t = self.start_s;
        let mut pose = super::Pose::default();
        self.pose_at_clip_time(clip_t, &mut pose);
        // The head centre in model units (the pose world is the model's divided by the scale).
        let centre_model = Vec3::from(pose.head.translation) * self.fit.scale;
        let to_origin = Affine3A::from_translation(-centre_model);
        for node in &mut self.nodes {
            let local = node.local(clip_t);
            node.rest_matrix = Some(match node.parent {
                None => to_origin * local,
                Some(_) => local,
            });
            node.translation = None;
            node.rotation = None;
            node.scale = None;
        }
        self.duration_s = 0.0;
        self
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

    /// The world axis the model stood along in the file: +Y, or the axis it was turned from
    /// so that it stands Y-up (see `MotionOptions::keep_axes`).
    pub fn file_up(&self) -> Vec3 {
        self.file_up
    }

    /// Whether the head joint is the rig's topmost joint, found without a name.
    pub fn head_is_topmost(&self) -> bool {
        self.head_is_topmost
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
    pub fn fit_method(&self) -> FitMethod {
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
