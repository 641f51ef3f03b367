//! The node hierarchy of a glTF file at rest ([`Skeleton`]): parents, names, which nodes are
//! skin joints, every node's rest world matrix, a parent-first order. Built once per load and
//! read by the loader, the automatic fit and the character's skinning.

use glam::{Affine3A, Mat4, Quat, Vec3};

use super::error::{MotionError, invalid, short_list};

/// Node hierarchy of the file at rest (node default transforms). Acyclic (checked when built),
/// and every per-node quantity is computed once in O(nodes): a file may have a million nodes
/// in one chain, where walking each node's chain would cost a million squared.
pub(crate) struct Skeleton {
    pub(crate) names: Vec<String>,
    pub(crate) parents: Vec<Option<usize>>,
    /// Node is a joint of some skin (all true when the file has no skin).
    pub(crate) is_joint: Vec<bool>,
    /// World matrix of each node at rest.
    rest_world: Vec<Affine3A>,
    /// All nodes, every parent before its children.
    order: Vec<usize>,
}

impl Skeleton {
    /// Node indices from the root to `node` (inclusive).
    pub(crate) fn chain(&self, node: usize) -> Vec<usize> {
        let mut chain = vec![node];
        let mut at = node;
        while let Some(p) = self.parents[at] {
            chain.push(p);
            at = p;
        }
        chain.reverse();
        chain
    }

    /// World matrix of `node` at rest.
    pub(crate) fn rest_world(&self, node: usize) -> Affine3A {
        self.rest_world[node]
    }

    /// Turns the whole model by `turn` about the world origin: every rest world matrix is
    /// premultiplied (see [`super::up_axis`]).
    pub(crate) fn turn_world(&mut self, turn: Quat) {
        let m = Affine3A::from_quat(turn);
        for w in &mut self.rest_world {
            *w = m * *w;
        }
    }

    /// Which nodes are `root` or lie below it.
    pub(crate) fn subtree(&self, root: usize) -> Vec<bool> {
        let mut inside = vec![false; self.names.len()];
        for &i in &self.order {
            inside[i] = i == root || self.parents[i].is_some_and(|p| inside[p]);
        }
        inside
    }

    /// "index name" list of the joints, for error messages (the first few of a long list).
    pub(crate) fn joint_list(&self) -> String {
        let joints: Vec<String> = (0..self.names.len())
            .filter(|&i| self.is_joint[i])
            .map(|i| format!("{i} {}", self.names[i]))
            .collect();
        short_list(joints.into_iter(), ", ")
    }
}

/// All nodes of the forest given by `parents`, every parent before its children (sorted by
/// depth), or a node on a cycle. O(nodes): each node is walked once.
fn parent_first_order(parents: &[Option<usize>]) -> Result<Vec<usize>, usize> {
    let n = parents.len();
    let mut depth: Vec<Option<usize>> = vec![None; n];
    let mut on_path = vec![false; n];
    let mut path = Vec::new();
    for start in 0..n {
        // Walk up to a node of known depth or to a root...
        let mut at = start;
        while depth[at].is_none() {
            if on_path[at] {
                return Err(at);
            }
            on_path[at] = true;
            path.push(at);
            match parents[at] {
                Some(p) => at = p,
                None => break,
            }
        }
        // ...then give the walked nodes their depths, top down.
        while let Some(node) = path.pop() {
            on_path[node] = false;
            depth[node] = Some(parents[node].map_or(0, |p| depth[p].map_or(0, |d| d + 1)));
        }
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&i| depth[i]);
    Ok(order)
}

pub(crate) fn rest_trs(node: &gltf::Node) -> (Vec3, Quat, Vec3, Affine3A) {
    match node.transform() {
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            let (t, r, s) = (
                Vec3::from(translation),
                Quat::from_array(rotation).normalize(),
                Vec3::from(scale),
            );
            (t, r, s, Affine3A::from_scale_rotation_translation(s, r, t))
        }
        gltf::scene::Transform::Matrix { matrix } => {
            let m = Affine3A::from_mat4(Mat4::from_cols_array_2d(&matrix));
            let (s, r, t) = m.to_scale_rotation_translation();
            (t, r, s, m)
        }
    }
}

pub(crate) fn build_skeleton(doc: &gltf::Document, file: &str) -> Result<Skeleton, MotionError> {
    let n = doc.nodes().len();
    let mut parents = vec![None; n];
    for node in doc.nodes() {
        for child in node.children() {
            if parents[child.index()].is_some() {
                return Err(invalid(
                    file,
                    format!("node {} has two parents", child.index()),
                ));
            }
            parents[child.index()] = Some(node.index());
        }
    }
    let mut is_joint = vec![doc.skins().len() == 0; n];
    for skin in doc.skins() {
        for j in skin.joints() {
            is_joint[j.index()] = true;
        }
    }
    let names: Vec<String> = doc
        .nodes()
        .map(|nd| {
            nd.name()
                .map_or_else(|| format!("#{}", nd.index()), str::to_string)
        })
        .collect();
    let mut rest_local = Vec::with_capacity(n);
    for nd in doc.nodes() {
        let (t, r, s, m) = rest_trs(&nd);
        // A zero quaternion normalises to NaN, and JSON numbers beyond f32 arrive as inf.
        if !(t.is_finite() && r.is_finite() && s.is_finite() && m.is_finite()) {
            return Err(invalid(
                file,
                format!(
                    "node {} ({:?}): its rest transform is not finite (translation, scale and matrix must be finite numbers, rotation a non-zero quaternion)",
                    nd.index(),
                    names[nd.index()]
                ),
            ));
        }
        rest_local.push(m);
    }
    let order = parent_first_order(&parents).map_err(|node| {
        invalid(
            file,
            format!("the node hierarchy has a cycle through node {node}"),
        )
    })?;
    let mut rest_world = vec![Affine3A::IDENTITY; n];
    for &i in &order {
        rest_world[i] = parents[i].map_or(Affine3A::IDENTITY, |p| rest_world[p]) * rest_local[i];
    }
    Ok(Skeleton {
        names,
        parents,
        is_joint,
        rest_world,
        order,
    })
}
