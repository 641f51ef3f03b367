use super::*;

#[test]
fn huge_directions_normalise_without_overflow() {
    let d = parse_direction("1e30,1e30,1e30").unwrap();
    let third = 1.0 / 3f32.sqrt();
    assert!((d - Vec3::splat(third)).abs().max_element() < 1e-6, "{d}");
    assert!(parse_direction("1e-30,0,0").is_err());
    assert!(
        parse_direction("1e39,0,0")
            .unwrap_err()
            .contains("outside the range")
    );
}

#[test]
fn numbers_beyond_f32_are_reported_as_written() {
    assert!(
        parse_finite_f32("1e308")
            .unwrap_err()
            .starts_with("1e308 is outside")
    );
    assert!(parse_f32_as_written("nan").unwrap().is_nan());
    assert!(
        parse_finite_f64("1e400")
            .unwrap_err()
            .starts_with("1e400 is outside")
    );
    assert!(
        parse_finite_f64("inf")
            .unwrap_err()
            .contains("must be finite")
    );
}
