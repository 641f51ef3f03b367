use super::*;

/// A particle driven into a long capsule from many directions ends outside it, at exactly
/// one link from its predecessor.
#[test]
fn push_out_keeps_the_link_and_leaves_the_capsule() {
    let cap = CapsuleCollider {
        a: Vec3::new(0.0, -0.2, 0.0),
        b: Vec3::new(0.05, 0.2, 0.0),
        radius_m: 0.06,
    };
    let link = 0.02;
    let mut touched = 0;
    for k in 0..300 {
        let (s, t) = (k as f32 * 0.37, k as f32 * 0.13);
        let axis = Vec3A::from(cap.b - cap.a).normalize();
        let f = (k % 11) as f32 / 10.0;
        let raw = Vec3A::new(s.cos() * t.sin(), t.cos(), s.sin() * t.sin());
        // Beside the segment (perpendicular to it), or beyond an end cap (any direction
        // pointing away from the segment there).
        let dir = if f > 0.0 && f < 1.0 {
            (raw - axis * raw.dot(axis)).normalize_or(axis.any_orthonormal_vector())
        } else {
            let away = if f == 0.0 { -axis } else { axis };
            (raw + away * (raw.dot(away).abs() + 0.1)).normalize()
        };
        let along = Vec3A::from(cap.a.lerp(cap.b, f));
        let prev = along + dir * (cap.radius_m + 0.002);
        let mut p = prev - dir * link;
        for _ in 0..super::super::collide::COLLISION_ROUNDS {
            match cap.push_out(prev, p, link, -dir) {
                Some(q) => {
                    p = q;
                    touched += 1;
                }
                None => break,
            }
        }
        assert!(((p - prev).length() / link - 1.0).abs() < 1e-5);
        assert!(
            cap.penetration_m(p) < 1e-4,
            "k {k}: {}",
            cap.penetration_m(p)
        );
    }
    assert!(touched > 250);
    // Degenerate capsules are ignored.
    let bad = CapsuleCollider {
        radius_m: f32::NAN,
        ..cap
    };
    assert!(bad.push_out(Vec3A::ZERO, Vec3A::X, 1.0, Vec3A::Y).is_none());
    assert_eq!(bad.penetration_m(Vec3A::ZERO), 0.0);
}
