//! Body colliders fitted to a character's mesh: capsules per bone, around the rest-pose
//! vertices that bone dominates.
//!
//! # How
//! For every bone outside the head (the head is the hairstyle's ellipsoid), the vertices whose
//! largest skin weight is on it are gathered at the rest pose, less those more than
//! [`HEAD_DEPTH_M`] inside the head ellipsoid (a collar or neck tube reaching up into the
//! skull, hidden there, must not put a collider under the scalp's roots; the part of a neck
//! just under the skull stays, or hair at the nape would sink into it). Their covariance gives three
//! principal axes with extents E₁ ≥ E₂ ≥ E₃ (eigenvectors by power iteration and deflation).
//!
//! - The capsules' direction is the principal axis nearest the bone's own direction (from the
//!   joint to its children, when it has any: an arm along the arm, a chest upward toward the
//!   neck and shoulders), else the first.
//! - Across it, the bone's vertices are cut into n slabs along the wider of the two other
//!   axes, n = round(2·E_wide / E_thin) clamped to [1, [`MAX_PER_BONE`]], or 1 when
//!   E_wide / E_thin < [`ROUND_ASPECT`]: one capsule for a round limb (two half-disc slabs
//!   would each bulge 8% past it), several side by side for a chest or a pelvis, whose
//!   cross-section is twice as wide as deep (each slab about half as wide as it is deep, so
//!   its capsule reaches the slab's corners with little to spare). A single capsule around a chest would be as thick as the chest is wide (the
//!   back 6 cm behind the real one); side by side, each is about as thick as the chest is deep.
//! - Each slab's capsule runs along the direction through the slab's centroid; its radius is
//!   the largest distance of a slab vertex from that line, and each end of the segment then
//!   moves out just far enough that every slab vertex lies within the radius of the segment
//!   (for a vertex at axial position t and distance d from the line, the end must reach
//!   t ∓ √(r² − d²)).
//!
//! Every capsule therefore contains every vertex it was fitted to: hair kept outside the
//! capsules is outside those vertices (up to the facets between them). The price is a bulge
//! where a slab's round capsule covers a flatter surface: on the mannequin's back about 1 cm
//! at the middle of a slab; on boxy parts more (a box's capsule reaches its corners).
//! Bones with fewer than [`MIN_VERTICES`] vertices are skipped (fingers, a stray vertex).
//!
//! Why capsules: a sphere per bone leaves gaps along limbs or bulges around them, and a capsule
//! costs one segment projection more than a sphere in the simulation's inner loop.

use glam::{Affine3A, Mat3, Vec3};

/// Fewest vertices a bone (or a slab of one) needs to get a capsule.
pub const MIN_VERTICES: usize = 8;
/// Most capsules side by side for one bone.
pub const MAX_PER_BONE: usize = 6;
/// Cross-sections less elongated than this (wide over thin extent) are round: one capsule,
/// which bulges by at most an eighth of the thin extent on either side.
pub const ROUND_ASPECT: f32 = 1.25;
/// Vertices deeper than this inside the head ellipsoid are left out of the fit, pose metres.
pub const HEAD_DEPTH_M: f32 = 0.01;
/// Thinnest capsule kept, pose metres.
pub const MIN_RADIUS_M: f32 = 0.005;

/// A fitted capsule in model rest space: the bone it follows, segment ends, radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FittedCapsule {
    pub(crate) bone: usize,
    pub(crate) a: Vec3,
    pub(crate) b: Vec3,
    pub(crate) radius: f32,
}

/// Capsules around the rest-pose `points` grouped by `bone_of_point` (see the module doc),
/// skipping bones marked in `skip`. `bone_dir[b]` is bone b's direction at rest (zero when it
/// has none); `head` maps the unit sphere to the head ellipsoid at rest (model space), and
/// points deeper than `depth` inside it (model units, measured along its shortest axis) are
/// left out. Capsules thinner than `min_radius` are dropped.
pub(crate) fn fit(
    points: &[Vec3],
    bone_of_point: &[usize],
    skip: &[bool],
    bone_dir: &[Vec3],
    head: Affine3A,
    depth: f32,
    min_radius: f32,
) -> Vec<FittedCapsule> {
    let groups = group_by_bone(points, bone_of_point, skip, head, depth);
    let mut out = Vec::new();
    for (bone, pts) in groups.iter().enumerate() {
        if pts.len() < MIN_VERTICES {
            continue;
        }
        let dir = bone_dir.get(bone).copied().unwrap_or(Vec3::ZERO);
        bone_capsules(bone, pts, dir, min_radius, &mut out);
    }
    out
}

/// The points of each of the `skip.len()` bones, less those of skipped bones and those deeper
/// than `depth` inside the head ellipsoid `head` (see [`fit`]).
fn group_by_bone(
    points: &[Vec3],
    bone_of_point: &[usize],
    skip: &[bool],
    head: Affine3A,
    depth: f32,
) -> Vec<Vec<Vec3>> {
    let bones = skip.len();
    let to_head = head.inverse();
    let shortest = head
        .matrix3
        .x_axis
        .length()
        .min(head.matrix3.y_axis.length())
        .min(head.matrix3.z_axis.length());
    let inside = if shortest > 0.0 {
        1.0 - depth / shortest
    } else {
        1.0
    };
    let mut groups: Vec<Vec<Vec3>> = vec![Vec::new(); bones];
    for (p, &b) in points.iter().zip(bone_of_point) {
        let near_head = to_head.transform_point3(*p).length() < inside;
        if b < bones && !skip[b] && !near_head {
            groups[b].push(*p);
        }
    }
    groups
}

