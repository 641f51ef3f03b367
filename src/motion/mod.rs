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

mod capsules;
pub mod dance;
pub mod fit;
mod gltf_io;
mod load;
pub mod sampler;
pub mod scalp;
mod skeleton;
pub mod skin;
pub mod texture;

pub use gltf_io::{MAX_BUFFER_BYTES, MAX_DECODED_VALUES, MAX_FILE_BYTES, MAX_JSON_CONTAINERS};
pub use scalp::RootsOnHead;
pub use skin::{Character, CharacterPose, Material};
pub use texture::Texture;

use std::path::Path;

use glam::{Affine3A, Mat3A, Quat, Vec3, Vec3A};

use sampler::Track;

/// Farthest a head or body collider may be from the world origin, pose metres. Positions are
/// f32: at 10 km their spacing is 1 mm, the collision margin, and beyond it the hair simulation
/// and the camera lose the hair (keyframes of 1e30 gave blank frames).
pub const MAX_POSE_DISTANCE_M: f32 = 10_000.0;

/// Most clip times [`Motion`] loading samples to check [`MAX_POSE_DISTANCE_M`].
const REACH_SAMPLES: usize = 10_000;

/// Head radius in metres that hairstyles are made for (the fit maps a head of this size onto
/// the model's head).
pub const HAIRSTYLE_HEAD_RADIUS_M: f32 = 0.09;

/// A body collision sphere in the pose world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre in the pose world, metres.
    pub center: Vec3,
    /// Radius in metres.
    pub radius_m: f32,
}

/// A body collision capsule in the pose world: the points within `radius_m` of the segment
/// from `a` to `b`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Capsule {
    /// Segment ends, pose metres.
    pub a: Vec3,
    pub b: Vec3,
    /// Radius in metres.
    pub radius_m: f32,
}

/// Where the head and the body colliders are at one instant.
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    /// Hairstyle head frame (metres, +Y up, +Z face, origin = head centre) -> pose world.
    /// Rigid: rotation and translation only.
    pub head: Affine3A,
    /// Body colliders in the pose world (metres).
    pub spheres: Vec<Sphere>,
    /// Body capsules fitted to the character's mesh, pose world (see [`MotionOptions`]).
    pub capsules: Vec<Capsule>,
}

impl Default for Pose {
    fn default() -> Self {
        Self {
            head: Affine3A::IDENTITY,
            spheres: Vec::new(),
            capsules: Vec::new(),
        }
    }
}

/// A node of the glTF file: by name (exact match first, then case-insensitive; skin joints
/// are preferred over other nodes with the same name) or by node index.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum JointRef {
    /// Node name.
    Name(String),
    /// Index into the glTF `nodes` array.
    Index(usize),
}

/// A body collision sphere hanging on a joint.
#[derive(Clone, Debug, PartialEq)]
pub struct SphereSpec {
    /// The joint the sphere follows.
    pub joint: JointRef,
    /// Centre offset in the joint frame (rest-pose-aligned axes, see the module doc), in pose
    /// metres (after the fit).
    pub offset_m: Vec3,
    /// Radius in pose metres (after the fit).
    pub radius_m: f32,
}

/// Maps the hairstyle's head frame into the head joint frame: `x_joint = scale·x_hair +
/// offset_m` (joint frame in model metres; see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// Model head size / hairstyle head size (dimensionless, > 0). 1 for a human-sized model.
    pub scale: f32,
    /// Head centre in the joint frame, model metres.
    pub offset_m: Vec3,
}

impl Fit {
    /// No scaling, head centre at the joint.
    pub const IDENTITY: Fit = Fit {
        scale: 1.0,
        offset_m: Vec3::ZERO,
    };
}

