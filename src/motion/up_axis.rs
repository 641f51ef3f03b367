//! Which way the model stands, and the head of a rig whose joints have no names.
//!
//! glTF's world is +Y up, and most files keep to it: a Z-up tool's export carries a root node
//! that turns it Y-up. Some do not (converters that copy Z-up data as it is), and then the
//! character lies along +Z of the file's world while wisp's gravity pulls along −Y. The rest
//! pose tells: from the head's parent joint (the neck) to the head points up the spine. When it
//! points within [`SNAP_DEG`] of another world axis and at least [`KEEP_DEG`] away from +Y,
//! the whole model is turned (about the origin, by the shortest arc) so that axis becomes +Y
//! ([`standing_turn`]); a model leaning forward or a quadruped's neck (at most 65° from +Y in
//! practice) is left as the file has it. The loader applies the turn to the rest pose and to
//! the root nodes' tracks, so everything downstream sees a Y-up model.
//!
//! A rig with no joint named like "head" gets the **topmost joint** as its head
//! ([`topmost_head`]): the joint highest along the candidate up axis at rest, stepping from a
//! leaf end bone (`HeadTop_End`-like: no children) to its parent. The axis is +Y, or the first
//! of +Z, −Z, +X, −X, −Y whose topmost joint's neck-to-head direction agrees with it within
//! 45°: the head found and the way up confirm each other.

use glam::{Quat, Vec3};

use super::skeleton::Skeleton;

/// The neck-to-head direction must be at least this far from +Y for the model to be turned.
pub const KEEP_DEG: f32 = 65.0;
/// ...and within this of another world axis.
pub const SNAP_DEG: f32 = 25.0;

/// The axes a model may stand along, +Y (glTF's) first.
const AXES: [Vec3; 6] = [
    Vec3::Y,
    Vec3::Z,
    Vec3::NEG_Z,
    Vec3::X,
    Vec3::NEG_X,
    Vec3::NEG_Y,
];

/// Direction up the spine at the head joint at rest: from its parent joint to it, else from
/// it to its farthest descendant; `None` when neither is measurable.
fn spine_direction(skel: &Skeleton, head: usize) -> Option<Vec3> {
    let at = Vec3::from(skel.rest_world(head).translation);
    let from_parent = skel.parents[head].map(|p| at - Vec3::from(skel.rest_world(p).translation));
    let to_child = || {
        let inside = skel.subtree(head);
        (0..skel.names.len())
            .filter(|&i| i != head && inside[i])
            .map(|i| Vec3::from(skel.rest_world(i).translation) - at)
            .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
    };
    from_parent
        .filter(|d| d.length() > 1e-6 * at.length().max(1e-6))
        .or_else(to_child)
        .filter(|d| d.is_finite() && d.length_squared() > 0.0)
        .map(Vec3::normalize)
}

/// The turn that stands the model up (identity when it already does, or when the rest pose
/// does not tell): see the module doc. Returns the axis it stood along with it.
pub(crate) fn standing_turn(skel: &Skeleton, head: usize) -> (Quat, Vec3) {
    let Some(d) = spine_direction(skel, head) else {
        return (Quat::IDENTITY, Vec3::Y);
    };
    if d.angle_between(Vec3::Y) < KEEP_DEG.to_radians() {
        return (Quat::IDENTITY, Vec3::Y);
    }
    AXES[1..]
        .iter()
        .find(|a| d.angle_between(**a) < SNAP_DEG.to_radians())
        .map_or((Quat::IDENTITY, Vec3::Y), |&a| (turn_to_y(a), a))
}

/// The shortest-arc rotation taking `axis` to +Y (about X for −Y, so an upside-down model
/// faces as it did).
pub(crate) fn turn_to_y(axis: Vec3) -> Quat {
    if axis == Vec3::NEG_Y {
        Quat::from_rotation_x(std::f32::consts::PI)
    } else {
        Quat::from_rotation_arc(axis, Vec3::Y)
    }
}

/// The topmost joint along the first up axis it agrees with (see the module doc), `None`
/// for a file without joints.
pub(crate) fn topmost_head(skel: &Skeleton) -> Option<usize> {
    let joints: Vec<usize> = (0..skel.names.len())
        .filter(|&i| skel.is_joint[i])
        .collect();
    let mut first = None;
    for axis in AXES {
        let Some(head) = topmost_along(skel, &joints, axis) else {
            continue;
        };
        first.get_or_insert(head);
        if spine_direction(skel, head).is_some_and(|d| d.angle_between(axis) < 45f32.to_radians()) {
            return Some(head);
        }
    }
    first
}

/// The joint highest along `axis` at rest, or its parent when it is a leaf end bone; `None`
/// when no joint stands above another (a rig of one point says nothing of where the head is).
fn topmost_along(skel: &Skeleton, joints: &[usize], axis: Vec3) -> Option<usize> {
    let height = |i: usize| axis.dot(Vec3::from(skel.rest_world(i).translation));
    let finite = || joints.iter().copied().filter(|&i| height(i).is_finite());
    let top = finite().max_by(|&a, &b| height(a).total_cmp(&height(b)).then(b.cmp(&a)))?;
    let bottom = finite().map(height).fold(f32::INFINITY, f32::min);
    if height(top) <= bottom {
        return None;
    }
    let is_leaf = !skel.parents.contains(&Some(top));
    match skel.parents[top] {
        Some(p) if is_leaf && skel.is_joint[p] => Some(p),
        _ => Some(top),
    }
}