/// Appends to `out` the capsules of one bone's points `pts`: along the principal axis nearest
/// the bone's direction `d`, side by side in slabs across the wider other axis (module doc).
fn bone_capsules(
    bone: usize,
    pts: &[Vec3],
    d: Vec3,
    min_radius: f32,
    out: &mut Vec<FittedCapsule>,
) {
    let Some(axes) = principal_axes(pts) else {
        return;
    };
    // Direction: the principal axis nearest the bone's own.
    let along = if d.length_squared() > 0.0 {
        (0..3)
            .max_by(|&i, &j| axes[i].0.dot(d).abs().total_cmp(&axes[j].0.dot(d).abs()))
            .unwrap_or(0)
    } else {
        0
    };
    let (axis, _) = axes[along];
    let mut others = [0usize, 1, 2].into_iter().filter(|&i| i != along);
    let (i, j) = (others.next().unwrap_or(1), others.next().unwrap_or(2));
    let ((wide, e_wide), (_, e_thin)) = if axes[i].1 >= axes[j].1 {
        (axes[i], axes[j])
    } else {
        (axes[j], axes[i])
    };
    let aspect = if e_thin > 0.0 { e_wide / e_thin } else { 0.0 };
    let n = if aspect >= ROUND_ASPECT {
        ((2.0 * aspect).round() as usize).clamp(1, MAX_PER_BONE)
    } else {
        1
    };
    for slab in &slabs(pts, wide, n) {
        if slab.len() < MIN_VERTICES.min(pts.len()) {
            continue;
        }
        if let Some(mut c) = capsule_along(slab, axis)
            && c.radius >= min_radius
            && c.a.is_finite()
            && c.b.is_finite()
        {
            c.bone = bone;
            out.push(c);
        }
    }
}

/// `pts` cut into `n` slabs of equal width along the unit direction `wide`.
fn slabs(pts: &[Vec3], wide: Vec3, n: usize) -> Vec<Vec<Vec3>> {
    let (lo, hi) = pts
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.dot(wide)), hi.max(p.dot(wide)))
        });
    let width = (hi - lo) / n as f32;
    let mut slabs: Vec<Vec<Vec3>> = vec![Vec::new(); n];
    for p in pts {
        let k = if width > 0.0 {
            (((p.dot(wide) - lo) / width) as usize).min(n - 1)
        } else {
            0
        };
        slabs[k].push(*p);
    }
    slabs
}

/// The principal axes of a point set (unit directions) with the points' extents along them,
/// largest variance first.
fn principal_axes(pts: &[Vec3]) -> Option<[(Vec3, f32); 3]> {
    let n = pts.len() as f32;
    let mean = pts.iter().copied().sum::<Vec3>() / n;
    let mut cov = Mat3::ZERO;
    for p in pts {
        let d = *p - mean;
        cov += Mat3::from_cols(d * d.x, d * d.y, d * d.z);
    }
    let mut axes = [Vec3::ZERO; 3];
    let mut m = cov;
    for k in 0..3 {
        // Power iteration on the deflated covariance from the column of largest norm (never
        // perpendicular to the top eigenvector unless the matrix is zero there).
        let mut v = [m.x_axis, m.y_axis, m.z_axis]
            .into_iter()
            .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))?
            .normalize_or(Vec3::X);
        for _ in 0..64 {
            v = (m * v).normalize_or(v);
        }
        // Keep the axes orthonormal against rounding.
        for a in &axes[..k] {
            v = (v - *a * v.dot(*a)).normalize_or(a.any_orthonormal_vector());
        }
        if k == 2 {
            v = axes[0].cross(axes[1]).normalize_or(v);
        }
        let lambda = v.dot(m * v);
        m -= Mat3::from_cols(v * v.x, v * v.y, v * v.z) * lambda;
        axes[k] = v;
    }
    let extent = |a: Vec3| {
        let (lo, hi) = pts
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.dot(a)), hi.max(p.dot(a)))
            });
        hi - lo
    };
    axes.iter()
        .all(|a| a.is_finite())
        .then(|| axes.map(|a| (a, extent(a))))
}

/// The point of segment `a`–`b` closest to `p`.
#[cfg(test)]
fn closest_on_segment(p: Vec3, a: Vec3, b: Vec3) -> Vec3 {
    let ab = b - a;
    let len2 = ab.length_squared();
    if len2.is_nan() || len2 <= 0.0 {
        return a;
    }
    a + ab * ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
}

/// The capsule along `axis` through the points' centroid that contains them all (module doc).
fn capsule_along(pts: &[Vec3], axis: Vec3) -> Option<FittedCapsule> {
    let mean = pts.iter().copied().sum::<Vec3>() / pts.len() as f32;
    let (mut t_lo, mut t_hi, mut r) = (f32::INFINITY, f32::NEG_INFINITY, 0.0f32);
    for p in pts {
        let d = *p - mean;
        let t = d.dot(axis);
        t_lo = t_lo.min(t);
        t_hi = t_hi.max(t);
        r = r.max((d - axis * t).length());
    }
    if !r.is_finite() || r <= 0.0 {
        return None;
    }
    // Ends start a radius inside the extremes (or both at the middle) and move out as needed.
    let (mut a, mut b) = if t_hi - t_lo > 2.0 * r {
        (t_lo + r, t_hi - r)
    } else {
        let m = 0.5 * (t_lo + t_hi);
        (m, m)
    };
    for p in pts {
        let d = *p - mean;
        let t = d.dot(axis);
        let perp = (d - axis * t).length().min(r);
        let reach = (r * r - perp * perp).max(0.0).sqrt();
        a = a.min(t + reach);
        b = b.max(t - reach);
    }
    Some(FittedCapsule {
        bone: 0,
        a: mean + axis * a,
        b: mean + axis * b,
        radius: r,
    })
}

#[cfg(test)]
mod tests;