/// How to read a glTF motion.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionOptions {
    /// Clip name (exact, then case-insensitive). Default: "Dance" if present, else the first.
    pub clip: Option<String>,
    /// Head joint. Default: a skin joint (or any node if there is no skin) named "head"
    /// (case-insensitive), else the shortest name containing "head" and neither "end" nor
    /// "top".
    pub head_joint: Option<JointRef>,
    /// Hairstyle-to-joint fit. Default (`None`): automatic, see [`fit`].
    pub fit: Option<Fit>,
    /// Body colliders. `None` = a default set on joints named like neck, chest/torso/spine and
    /// shoulders when found (radii and rules in [`fit`]), but only for a file without meshes
    /// (a character's capsules replace them); `Some(vec![])` = none.
    pub body_spheres: Option<Vec<SphereSpec>>,
    /// Fit a collision capsule to each bone of the character's mesh (default true; see
    /// `capsules.rs`). Without a mesh there are none.
    pub body_capsules: bool,
    /// Load the character's meshes (default true). Without them the head ellipsoid and the
    /// body spheres are drawn, as for a file that has none.
    pub meshes: bool,
    /// Playback rate (1 = real time; negative plays backwards). Must be finite.
    pub speed: f32,
}

impl Default for MotionOptions {
    fn default() -> Self {
        Self {
            clip: None,
            head_joint: None,
            fit: None,
            body_spheres: None,
            body_capsules: true,
            meshes: true,
            speed: 1.0,
        }
    }
}

/// Why a motion could not be loaded. Every message names the file.
#[derive(Debug, thiserror::Error)]
pub enum MotionError {
    /// The file could not be read (missing, not a regular file, over
    /// [`MAX_FILE_BYTES`]).
    #[error("{file}: {error}")]
    Io {
        /// File name.
        file: String,
        /// What went wrong.
        error: crate::input::ReadError,
    },
    /// Not glTF at all (neither the GLB magic nor JSON).
    #[error("{file}: not a glTF 2.0 file: {reason}")]
    NotGltf {
        /// File name.
        file: String,
        /// What was found.
        reason: String,
    },
    /// A .glb shorter than its header or chunks say.
    #[error("{file}: truncated .glb: {reason}")]
    Truncated {
        /// File name.
        file: String,
        /// What is missing.
        reason: String,
    },
    /// glTF that breaks the specification or uses something unsupported.
    #[error("{file}: invalid glTF: {reason}")]
    Invalid {
        /// File name.
        file: String,
        /// What is wrong.
        reason: String,
    },
    /// A buffer could not be resolved (unsupported URI, missing file, bad base64).
    #[error("{file}: buffer {index}: {reason}")]
    Buffer {
        /// File name.
        file: String,
        /// Buffer index.
        index: usize,
        /// What is wrong.
        reason: String,
    },
    /// The file has no animation clip.
    #[error("{file}: the glTF has no animations (a motion needs at least one clip)")]
    NoAnimations {
        /// File name.
        file: String,
    },
    /// The requested clip does not exist.
    #[error("{file}: no clip named {requested:?}; clips: {}", gltf_io::short_list(available.iter().cloned(), ", "))]
    UnknownClip {
        /// File name.
        file: String,
        /// Requested name.
        requested: String,
        /// Names of the clips in the file (unnamed ones as `#index`).
        available: Vec<String>,
    },
    /// A requested joint (head or body sphere) does not exist, or no head joint was found.
    #[error("{file}: {role}: no joint {requested}; joints (index name): {available}")]
    UnknownJoint {
        /// File name.
        file: String,
        /// Which joint was asked for ("head joint", "body sphere joint").
        role: String,
        /// What was asked for (a quoted name, an index, or "named like \"head\"").
        requested: String,
        /// The joints, as "index name" pairs separated by commas.
        available: String,
    },
    /// A clip's tracks are malformed (key counts, non-increasing times, non-finite values).
    #[error("{file}: clip {clip:?}: {reason}")]
    BadClip {
        /// File name.
        file: String,
        /// Clip name.
        clip: String,
        /// What is wrong.
        reason: String,
    },
    /// An option is out of range (speed not finite, fit scale not positive, ...).
    #[error("{file}: invalid option: {reason}")]
    BadOption {
        /// File name.
        file: String,
        /// What is wrong.
        reason: String,
    },
}

