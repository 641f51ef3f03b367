//! Body colliders fitted to a character's mesh: one capsule per bone, around the rest-pose
//! vertices that bone dominates.
//!
//! # How
//! For every bone outside the head (the head is the hairstyle's ellipsoid), the vertices whose
//! largest skin weight is on it are gathered at the rest pose. Their principal axis (the
//! covariance's largest eigenvector, by power iteration) carries the capsule's segment; the
//! radius is the largest distance of a vertex from that axis, and each end of the segment is
//! then moved out just far enough that every vertex lies within the radius of the segment
//! (for a vertex at axial position t and distance d from the axis, the end must reach
//! t ∓ √(r² − d²)). The capsule therefore contains every vertex it was fitted to: hair kept
//! outside the capsules is outside those vertices' hull. On round limbs (the mannequin of the
//! embedded dance) it hugs the surface; on boxy parts it bulges past the faces (a box's
//! capsule reaches its corners), so hair rests a little above them.
//!
//! Bones with fewer than [`MIN_VERTICES`] vertices are skipped (fingers, a stray vertex). A
//! capsule is also shrunk so that, at rest, it keeps [`HEAD_CLEARANCE_M`] from the head
//! ellipsoid: hair roots sit on the ellipsoid and must never start inside a body collider
//! (a neck capsule fitted to a collar would otherwise swallow the nape's roots).
//!
//! Why capsules: a sphere per bone leaves gaps along limbs or bulges around them, and a capsule
//! costs one segment projection more than a sphere in the simulation's inner loop.

use glam::{Affine3A, Vec3};

/// Fewest vertices a bone needs to get a capsule.
pub const MIN_VERTICES: usize = 8;
/// Distance a capsule keeps from the fitted head ellipsoid at rest, in pose metres.
pub const HEAD_CLEARANCE_M: f32 = 0.005;
/// Thinnest capsule kept, pose metres.
pub const MIN_RADIUS_M: f32 = 0.01;

/// A fitted capsule in model rest space: the bone it follows, segment ends, radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FittedCapsule {
    pub(crate) bone: usize,
    pub(crate) a: Vec3,
    pub(crate) b: Vec3,
    pub(crate) radius: f32,
}

