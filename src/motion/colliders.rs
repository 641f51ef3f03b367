//! The body colliders of a load: the spheres asked for (or the default set below) and the
//! capsules fitted to the character's mesh (see `capsules.rs`), each on the evaluated chain of
//! the joint it follows.
//!
//! # Default spheres
//! When [`MotionOptions::body_spheres`] is `None` (and the file has no character whose
//! capsules replace them): spheres centred on the nearest
//! ancestors of the head named like "neck" ([`NECK_RADIUS_M`]) and "chest" / "torso" / "spine"
//! ([`CHEST_RADIUS_M`]), and on the topmost joints named like "shoulder" / "clavicle", at most
//! two ([`SHOULDER_RADIUS_M`]). Each radius is shrunk so that, at rest, the sphere stays outside
//! the fitted 0.09 m head sphere; below [`MIN_SPHERE_RADIUS_M`] it is dropped (on cartoon
//! proportions, such as RobotExpressive's, the chest sphere is dropped this way).
//!
//! # Capsules
//! A capsule is fitted at the rest pose in model space, around the vertices each bone
//! dominates, then stored in the bone's bind space (`(W_rest · B)⁻¹ · x`), so that at clip time
//! t it is carried by the same matrix as the vertices it was fitted to: `W(t) · B · x`. The
//! hairstyle's head ellipsoid (the head mesh's box, or the fitted 0.09 m head) is left to the
//! head collider: vertices deep inside it are not fitted (see `capsules.rs`).

use glam::{Affine3A, Quat, Vec3};

use super::capsules;
use super::chain::{CapsuleSpec, ChainSet};
use super::error::MotionError;
use super::fit::HAIRSTYLE_HEAD_RADIUS_M;
use super::joints::resolve_joint;
use super::options::{Fit, MotionOptions};
use super::skeleton::Skeleton;
use super::skin::{Character, dominant};

/// Default radii of the body colliders, in pose metres (adult proportions: neck ~0.10–0.12 m
/// across, upper chest ~0.25 m deep, deltoid ~0.12 m).
pub const NECK_RADIUS_M: f32 = 0.05;
/// See [`NECK_RADIUS_M`].
pub const CHEST_RADIUS_M: f32 = 0.12;
/// See [`NECK_RADIUS_M`].
pub const SHOULDER_RADIUS_M: f32 = 0.06;
/// A default collider is shrunk so that, at rest, it stays outside the fitted 0.09 m head
/// sphere; below this radius (metres) it is dropped.
pub const MIN_SPHERE_RADIUS_M: f32 = 0.01;

/// The body spheres `(joint, offset, radius)`, pose metres: those of `opts.body_spheres`
/// (checked and resolved), or without them the default set, which a character's capsules
/// replace.
pub(super) fn sphere_specs(
    opts: &MotionOptions,
    has_character: bool,
    skel: &Skeleton,
    head: usize,
    fit: &Fit,
    file: &str,
) -> Result<Vec<(usize, Vec3, f32)>, MotionError> {
    Ok(match &opts.body_spheres {
        None if has_character && opts.body_capsules => Vec::new(),
        None => default_spheres(skel, head, fit),
        Some(specs) => {
            let mut out = Vec::with_capacity(specs.len());
            for s in specs {
                if !(s.radius_m.is_finite() && s.radius_m > 0.0 && s.offset_m.is_finite()) {
                    return Err(MotionError::BadOption {
                        file: file.to_string(),
                        reason: format!("body sphere {s:?}: radius must be > 0, values finite"),
                    });
                }
                out.push((
                    resolve_joint(skel, &s.joint, file, "body sphere joint")?,
                    s.offset_m,
                    s.radius_m,
                ));
            }
            out
        }
    })
}

/// The capsules fitted to the character `ch` (see the module doc), their bones' chains added
/// to `chains`. `head_half_extents_m` is the head mesh's box (pose metres), if any.
pub(super) fn character_capsules(
    ch: &Character,
    skel: &Skeleton,
    head: usize,
    fit: &Fit,
    head_half_extents_m: Option<Vec3>,
    chains: &mut ChainSet,
) -> Vec<CapsuleSpec> {
    let head_ellipsoid = head_ellipsoid(skel, head, fit, head_half_extents_m);
    let bone_of: Vec<usize> = (0..ch.vertex_count())
        .map(|v| ch.joints[v][dominant(&ch.weights[v])] as usize)
        .collect();
    let bone_dir = bone_directions(ch, skel, fit);
    capsules::fit(
        &ch.rest_model,
        &bone_of,
        &ch.bone_in_head,
        &bone_dir,
        head_ellipsoid,
        capsules::HEAD_DEPTH_M * fit.scale,
        capsules::MIN_RADIUS_M * fit.scale,
    )
    .into_iter()
    .map(|c| {
        let bone = &ch.bones[c.bone];
        let to_bind = (skel.rest_world(bone.node) * bone.bind).inverse();
        CapsuleSpec {
            chain: chains.chain(bone.node),
            bind: bone.bind,
            a: to_bind.transform_point3(c.a),
            b: to_bind.transform_point3(c.b),
            radius_m: c.radius / fit.scale,
        }
    })
    .collect()
}