/// Rest transform of one node on an evaluated chain, with the clip's tracks for it.
#[derive(Clone, Debug)]
pub(crate) struct ChainNode {
    /// Index of the parent node in `Motion::nodes` (always smaller: nodes are stored parent
    /// first), `None` for a root.
    pub(crate) parent: Option<usize>,
    /// Rest local transform when the node has a matrix that no channel overrides.
    pub(crate) rest_matrix: Option<Affine3A>,
    pub(crate) rest_t: Vec3,
    pub(crate) rest_r: Quat,
    pub(crate) rest_s: Vec3,
    pub(crate) translation: Option<Track>,
    pub(crate) rotation: Option<Track>,
    pub(crate) scale: Option<Track>,
}

impl ChainNode {
    fn local(&self, t_s: f32) -> Affine3A {
        if let Some(m) = self.rest_matrix {
            return m;
        }
        let t = self
            .translation
            .as_ref()
            .map_or(self.rest_t, |k| k.sample_vec3(t_s));
        let r = self
            .rotation
            .as_ref()
            .map_or(self.rest_r, |k| k.sample_quat(t_s));
        let s = self
            .scale
            .as_ref()
            .map_or(self.rest_s, |k| k.sample_vec3(t_s));
        Affine3A::from_scale_rotation_translation(s, r, t)
    }
}

/// A capsule collider on a bone (see `Motion::capsules`).
#[derive(Clone, Debug)]
pub(crate) struct CapsuleSpec {
    pub(crate) chain: JointChain,
    pub(crate) bind: Affine3A,
    pub(crate) a: Vec3,
    pub(crate) b: Vec3,
    pub(crate) radius_m: f32,
}

/// A joint whose frame is evaluated: its root-to-joint chain and the rest-pose alignment.
#[derive(Clone, Debug)]
pub(crate) struct JointChain {
    /// Indices into `Motion::nodes`, root first, the joint last.
    pub(crate) chain: Vec<usize>,
    /// Inverse of the joint's world rotation at rest: joint frame axes = rest world axes.
    pub(crate) rest_align: Quat,
}

/// A clip ready to be sampled. See the module doc.
#[derive(Clone, Debug)]
pub struct Motion {
    pub(crate) clip_name: String,
    pub(crate) start_s: f32,
    pub(crate) duration_s: f32,
    pub(crate) speed: f32,
    pub(crate) fit: Fit,
    pub(crate) fit_method: fit::FitMethod,
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
}

impl Motion {
    /// Loads a glTF 2.0 motion from a `.glb` or `.gltf` file (recognised by content). Relative
    /// buffer URIs are resolved next to the file; `data:` base64 URIs are decoded.
    pub fn load(path: &Path, opts: &MotionOptions) -> Result<Motion, MotionError> {
        let name = path.display().to_string();
        let bytes =
            crate::input::read_capped(path, MAX_FILE_BYTES, "a glTF file").map_err(|error| {
                MotionError::Io {
                    file: name.clone(),
                    error,
                }
            })?;
        load::from_bytes(&bytes, &name, path.parent(), opts)
    }

    /// Loads a motion from the bytes of a `.glb` (or a self-contained `.gltf` whose buffers
    /// are `data:` URIs). `name_for_errors` is the file name used in error messages.
    pub fn from_glb_bytes(
        bytes: &[u8],
        name_for_errors: &str,
        opts: &MotionOptions,
    ) -> Result<Motion, MotionError> {
        load::from_bytes(bytes, name_for_errors, None, opts)
    }

    /// The project's own dance (`animations/dance.glb`, made by `examples/make_dance.rs`), with
    /// default options: a human-sized rig, so the automatic fit is scale 1.
    pub fn default_dance() -> Motion {
        dance::default_dance()
    }

