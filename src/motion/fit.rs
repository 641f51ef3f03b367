//! Automatic fit of a 0.09 m hairstyle head onto the model's head joint.
//!
//! # The head-size estimate (in order of preference)
//! 1. **Mesh bounds** ([`FitMethod::MeshBounds`]): at the rest pose, gather the vertices that
//!    belong to the head: meshes on nodes in the head joint's subtree (rigidly attached heads,
//!    as in RobotExpressive), and skinned vertices whose largest weight is on a joint in that
//!    subtree (skinned with `Σ wᵢ·Jᵢ·IBMᵢ·v / Σ wᵢ`, since real files have weights that do not
//!    sum to 1). Their bounding box, in the joint frame (rest world axes, origin at the joint),
//!    gives the centre (`offset_m`) and the radius as the geometric mean of the half-extents
//!    (a human head's [0.075, 0.10, 0.095] m gives 0.089 m, the 0.09 m hairstyles are made
//!    for). `scale = radius / 0.09`.
//! 2. **Head child** ([`FitMethod::HeadChild`]): no head mesh, but the head joint has
//!    descendants (a `Head_end` / `HeadTop_End` bone at the top of the skull): the farthest one
//!    at distance d gives radius d/2 and the centre half-way.
//! 3. **Neck length** ([`FitMethod::NeckLength`]): only a parent: radius = 0.9·|head − parent|
//!    (adult: head joint ~0.10 m above the neck joint, head radius ~0.09 m), centre that far
//!    above the joint.
//! 4. Otherwise identity ([`FitMethod::Default`]).
//!
//! Meshes that cannot be read (sparse accessors, missing attributes) are skipped: the fit is a
//! best effort and must not make an otherwise playable clip fail.

use glam::{Affine3A, Mat4, Vec3};
use gltf::Semantic;

use super::gltf_io::{Loaded, read_accessor};
use super::options::Fit;
use super::skeleton::Skeleton;

/// Head radius in metres that hairstyles are made for (the fit maps a head of this size onto
/// the model's head).
pub const HAIRSTYLE_HEAD_RADIUS_M: f32 = 0.09;

/// Where a [`Fit`] came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FitMethod {
    /// Given in [`super::MotionOptions::fit`].
    Given,
    /// Bounding box of this many head vertices.
    MeshBounds {
        /// Vertices used.
        vertices: usize,
    },
    /// Distance to the head joint's farthest descendant node.
    HeadChild,
    /// Distance to the head joint's parent.
    NeckLength,
    /// Nothing to measure: identity.
    Default,
}

/// Estimates the fit (see the module doc).
pub(crate) fn estimate(loaded: &Loaded, skel: &Skeleton, head: usize) -> (Fit, FitMethod) {
    let in_head = skel.subtree(head);
    let verts = head_vertices(loaded, skel, &in_head);
    if verts.len() >= 4 {
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for v in &verts {
            lo = lo.min(*v);
            hi = hi.max(*v);
        }
        return from_box(lo, hi, verts.len(), skel, head);
    }
    estimate_without_mesh(skel, head)
}

/// The fit from the head mesh's rest-pose bounding box `lo`–`hi` (model metres, world axes)
/// of `vertices` vertices ([`FitMethod::MeshBounds`]), or from the skeleton when the box is
/// degenerate.
pub(crate) fn from_box(
    lo: Vec3,
    hi: Vec3,
    vertices: usize,
    skel: &Skeleton,
    head: usize,
) -> (Fit, FitMethod) {
    let origin = skel.rest_world(head).translation;
    let half = (hi - lo) * 0.5;
    let radius = if half.min_element() > 1e-6 * half.max_element() {
        (half.x * half.y * half.z).cbrt()
    } else {
        (half.x + half.y + half.z) / 3.0
    };
    if radius.is_finite() && radius > 0.0 {
        let fit = Fit {
            scale: radius / HAIRSTYLE_HEAD_RADIUS_M,
            offset_m: (lo + hi) * 0.5 - Vec3::from(origin),
        };
        return (fit, FitMethod::MeshBounds { vertices });
    }
    estimate_without_mesh(skel, head)
}

/// The fit from the skeleton alone: head child, neck length, or identity.
pub(crate) fn estimate_without_mesh(skel: &Skeleton, head: usize) -> (Fit, FitMethod) {
    let origin = skel.rest_world(head).translation;
    let in_head = skel.subtree(head);
    let farthest = (0..skel.names.len())
        .filter(|&i| i != head && in_head[i])
        .map(|i| Vec3::from(skel.rest_world(i).translation - origin))
        .max_by(|a, b| a.length().total_cmp(&b.length()));
    if let Some(d) = farthest.filter(|d| d.length() > 1e-6) {
        let fit = Fit {
            scale: 0.5 * d.length() / HAIRSTYLE_HEAD_RADIUS_M,
            offset_m: 0.5 * d,
        };
        return (fit, FitMethod::HeadChild);
    }
    if let Some(p) = skel.parents[head] {
        let len = (skel.rest_world(p).translation - origin).length();
        if len > 1e-6 && len.is_finite() {
            let radius = 0.9 * len;
            let fit = Fit {
                scale: radius / HAIRSTYLE_HEAD_RADIUS_M,
                offset_m: Vec3::new(0.0, radius, 0.0),
            };
            return (fit, FitMethod::NeckLength);
        }
    }
    (Fit::IDENTITY, FitMethod::Default)
}