/// The head ellipsoid at rest in model space (the unit sphere mapped onto it): the head mesh's
/// box, or the fitted 0.09 m head.
fn head_ellipsoid(
    skel: &Skeleton,
    head: usize,
    fit: &Fit,
    head_half_extents_m: Option<Vec3>,
) -> Affine3A {
    let centre = Vec3::from(skel.rest_world(head).translation) + fit.offset_m;
    let radii = head_half_extents_m.map_or(Vec3::splat(HAIRSTYLE_HEAD_RADIUS_M), |h| h) * fit.scale;
    Affine3A::from_scale_rotation_translation(radii, Quat::IDENTITY, centre)
}

/// Each bone's direction at rest, model space: from its node to the mean of its children's,
/// zero for a bone without children or shorter than a millimetre at the fitted scale.
fn bone_directions(ch: &Character, skel: &Skeleton, fit: &Fit) -> Vec<Vec3> {
    let mut child_sum = vec![(Vec3::ZERO, 0u32); skel.names.len()];
    for (i, p) in skel.parents.iter().enumerate() {
        if let Some(p) = *p {
            child_sum[p].0 += Vec3::from(skel.rest_world(i).translation);
            child_sum[p].1 += 1;
        }
    }
    ch.bones
        .iter()
        .map(|b| {
            let (sum, n) = child_sum[b.node];
            if n == 0 {
                return Vec3::ZERO;
            }
            let d = sum / n as f32 - Vec3::from(skel.rest_world(b.node).translation);
            // Shorter than a millimetre at the fitted scale: no direction.
            if d.length() > 1e-3 * fit.scale {
                d
            } else {
                Vec3::ZERO
            }
        })
        .collect()
}

/// Default colliders `(joint, offset in pose metres, radius in pose metres)`: the nearest
/// ancestors of the head named like "neck" and like "chest" / "torso" / "spine", and the
/// topmost joints named like "shoulder" / "clavicle" (at most two), centred on the joints. Each
/// radius is shrunk to stay outside the fitted head sphere at rest (see
/// [`MIN_SPHERE_RADIUS_M`]).
fn default_spheres(skel: &Skeleton, head: usize, fit: &Fit) -> Vec<(usize, Vec3, f32)> {
    let lower: Vec<String> = skel.names.iter().map(|n| n.to_lowercase()).collect();
    let in_head = skel.subtree(head);
    let ancestors: Vec<usize> = skel.chain(head).into_iter().rev().skip(1).collect();
    let is_shoulder = |i: usize| lower[i].contains("shoulder") || lower[i].contains("clavicle");
    let neck = ancestors
        .iter()
        .copied()
        .find(|&i| lower[i].contains("neck"));
    let chest = ancestors.iter().copied().find(|&i| {
        Some(i) != neck
            && ["chest", "torso", "spine"]
                .iter()
                .any(|k| lower[i].contains(k))
    });
    let shoulders = (0..skel.names.len())
        .filter(|&i| skel.is_joint[i] && is_shoulder(i) && !in_head[i])
        .filter(|&i| !skel.parents[i].is_some_and(is_shoulder))
        .take(2);

    let head_center = (Vec3::from(skel.rest_world(head).translation) + fit.offset_m) / fit.scale;
    let mut out = Vec::new();
    let wanted = neck
        .map(|j| (j, NECK_RADIUS_M))
        .into_iter()
        .chain(chest.map(|j| (j, CHEST_RADIUS_M)))
        .chain(shoulders.map(|j| (j, SHOULDER_RADIUS_M)));
    for (joint, radius_m) in wanted {
        let center = Vec3::from(skel.rest_world(joint).translation) / fit.scale;
        let room_m = center.distance(head_center) - HAIRSTYLE_HEAD_RADIUS_M;
        let r = radius_m.min(room_m);
        if r >= MIN_SPHERE_RADIUS_M {
            out.push((joint, Vec3::ZERO, r));
        }
    }
    out
}
