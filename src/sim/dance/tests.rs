use super::*;

#[test]
fn peak_yaw_rate_and_bob_are_as_documented() {
    let d = AnalyticDance::new(Vec3::new(0.076, 0.098, 0.094));
    let h = 1e-4;
    let mut max_rate = 0.0f32;
    let mut max_bob = 0.0f32;
    for k in 0..20_000 {
        let t = k as f64 * 5e-4;
        let a = d.head_at(t);
        let b = d.head_at(t + h);
        let q = Quat::from_mat3a(&(b.matrix3 * a.matrix3.transpose()));
        max_rate = max_rate.max(q.to_axis_angle().1 / h as f32);
        max_bob = max_bob.max(d.translation_m(t).y.abs());
    }
    assert!((7.0..9.5).contains(&max_rate), "peak rate {max_rate} rad/s");
    assert!((max_bob - 0.1).abs() < 1e-3, "bob {max_bob} m");
}

#[test]
fn head_never_touches_the_body_spheres() {
    let r = Vec3::new(0.076, 0.098, 0.094);
    let d = AnalyticDance::new(r);
    for k in 0..2000 {
        let c = d.colliders(k as f64 * 0.005);
        let centre: Vec3 = c.head.translation.into();
        for s in &c.spheres {
            // Every point of the sphere is farther from the head centre than the largest
            // semi-axis (plus the collision margin), so it cannot touch the ellipsoid.
            let gap = (centre - s.center).length() - s.radius_m;
            assert!(
                gap > r.max_element() + crate::sim::COLLISION_MARGIN_M,
                "sphere touches the head at step {k}: gap {gap} m"
            );
        }
    }
}
