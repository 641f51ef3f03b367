//! How a glTF motion is read: which clip and head joint, how the hairstyle's head is fitted
//! onto the joint, which body colliders follow the character, and the playback rate. Every
//! field has a default that plays the file's "Dance" clip (or its first) on a joint named like
//! "head", with an automatic fit and colliders fitted to the character's mesh.

use glam::Vec3;

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
    /// "top", else the topmost joint (see [`up_axis`](super::up_axis)).
    pub head_joint: Option<JointRef>,
    /// Hairstyle-to-joint fit. Default (`None`): automatic, see [`fit`](super::fit).
    pub fit: Option<Fit>,
    /// Body colliders. `None` = a default set on joints named like neck, chest/torso/spine and
    /// shoulders when found (radii and rules in [`colliders`](super::colliders)), but only for
    /// a file without meshes (a character's capsules replace them); `Some(vec![])` = none.
    pub body_spheres: Option<Vec<SphereSpec>>,
    /// Fit a collision capsule to each bone of the character's mesh (default true; see
    /// `capsules.rs`). Without a mesh there are none.
    pub body_capsules: bool,
    /// Load the character's meshes (default true). Without them the head ellipsoid and the
    /// body spheres are drawn, as for a file that has none.
    pub meshes: bool,
    /// Playback rate (1 = real time; negative plays backwards). Must be finite.
    pub speed: f32,
    /// Keep the file's axes even when its model lies along another axis than +Y (default
    /// false: such a model is turned upright, see [`up_axis`](super::up_axis)).
    pub keep_axes: bool,
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
            keep_axes: false,
        }
    }
}
