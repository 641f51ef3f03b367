use super::*;

#[test]
fn spec_accepts_a_normal_camera_and_rebuilds_it() {
    let s = CameraSpec::new(Vec3::new(0.0, 0.1, 1.0), Vec3::ZERO, Vec3::Y, 0.5).unwrap();
    let cam = s.camera(40, 30);
    assert_eq!((cam.eye, cam.target, cam.up), (s.eye(), s.target(), s.up()));
    assert_eq!((cam.fov_y_rad, cam.width, cam.height), (0.5, 40, 30));
    assert_eq!(CameraSpec::from_camera(&cam), Some(s));
}

#[test]
fn spec_refuses_each_broken_rule() {
    let (e, t, u) = (Vec3::Z, Vec3::ZERO, Vec3::Y);
    let nan = Vec3::new(f32::NAN, 0.0, 0.0);
    assert!(matches!(
        CameraSpec::new(nan, t, u, 0.5),
        Err(CameraError::NonFinite { field: "eye", .. })
    ));
    assert!(matches!(
        CameraSpec::new(e, Vec3::INFINITY, u, 0.5),
        Err(CameraError::NonFinite {
            field: "target",
            ..
        })
    ));
    assert!(matches!(
        CameraSpec::new(e, e, u, 0.5),
        Err(CameraError::EyeAtTarget(_))
    ));
    for up in [Vec3::ZERO, Vec3::Z, -2.0 * Vec3::Z] {
        assert!(matches!(
            CameraSpec::new(e, t, up, 0.5),
            Err(CameraError::UpAlongView { .. })
        ));
    }
    for fov in [0.0, -0.1, std::f32::consts::PI, 4.0, f32::NAN] {
        let err = CameraSpec::new(e, t, u, fov).unwrap_err();
        assert!(matches!(err, CameraError::FieldOfView { .. }), "{fov}");
        assert!(err.to_string().contains("degrees"));
    }
}

/// The framing keeps every strand point in the image and follows translation only.
#[test]
fn head_following_frames_the_hair_and_follows_translation() {
    let pts: Vec<Vec3> = (0..200)
        .map(|i| {
            let a = i as f32 * 0.1;
            Vec3::new(0.1 * a.sin(), -0.002 * i as f32, 0.1 * a.cos())
        })
        .chain([Vec3::NAN])
        .collect();
    let (rig, cam) = HeadFollowing::frame(&pts, Affine3A::IDENTITY, 0.4, 200, 100);
    for p in pts.iter().filter(|p| p.is_finite()) {
        let q = cam.project(*p).expect("in front of the camera");
        assert!(q.x > 0.0 && q.x < 200.0 && q.y > 0.0 && q.y < 100.0, "{q}");
    }
    let moved = Vec3::new(0.3, -0.1, 2.0);
    let (c0, c1) = (
        rig.camera(Vec3::ZERO, 200, 100),
        rig.camera(moved, 200, 100),
    );
    assert!((c1.eye - c0.eye - moved).length() < 1e-5);
    assert!((c1.target - c0.target - moved).length() < 1e-5);
    assert_eq!(c1.fov_y_rad, HEAD_FOLLOWING_FOV_Y_RAD);
    // No finite strand point: the framing still gives a usable camera around the head.
    let (_, cam) = HeadFollowing::frame(&[Vec3::NAN], Affine3A::IDENTITY, 0.4, 10, 10);
    assert!(cam.project(Vec3::ZERO).is_some());
}
