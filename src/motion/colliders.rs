//! The body colliders of a load: the spheres asked for (or the default set, see [`fit`]) and the
//! capsules fitted to the character's mesh (see [`capsules`]), each on the evaluated chain of
//! the joint it follows.
//!
//! A capsule is fitted at the rest pose in model space, around the vertices each bone
//! dominates, then stored in the bone's bind space (`(W_rest · B)⁻¹ · x`), so that at clip time
//! t it is carried by the same matrix as the vertices it was fitted to: `W(t) · B · x`. The
//! hairstyle's head ellipsoid (the head mesh's box, or the fitted 0.09 m head) is left to the
//! head collider: vertices deep inside it are not fitted (see [`capsules`]).

use glam::{Affine3A, Quat, Vec3};

use super::chain::{CapsuleSpec, ChainSet};
use super::joints::resolve_joint;
use super::skeleton::Skeleton;
use super::skin::{Character, dominant};
use super::{Fit, HAIRSTYLE_HEAD_RADIUS_M, MotionError, MotionOptions, capsules, fit};

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
        None => fit::default_spheres(skel, head, fit),
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
