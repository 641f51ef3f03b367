use super::*;

fn v3(x: f32, y: f32, z: f32) -> Vec4 {
    Vec4::new(x, y, z, 0.0)
}

#[test]
fn linear_midpoint_and_clamping() {
    let t = Track::new(
        vec![1.0, 3.0],
        vec![v3(0.0, 2.0, -4.0), v3(2.0, 6.0, 4.0)],
        Interpolation::Linear,
    )
    .expect("valid track");
    assert!((t.sample_vec3(2.0) - Vec3::new(1.0, 4.0, 0.0)).length() < 1e-6);
    assert_eq!(t.sample_vec3(0.0), Vec3::new(0.0, 2.0, -4.0));
    assert_eq!(t.sample_vec3(9.0), Vec3::new(2.0, 6.0, 4.0));
}

#[test]
fn step_holds_previous_key() {
    let t = Track::new(
        vec![0.0, 1.0, 2.0],
        vec![v3(1.0, 0.0, 0.0), v3(2.0, 0.0, 0.0), v3(3.0, 0.0, 0.0)],
        Interpolation::Step,
    )
    .expect("valid track");
    assert_eq!(t.sample_vec3(0.999).x, 1.0);
    assert_eq!(t.sample_vec3(1.0).x, 2.0);
    assert_eq!(t.sample_vec3(1.5).x, 2.0);
    assert_eq!(t.sample_vec3(2.5).x, 3.0);
}

#[test]
fn cubic_zero_tangents_is_smoothstep() {
    // With zero tangents the Hermite basis reduces to p0 + (p1 − p0)(3u² − 2u³):
    // u = 0.25 -> 0.15625 (= 3/16 − 2/64), u = 0.5 -> 0.5.
    let z = Vec4::ZERO;
    let t = Track::new(
        vec![0.0, 2.0],
        vec![z, v3(0.0, 0.0, 0.0), z, z, v3(1.0, 0.0, 0.0), z],
        Interpolation::CubicSpline,
    )
    .expect("valid track");
    assert!((t.sample_vec3(0.5).x - 0.15625).abs() < 1e-6);
    assert!((t.sample_vec3(1.0).x - 0.5).abs() < 1e-6);
}

#[test]
fn cubic_tangents_are_scaled_by_interval() {
    // Values 0 -> 0 with out-tangent 1/s over a 2 s interval: p(u) = 2(u³ − 2u² + u);
    // at u = 0.5: 2·(0.125 − 0.5 + 0.5) = 0.25.
    let z = Vec4::ZERO;
    let t = Track::new(
        vec![0.0, 2.0],
        vec![z, z, v3(1.0, 0.0, 0.0), z, z, z],
        Interpolation::CubicSpline,
    )
    .expect("valid track");
    assert!((t.sample_vec3(1.0).x - 0.25).abs() < 1e-6);
}

#[test]
fn slerp_takes_shortest_path() {
    // 170° and −170° about Y are 20° apart the short way; the midpoint is 180°.
    let a = Quat::from_rotation_y(170f32.to_radians());
    let b = Quat::from_rotation_y(-170f32.to_radians());
    let m = slerp_shortest(a, b, 0.5);
    let expected = Quat::from_rotation_y(std::f32::consts::PI);
    assert!(m.dot(expected).abs() > 1.0 - 1e-6, "got {m:?}");
}

#[test]
fn rejects_bad_tracks() {
    assert_eq!(
        Track::new(vec![], vec![], Interpolation::Linear),
        Err(TrackError::Empty)
    );
    assert!(matches!(
        Track::new(vec![0.0, 0.0], vec![Vec4::ZERO; 2], Interpolation::Linear),
        Err(TrackError::BadTime { index: 1, .. })
    ));
    assert!(matches!(
        Track::new(
            vec![0.0, 1.0],
            vec![Vec4::ZERO; 2],
            Interpolation::CubicSpline
        ),
        Err(TrackError::CountMismatch { .. })
    ));
    assert!(matches!(
        Track::new(vec![0.0], vec![Vec4::NAN], Interpolation::Step),
        Err(TrackError::BadValue { index: 0 })
    ));
}
