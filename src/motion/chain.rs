//! The evaluated nodes of a motion: every node on a chain from a scene root to a joint whose
//! frame is sampled (the head, each body sphere's and capsule's joint, each bone of the
//! character), each once, parents first, with its rest transform and the clip's tracks.
//!
//! A joint's world matrix at clip time t is the product of its chain's local transforms, root
//! first: `W(t) = L₀(t) · L₁(t) ⋯ L_joint(t)`, each `L = T·R·S` from the node's tracks (or its
//! rest values where a property is not animated). Only these nodes are kept: about ten for a
//! humanoid rig's head and colliders, against hundreds of nodes in the file, so sampling needs
//! neither a hash map nor a pass over the whole hierarchy.

use glam::{Affine3A, Mat3A, Quat, Vec3, Vec3A, Vec4};

use super::clip::NodeTracks;
use super::sampler::Track;
use super::skeleton::{Skeleton, rest_trs};

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
    /// The node's local transform at clip time `t_s`: `T·R·S` from its tracks and rest values.
    pub(crate) fn local(&self, t_s: f32) -> Affine3A {
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

/// The evaluated nodes being gathered during a load: the union of the chains asked for, each
/// node once, in the order first asked for (so every parent comes before its children).
pub(crate) struct ChainSet<'a> {
    doc: &'a gltf::Document,
    skel: &'a Skeleton,
    /// The clip's tracks of the nodes not yet evaluated.
    tracks: NodeTracks,
    /// Index in `nodes` of each glTF node already evaluated.
    slot_of: Vec<Option<usize>>,
    nodes: Vec<ChainNode>,
    /// Turn of the whole model, put on every root node ([`super::up_axis`]).
    turn: Quat,
}

impl<'a> ChainSet<'a> {
    /// No node evaluated yet; `tracks` are the clip's tracks by glTF node.
    pub(crate) fn new(doc: &'a gltf::Document, skel: &'a Skeleton, tracks: NodeTracks) -> Self {
        Self {
            doc,
            skel,
            tracks,
            slot_of: vec![None; skel.names.len()],
            nodes: Vec::new(),
            turn: Quat::IDENTITY,
        }
    }

    /// Turns the whole model by `turn` (the same turn as the skeleton's,
    /// [`Skeleton::turn_world`]): root nodes evaluated from now on are premultiplied by it.
    pub(crate) fn turned(mut self, turn: Quat) -> Self {
        self.turn = turn;
        self
    }

    /// The chain of glTF node `joint`, evaluating the nodes on it that are not yet.
    pub(crate) fn chain(&mut self, joint: usize) -> JointChain {
        let chain = self.skel.chain(joint);
        let mut idx: Vec<usize> = Vec::with_capacity(chain.len());
        for &n in &chain {
            let parent = idx.last().copied();
            let slot = match self.slot_of[n] {
                Some(slot) => slot,
                None => {
                    let node = self.rest_node(n, parent);
                    self.nodes.push(node);
                    let slot = self.nodes.len() - 1;
                    self.slot_of[n] = Some(slot);
                    slot
                }
            };
            idx.push(slot);
        }
        JointChain {
            chain: idx,
            rest_align: rigid_rotation(&self.skel.rest_world(joint)).inverse(),
        }
    }

    /// Index in the evaluated nodes of glTF node `node` (evaluating its chain if needed).
    pub(crate) fn slot(&mut self, node: usize) -> usize {
        self.chain(node).chain.last().copied().unwrap_or(0)
    }

    /// The evaluated nodes, parents first.
    pub(crate) fn into_nodes(self) -> Vec<ChainNode> {
        self.nodes
    }

    /// glTF node `n` at rest with its tracks, under the evaluated node `parent`. A node given
    /// as a matrix keeps it unless a channel animates the node.
    fn rest_node(&mut self, n: usize, parent: Option<usize>) -> ChainNode {
        let [t, r, s] = self.tracks.remove(&n).unwrap_or_default();
        let nd = self.doc.nodes().nth(n);
        let (rt, rr, rs, m) = nd.as_ref().map_or(
            (Vec3::ZERO, Quat::IDENTITY, Vec3::ONE, Affine3A::IDENTITY),
            rest_trs,
        );
        let is_matrix =
            nd.is_some_and(|nd| matches!(nd.transform(), gltf::scene::Transform::Matrix { .. }));
        let animated = t.is_some() || r.is_some() || s.is_some();
        let node = ChainNode {
            parent,
            rest_matrix: (is_matrix && !animated).then_some(m),
            rest_t: rt,
            rest_r: rr,
            rest_s: rs,
            translation: t,
            rotation: r,
            scale: s,
        };
        if parent.is_none() && self.turn != Quat::IDENTITY {
            turn_root(node, self.turn)
        } else {
            node
        }
    }
}

/// A root node premultiplied by `turn`: `turn·(T·R·S) = (turn·t)·(turn·r)·S`, applied to the
/// rest values and to every key (both maps are linear, so they commute with interpolation).
fn turn_root(mut node: ChainNode, turn: Quat) -> ChainNode {
    node.rest_matrix = node.rest_matrix.map(|m| Affine3A::from_quat(turn) * m);
    node.rest_t = turn * node.rest_t;
    node.rest_r = turn * node.rest_r;
    if let Some(track) = &mut node.translation {
        track.map_values(|v| (turn * v.truncate()).extend(v.w));
    }
    if let Some(track) = &mut node.rotation {
        track.map_values(|v| Vec4::from(turn * Quat::from_vec4(v)));
    }
    node
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
