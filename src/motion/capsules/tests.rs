use super::*;

fn contained(pts: &[Vec3], caps: &[FittedCapsule]) -> bool {
    pts.iter().all(|p| {
        caps.iter()
            .any(|c| (*p - closest_on_segment(*p, c.a, c.b)).length() <= c.radius * (1.0 + 1e-5))
    })
}

/// Points on a cylinder of radius 3 along Y from y = −10 to 10: one capsule along Y, of
/// radius 3, reaching the end rims, containing every point.
#[test]
fn a_limb_gets_one_capsule_along_it() {
    let mut pts = Vec::new();
    for i in 0..40 {
        let a = i as f32 * std::f32::consts::TAU / 40.0;
        for y in [-10.0f32, -5.0, 0.0, 5.0, 10.0] {
            pts.push(Vec3::new(3.0 * a.cos(), y, 3.0 * a.sin()));
        }
    }
    let bones = vec![0usize; pts.len()];
    let far_head = Affine3A::from_translation(Vec3::splat(100.0));
    let caps = fit(&pts, &bones, &[false], &[Vec3::Y], far_head, 0.0, 0.0);
    assert_eq!(caps.len(), 1);
    let c = caps[0];
    assert!((c.radius - 3.0).abs() < 0.05, "{}", c.radius);
    assert!((c.a - c.b).normalize().dot(Vec3::Y).abs() > 0.999);
    assert!((c.a.y.abs() - 10.0).abs() < 0.05 && (c.b.y.abs() - 10.0).abs() < 0.05);
    assert!(contained(&pts, &caps));
}

/// An elliptic trunk twice as wide (x) as deep (z), along Y: several capsules side by side,
/// each about as thick as the trunk is deep, together containing every point; the back
/// (z = −depth) bulges out by much less than a single enclosing capsule would.
#[test]
fn a_wide_trunk_gets_capsules_side_by_side() {
    let (wx, wz) = (0.17f32, 0.11f32);
    let mut pts = Vec::new();
    for i in 0..48 {
        let a = i as f32 * std::f32::consts::TAU / 48.0;
        for k in 0..6 {
            pts.push(Vec3::new(wx * a.cos(), 1.2 + 0.05 * k as f32, wz * a.sin()));
        }
    }
    let bones = vec![0usize; pts.len()];
    let far_head = Affine3A::from_translation(Vec3::splat(100.0));
    let caps = fit(&pts, &bones, &[false], &[Vec3::Y], far_head, 0.0, 0.0);
    assert!(caps.len() >= 3, "{} capsules", caps.len());
    assert!(contained(&pts, &caps));
    for c in &caps {
        assert!((c.a - c.b).normalize().dot(Vec3::Y).abs() > 0.99);
    }
    // How far the colliders reach behind the back at its middle (x = 0, z = −wz).
    let reach = caps
        .iter()
        .map(|c| {
            let p = Vec3::new(0.0, 1.3, -1.0);
            let q = closest_on_segment(p, c.a, c.b);
            // Farthest point of this capsule along −z at x = 0 (if it spans x = 0).
            let dx = q.x.abs();
            if dx < c.radius {
                -q.z + (c.radius * c.radius - dx * dx).sqrt()
            } else {
                0.0
            }
        })
        .fold(0.0f32, f32::max);
    assert!(reach - wz < 0.015, "the back bulges {} m", reach - wz);
}

#[test]
fn head_points_and_small_groups_are_left_out() {
    // A bone whose points reach into a unit head sphere at the origin.
    let pts: Vec<Vec3> = (0..40)
        .map(|i| {
            let a = i as f32 * 0.7;
            Vec3::new(0.3 * a.cos(), -0.5 - 0.05 * i as f32, 0.3 * a.sin())
        })
        .collect();
    let bones = vec![0usize; pts.len()];
    let caps = fit(
        &pts,
        &bones,
        &[false],
        &[Vec3::Y],
        Affine3A::IDENTITY,
        0.05,
        0.0,
    );
    assert!(!caps.is_empty());
    let kept: Vec<Vec3> = pts.iter().copied().filter(|p| p.length() >= 0.95).collect();
    assert!(contained(&kept, &caps));
    let few = fit(
        &pts[..5],
        &bones[..5],
        &[false],
        &[Vec3::Y],
        Affine3A::IDENTITY,
        0.0,
        0.0,
    );
    assert!(few.is_empty());
    let skipped = fit(
        &pts,
        &bones,
        &[true],
        &[Vec3::Y],
        Affine3A::IDENTITY,
        0.0,
        0.0,
    );
    assert!(skipped.is_empty());
}
