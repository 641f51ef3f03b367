use super::*;

#[test]
fn directions_are_normalised_once_and_bad_ones_refused() {
    let u = UnitDir::new(Vec3::new(0.0, -3.0, 4.0)).unwrap();
    assert!((u.get() - Vec3::new(0.0, -0.6, 0.8)).length() < 1e-6);
    // Huge but finite vectors normalise (their length² would overflow f32).
    let big = UnitDir::new(Vec3::new(1e30, 1e30, 0.0)).unwrap();
    assert!((big.get().length() - 1.0).abs() < 1e-6);
    for bad in [
        Vec3::ZERO,
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::splat(f32::INFINITY),
    ] {
        assert!(UnitDir::new(bad).is_err(), "{bad}");
    }
}

#[test]
fn point_light_follows_the_inverse_square_law_and_stays_finite_at_its_centre() {
    let l = Light::point(Vec3::new(0.0, 2.0, 0.0), Vec3::splat(8.0)).unwrap();
    let (wi, e) = l.toward_and_irradiance(Vec3::ZERO);
    assert!((wi - Vec3::Y).length() < 1e-6);
    assert!((e - Vec3::splat(2.0)).length() < 1e-6, "{e}: 8 / 2²");
    let (wi, e) = l.toward_and_irradiance(Vec3::new(0.0, 2.0, 0.0));
    assert!(wi.is_finite() && e.is_finite());
}

#[test]
fn colors_must_be_finite_and_non_negative() {
    assert!(Light::directional(Vec3::X, Vec3::new(1.0, -0.1, 1.0)).is_err());
    assert!(Light::point(Vec3::X, Vec3::splat(f32::NAN)).is_err());
    assert!(Light::point(Vec3::splat(f32::INFINITY), Vec3::ONE).is_err());
}

#[test]
fn turning_moves_a_point_light_about_the_pivot() {
    let l = Light::point(Vec3::new(1.0, 0.0, 0.0), Vec3::ONE).unwrap();
    let q = Quat::from_rotation_y(std::f32::consts::FRAC_PI_2);
    let Light::Point { position_m, .. } = l.turned(q, Vec3::ZERO) else {
        unreachable!()
    };
    assert!((position_m - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-6);
}