/// Rest-pose world positions of the head's vertices (see the module doc); `in_head` marks
/// the head joint's subtree.
fn head_vertices(loaded: &Loaded, skel: &Skeleton, in_head: &[bool]) -> Vec<Vec3> {
    // Each skin's use, worked out on first use; `Some(None)` for a skin without head joints.
    let mut skins: Vec<Option<Option<SkinUse>>> =
        (0..loaded.doc.skins().len()).map(|_| None).collect();
    let mut out = Vec::new();
    for node in loaded.doc.nodes() {
        let Some(mesh) = node.mesh() else { continue };
        if let Some(skin) = node.skin() {
            let entry = skins[skin.index()]
                .get_or_insert_with(|| SkinUse::new(&skin, loaded, skel, in_head));
            if let Some(skin_use) = entry.as_ref() {
                skinned_head_vertices(&mesh, skin_use, loaded, &mut out);
            }
        } else if in_head[node.index()] {
            let m = skel.rest_world(node.index());
            for prim in mesh.primitives() {
                if let Some((pos, 3)) = prim
                    .get(&Semantic::Positions)
                    .and_then(|a| read_accessor(&a, loaded).ok())
                {
                    out.extend(
                        pos.chunks_exact(3)
                            .map(|p| m.transform_point3(Vec3::new(p[0], p[1], p[2])))
                            .filter(|p| p.is_finite()),
                    );
                }
            }
        }
    }
    out
}

/// What a skin contributes, worked out once per skin (a file may point a million nodes at
/// one skin of a million joints).
struct SkinUse {
    /// Per joint of the skin: in the head's subtree.
    in_head: Vec<bool>,
    /// Per joint: rest world matrix × inverse bind matrix.
    mats: Vec<Affine3A>,
}

impl SkinUse {
    /// The skin's joints' rest skinning matrices, `None` when no joint is in the head (its
    /// meshes have no head vertex). Unreadable inverse bind matrices count as identity.
    fn new(skin: &gltf::Skin, loaded: &Loaded, skel: &Skeleton, in_head: &[bool]) -> Option<Self> {
        let joints: Vec<usize> = skin.joints().map(|j| j.index()).collect();
        let in_head: Vec<bool> = joints.iter().map(|&j| in_head[j]).collect();
        if !in_head.contains(&true) {
            return None;
        }
        let ibm: Vec<Affine3A> = skin
            .inverse_bind_matrices()
            .and_then(|a| read_accessor(&a, loaded).ok())
            .filter(|(v, c)| *c == 16 && v.len() == 16 * joints.len())
            .map(|(v, _)| {
                v.chunks_exact(16)
                    .map(|m| Affine3A::from_mat4(Mat4::from_cols_slice(m)))
                    .collect()
            })
            .unwrap_or_else(|| vec![Affine3A::IDENTITY; joints.len()]);
        let mats = joints
            .iter()
            .zip(&ibm)
            .map(|(&j, b)| skel.rest_world(j) * *b)
            .collect();
        Some(SkinUse { in_head, mats })
    }
}

/// Appends to `out` the rest positions of `mesh`'s skinned vertices whose largest weight is on
/// a head joint of `skin` (`Σ wᵢ·Mᵢ·v / Σ wᵢ`); primitives without positions, joints and
/// weights are skipped.
fn skinned_head_vertices(mesh: &gltf::Mesh, skin: &SkinUse, loaded: &Loaded, out: &mut Vec<Vec3>) {
    let SkinUse { in_head, mats } = skin;
    for prim in mesh.primitives() {
        let read = |s: Semantic| prim.get(&s).and_then(|a| read_accessor(&a, loaded).ok());
        let (Some((pos, 3)), Some((jnt, 4)), Some((wgt, 4))) = (
            read(Semantic::Positions),
            read(Semantic::Joints(0)),
            read(Semantic::Weights(0)),
        ) else {
            continue;
        };
        for ((p, j), w) in pos
            .chunks_exact(3)
            .zip(jnt.chunks_exact(4))
            .zip(wgt.chunks_exact(4))
        {
            let v = Vec3::new(p[0], p[1], p[2]);
            let dominant = (0..4).max_by(|&a, &b| w[a].total_cmp(&w[b])).unwrap_or(0);
            if !in_head.get(j[dominant] as usize).copied().unwrap_or(false) {
                continue;
            }
            let (mut acc, mut total) = (Vec3::ZERO, 0.0);
            for k in 0..4 {
                if let Some(m) = mats.get(j[k] as usize).filter(|_| w[k] > 0.0) {
                    acc += w[k] * m.transform_point3(v);
                    total += w[k];
                }
            }
            if total > 0.0 && acc.is_finite() {
                out.push(acc / total);
            }
        }
    }
}
