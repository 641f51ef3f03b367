use super::*;

fn point(position_m: Vec3, intensity: f32) -> Light {
    Light::point(position_m, Vec3::splat(intensity)).unwrap()
}

#[test]
fn a_point_light_past_the_ratio_becomes_directional_with_i_over_d_squared() {
    let head = Vec3::new(0.0, 1.6, 0.0);
    let reach = 0.5;
    // 1.5e11 m straight above the head: travels −Y, I/d² = 2.25e23 / 2.25e22 = 10.
    let mut lights = [
        point(head + Vec3::new(0.0, 1.5e11, 0.0), 2.25e23),
        // 2047 × reach: stays a point light.
        point(head + Vec3::new(2047.0 * reach, 0.0, 0.0), 1.0),
        crate::light::default_light(),
    ];
    let before = lights;
    let far = far_point_lights_as_directional(&mut lights, head, reach);
    assert_eq!(far.len(), 1);
    assert_eq!(far[0].index, 0);
    match lights[0] {
        Light::Directional { travel, irradiance } => {
            assert!((travel.get() - Vec3::NEG_Y).length() < 1e-6, "{travel:?}");
            assert!((irradiance - Vec3::splat(10.0)).abs().max_element() < 1e-5);
        }
        Light::Point { .. } => panic!("still a point light"),
    }
    assert_eq!(&lights[1..], &before[1..]);
    // Idempotent.
    assert!(far_point_lights_as_directional(&mut lights, head, reach).is_empty());
}

#[test]
fn a_light_at_the_edge_of_f32_gives_a_finite_direction() {
    // |d|² = 3e76 overflows f32; in f64 the irradiance is 1e38 / 3e76 ≈ 3.3e-39 (a
    // subnormal f32 that still compares above 0).
    let mut lights = [point(Vec3::new(-1e38, 1e38, 1e38), 1e38)];
    let far = far_point_lights_as_directional(&mut lights, Vec3::ZERO, 0.4);
    assert_eq!(far.len(), 1);
    let Light::Directional { travel, irradiance } = lights[0] else {
        panic!("still a point light");
    };
    let t = travel.get();
    let third = 1.0 / 3f32.sqrt();
    assert!(
        (t - Vec3::new(third, -third, -third)).length() < 1e-6,
        "{t}"
    );
    assert!(irradiance.is_finite() && irradiance.x > 0.0, "{irradiance}");
}