/// Capsules around the rest-pose `points` grouped by `bone_of_point`, skipping bones marked in
/// `skip`. `head` maps the unit sphere to the head ellipsoid at rest (model space); capsules
/// are shrunk to keep `clearance` (model units) from it.
pub(crate) fn fit(
    points: &[Vec3],
    bone_of_point: &[usize],
    skip: &[bool],
    head: Affine3A,
    clearance: f32,
    min_radius: f32,
) -> Vec<FittedCapsule> {
    let bones = skip.len();
    let mut groups: Vec<Vec<Vec3>> = vec![Vec::new(); bones];
    for (p, &b) in points.iter().zip(bone_of_point) {
        if b < bones && !skip[b] {
            groups[b].push(*p);
        }
    }
    let to_head = head.inverse();
    let mut out = Vec::new();
    for (bone, pts) in groups.iter().enumerate() {
        if pts.len() < MIN_VERTICES {
            continue;
        }
        let Some(mut c) = enclosing_capsule(pts) else {
            continue;
        };
        c.bone = bone;
        // Keep clear of the head: the end nearer the head is pulled back along the segment
        // until the capsule leaves `clearance` (the distance is measured in the ellipsoid's
        // unit-sphere space and scaled by its shortest axis, which never over-states it);
        // if even the far end alone is too close, the radius shrinks instead.
        let unit = min_axis(&head);
        let gap_of = |a: Vec3, b: Vec3, r: f32| {
            let (a_u, b_u) = (to_head.transform_point3(a), to_head.transform_point3(b));
            (closest_on_segment(Vec3::ZERO, a_u, b_u).length() - 1.0) * unit - r
        };
        if gap_of(c.a, c.b, c.radius) < clearance {
            let (near, far) = if to_head.transform_point3(c.a).length()
                < to_head.transform_point3(c.b).length()
            {
                (c.a, c.b)
            } else {
                (c.b, c.a)
            };
            let far_gap = gap_of(far, far, c.radius);
            let kept = if far_gap < clearance {
                c.radius += far_gap - clearance;
                0.0
            } else {
                let (mut lo, mut hi) = (0.0f32, 1.0f32);
                for _ in 0..30 {
                    let mid = 0.5 * (lo + hi);
                    if gap_of(far, far + (near - far) * mid, c.radius) >= clearance {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                lo
            };
            c.a = far;
            c.b = far + (near - far) * kept;
        }
        if c.radius >= min_radius && c.radius.is_finite() && c.a.is_finite() && c.b.is_finite() {
            out.push(c);
        }
    }
    out
}

fn min_axis(m: &Affine3A) -> f32 {
    m.matrix3
        .x_axis
        .length()
        .min(m.matrix3.y_axis.length())
        .min(m.matrix3.z_axis.length())
}

/// The point of segment `a`–`b` closest to `p`.
pub(crate) fn closest_on_segment(p: Vec3, a: Vec3, b: Vec3) -> Vec3 {
    let ab = b - a;
    let len2 = ab.length_squared();
    if !(len2 > 0.0) {
        return a;
    }
    a + ab * ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
}

/// The capsule along the points' principal axis that contains them all (module doc).
fn enclosing_capsule(pts: &[Vec3]) -> Option<FittedCapsule> {
    let n = pts.len() as f32;
    let mean = pts.iter().copied().sum::<Vec3>() / n;
    let (mut xx, mut xy, mut xz, mut yy, mut yz, mut zz) = (0.0f32, 0.0, 0.0, 0.0, 0.0, 0.0);
    for p in pts {
        let d = *p - mean;
        xx += d.x * d.x;
        xy += d.x * d.y;
        xz += d.x * d.z;
        yy += d.y * d.y;
        yz += d.y * d.z;
        zz += d.z * d.z;
    }
    let cov = glam::Mat3::from_cols(
        Vec3::new(xx, xy, xz),
        Vec3::new(xy, yy, yz),
        Vec3::new(xz, yz, zz),
    );
    // Power iteration from the extent's longest axis (converges for any start not
    // perpendicular to the principal axis; 64 rounds reach f32 precision for ratios ≥ 1.3).
    let mut axis = [Vec3::X, Vec3::Y, Vec3::Z]
        .into_iter()
        .max_by(|a, b| (cov * *a).length().total_cmp(&(cov * *b).length()))?;
    for _ in 0..64 {
        axis = (cov * axis).normalize_or(axis);
    }
    let (mut t_lo, mut t_hi, mut r) = (f32::INFINITY, f32::NEG_INFINITY, 0.0f32);
    for p in pts {
        let d = *p - mean;
        let t = d.dot(axis);
        t_lo = t_lo.min(t);
        t_hi = t_hi.max(t);
        r = r.max((d - axis * t).length());
    }
    if !(r > 0.0) || !r.is_finite() {
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
mod tests {
    use super::*;

    /// Points on a cylinder of radius 3 along Y from y = −10 to 10, plus its two end discs: the
    /// capsule runs along Y, has radius 3, and contains every point (to rounding).
    #[test]
    fn capsule_contains_its_points_and_follows_the_long_axis() {
        let mut pts = Vec::new();
        for i in 0..40 {
            let a = i as f32 * std::f32::consts::TAU / 40.0;
            for y in [-10.0f32, -5.0, 0.0, 5.0, 10.0] {
                pts.push(Vec3::new(3.0 * a.cos(), y, 3.0 * a.sin()));
            }
        }
        let c = enclosing_capsule(&pts).unwrap();
        assert!((c.radius - 3.0).abs() < 0.05, "{}", c.radius);
        assert!((c.a - c.b).normalize().dot(Vec3::Y).abs() > 0.999);
        for p in &pts {
            let d = (*p - closest_on_segment(*p, c.a, c.b)).length();
            assert!(d <= c.radius * (1.0 + 1e-5), "{p} at {d} > {}", c.radius);
        }
        // The ends reach the discs' rims: the segment spans y = ±10 (the rim points at
        // distance r from the axis need the ends at their own height).
        assert!((c.a.y.abs() - 10.0).abs() < 0.05 && (c.b.y.abs() - 10.0).abs() < 0.05);
    }

    #[test]
    fn capsules_keep_clear_of_the_head_and_small_groups_are_skipped() {
        // A bone whose points reach into a unit head sphere at the origin.
        let pts: Vec<Vec3> = (0..20)
            .map(|i| {
                Vec3::new(
                    0.3 * (i as f32).cos(),
                    -0.9 - 0.1 * i as f32,
                    0.3 * (i as f32).sin(),
                )
            })
            .collect();
        let bones = vec![0usize; pts.len()];
        let caps = fit(&pts, &bones, &[false], Affine3A::IDENTITY, 0.05, 0.01);
        assert_eq!(caps.len(), 1);
        let c = caps[0];
        let closest = closest_on_segment(Vec3::ZERO, c.a, c.b).length() - c.radius;
        assert!(
            closest >= 1.0 + 0.05 - 1e-4,
            "capsule reaches {closest} from the centre"
        );
        // It was shortened, not thinned: the radius still holds the points' spread.
        assert!(c.radius > 0.25, "radius {}", c.radius);
        let few = fit(
            &pts[..5],
            &bones[..5],
            &[false],
            Affine3A::IDENTITY,
            0.0,
            0.0,
        );
        assert!(few.is_empty());
        let skipped = fit(&pts, &bones, &[true], Affine3A::IDENTITY, 0.0, 0.0);
        assert!(skipped.is_empty());
    }
}