    /// A motionless pose: `head` at all times, no body spheres, duration 0.
    pub fn still(head: Affine3A) -> Motion {
        Motion {
            clip_name: "still".to_string(),
            start_s: 0.0,
            duration_s: 0.0,
            speed: 1.0,
            fit: Fit::IDENTITY,
            fit_method: fit::FitMethod::Given,
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
        }
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

    /// The character's meshes (bind space), if the motion has any.
    pub fn character(&self) -> Option<&Character> {
        self.character.as_ref()
    }

    /// Half extents of the head mesh's bounding box in the head joint frame (rest-pose world
    /// axes), pose metres; `None` when the file has no head mesh.
    pub fn head_half_extents_m(&self) -> Option<Vec3> {
        self.head_half_extents_m
    }

    /// Poses the character at wall time `t_s` (looped) into `out`: positions and normals in
    /// the pose world. Allocation-free once `out` has held this character. Does nothing
    /// without a character.
    pub fn pose_character(&self, t_s: f32, out: &mut CharacterPose) {
        let Some(ch) = &self.character else {
            return;
        };
        let clip_t = self.clip_time_s(t_s);
        out.node_worlds.clear();
        for node in &self.nodes {
            let local = node.local(clip_t);
            let world = match node.parent {
                Some(p) => out.node_worlds[p] * local,
                None => local,
            };
            out.node_worlds.push(world);
        }
        let to_pose = Affine3A::from_scale(Vec3::splat(1.0 / self.fit.scale));
        out.bone_mats.clear();
        out.bone_mats.extend(
            ch.bones
                .iter()
                .map(|b| to_pose * out.node_worlds[b.slot] * b.bind),
        );
        ch.skin(out);
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
    pub fn fit_method(&self) -> fit::FitMethod {
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

    /// Clip time (seconds, within the key range) played at wall time `t_s`.
    pub fn clip_time_s(&self, t_s: f32) -> f32 {
        let t = t_s * self.speed;
        if self.duration_s > 0.0 && t.is_finite() {
            self.start_s + t.rem_euclid(self.duration_s).min(self.duration_s)
        } else {
            self.start_s
        }
    }

    /// The pose at wall time `t_s` (looped).
    pub fn sample(&self, t_s: f32) -> Pose {
        let mut pose = Pose {
            head: Affine3A::IDENTITY,
            spheres: Vec::with_capacity(self.spheres.len()),
            capsules: Vec::with_capacity(self.capsules.len()),
        };
        self.sample_into(t_s, &mut pose);
        pose
    }

    /// The pose at wall time `t_s` (looped), written into `pose` without allocating once
    /// `pose.spheres` has the capacity.
    pub fn sample_into(&self, t_s: f32, pose: &mut Pose) {
        self.pose_at_clip_time(self.clip_time_s(t_s), pose);
    }

    /// The pose at clip time `clip_t` (seconds within the key range).
    fn pose_at_clip_time(&self, clip_t: f32, pose: &mut Pose) {
        let inv_scale = 1.0 / self.fit.scale;
        let (rot, origin) = self.joint_frame(&self.head, clip_t);
        let center_model = origin + rot * Vec3A::from(self.fit.offset_m);
        pose.head = Affine3A {
            matrix3: Mat3A::from_quat(rot),
            translation: center_model * inv_scale,
        };
        pose.spheres.clear();
        for (joint, offset_m, radius_m) in &self.spheres {
            let (rot, origin) = self.joint_frame(joint, clip_t);
            let center = origin * inv_scale + rot * Vec3A::from(*offset_m);
            pose.spheres.push(Sphere {
                center: center.into(),
                radius_m: *radius_m,
            });
        }
        pose.capsules.clear();
        for c in &self.capsules {
            let m = self.world(&c.chain, clip_t) * c.bind;
            pose.capsules.push(Capsule {
                a: m.transform_point3(c.a) * inv_scale,
                b: m.transform_point3(c.b) * inv_scale,
                radius_m: c.radius_m,
            });
        }
    }

    /// Checks that the head and the colliders stay finite and within [`MAX_POSE_DISTANCE_M`]
    /// of the origin over the clip: at every key time of the evaluated nodes and at uniform
    /// times between (at most [`REACH_SAMPLES`] poses in all).
    pub(crate) fn check_reach(&self) -> Result<(), String> {
        let mut times: Vec<f32> = self
            .nodes
            .iter()
            .flat_map(|n| [&n.translation, &n.rotation, &n.scale])
            .flatten()
            .flat_map(|t| t.times_s().iter().copied())
            .collect();
        let uniform = 1000;
        if times.len() > REACH_SAMPLES - uniform - 1 {
            let stride = times.len().div_ceil(REACH_SAMPLES - uniform - 1);
            times = times.into_iter().step_by(stride).collect();
        }
        times.extend(
            (0..=uniform).map(|i| self.start_s + self.duration_s * (i as f32 / uniform as f32)),
        );
        let mut pose = Pose::default();
        for clip_t in times {
            self.pose_at_clip_time(clip_t, &mut pose);
            let head = Vec3::from(pose.head.translation);
            let far = |p: Vec3| !(p.is_finite() && p.length() <= MAX_POSE_DISTANCE_M);
            if far(head) || !pose.head.matrix3.is_finite() {
                return Err(format!(
                    "at clip time {clip_t} s the head is at {head} (pose metres, after the fit); \
                     it must stay finite and within {MAX_POSE_DISTANCE_M} m of the origin, where \
                     f32 positions still resolve the 1 mm collision margin"
                ));
            }
            if let Some(c) = pose.capsules.iter().find(|c| far(c.a) || far(c.b)) {
                return Err(format!(
                    "at clip time {clip_t} s a body capsule reaches {} (pose metres, after the \
                     fit); colliders must stay finite and within {MAX_POSE_DISTANCE_M} m of \
                     the origin",
                    if far(c.a) { c.a } else { c.b }
                ));
            }
            if let Some(s) = pose
                .spheres
                .iter()
                .find(|s| far(s.center) || !s.radius_m.is_finite())
            {
                return Err(format!(
                    "at clip time {clip_t} s a body collider is at {} (pose metres, after the \
                     fit); colliders must stay finite and within {MAX_POSE_DISTANCE_M} m of \
                     the origin",
                    s.center
                ));
            }
        }
        Ok(())
    }

    /// World matrix of a joint at clip time (model units, including node scales).
    fn world(&self, joint: &JointChain, clip_t: f32) -> Affine3A {
        let mut m = Affine3A::IDENTITY;
        for &i in &joint.chain {
            m *= self.nodes[i].local(clip_t);
        }
        m
    }

    /// Rigid joint frame at clip time: rotation (rest-aligned) and origin (model metres).
    fn joint_frame(&self, joint: &JointChain, clip_t: f32) -> (Quat, Vec3A) {
        let m = self.world(joint, clip_t);
        (rigid_rotation(&m) * joint.rest_align, m.translation)
    }
}

/// Rotation part of an affine map with its scale (and any shear) removed: the columns are
/// normalised and re-orthogonalised (Gram–Schmidt, X then Y; Z = X × Y keeps det = +1 even
/// when a node mirrors the model).
pub(crate) fn rigid_rotation(m: &Affine3A) -> Quat {
    let x = m.matrix3.x_axis.normalize_or(Vec3A::X);
    let y0 = m.matrix3.y_axis - x * x.dot(m.matrix3.y_axis);
    let y = y0.normalize_or(x.any_orthonormal_vector());
    let z = x.cross(y);
    Quat::from_mat3a(&Mat3A::from_cols(x, y, z)).normalize()
}
