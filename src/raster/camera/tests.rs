use super::*;

fn cam() -> Camera {
    // 90° vertical fov: focal length = height / 2.
    Camera::look_at(
        Vec3::new(0.0, 0.0, 2.0),
        Vec3::ZERO,
        Vec3::Y,
        std::f32::consts::FRAC_PI_2,
        200,
        100,
    )
}

#[test]
fn projects_known_points() {
    let c = cam();
    assert!((c.focal_px() - 50.0).abs() < 1e-4);
    // The target is on the optical axis, at the image centre, 2 m deep.
    let p = c.project(Vec3::ZERO).unwrap();
    assert!((p - Vec3::new(100.0, 50.0, 2.0)).length() < 1e-4, "{p}");
    // 0.5 m right and 0.25 m up at depth 1: x = 100 + 50 * 0.5, y = 50 - 50 * 0.25.
    let p = c.project(Vec3::new(0.5, 0.25, 1.0)).unwrap();
    assert!((p - Vec3::new(125.0, 37.5, 1.0)).length() < 1e-4, "{p}");
    // Depth is along the axis, not the Euclidean distance.
    let p = c.project(Vec3::new(2.0, 0.0, 0.0)).unwrap();
    assert!(
        (p.z - 2.0).abs() < 1e-5 && (p.x - 150.0).abs() < 1e-3,
        "{p}"
    );
}

#[test]
fn rejects_points_behind_or_too_near() {
    let c = cam();
    assert!(c.project(Vec3::new(0.0, 0.0, 3.0)).is_none());
    assert!(
        c.project(Vec3::new(0.0, 0.0, 2.0 - 0.5 * DEFAULT_NEAR_M))
            .is_none()
    );
    assert!(c.project(Vec3::new(f32::NAN, 0.0, 0.0)).is_none());
    assert!(c.project(Vec3::new(f32::INFINITY, 0.0, 0.0)).is_none());
}

#[test]
fn ray_dir_hits_the_projected_pixel() {
    let c = cam();
    let v = c.view();
    let p = Vec3::new(0.3, -0.2, -0.4);
    let q = c.project(p).unwrap();
    let hit = v.eye + v.ray_dir(q.x, q.y) * q.z;
    assert!((hit - p).length() < 1e-5, "{hit} vs {p}");
}

#[test]
fn framing_keeps_sphere_inside() {
    let center = Vec3::new(0.1, 1.6, -0.2);
    let r = 0.15;
    let c = Camera::framing(center, r, Vec3::new(1.0, 0.2, 1.0), 0.7, 320, 180);
    let v = c.view();
    // Extreme points of the sphere in the image axes project inside the image.
    for d in [v.right, -v.right, v.up, -v.up] {
        let p = c.project(center + d * r).unwrap();
        assert!(p.x > 0.0 && p.x < 320.0 && p.y > 0.0 && p.y < 180.0, "{p}");
    }
    let p = c.project(center).unwrap();
    assert!((p.x - 160.0).abs() < 1e-3 && (p.y - 90.0).abs() < 1e-3);
    // Degenerate inputs still give a usable camera.
    let c = Camera::framing(center, r, Vec3::ZERO, 0.7, 0, 0);
    assert!(c.eye.is_finite());
    let c = Camera::framing(center, r, Vec3::Y, 0.7, 10, 10);
    assert!(c.project(center).is_some());
}

#[test]
fn degenerate_camera_does_not_panic() {
    let c = Camera::look_at(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, 0.0, 0, 0);
    let _ = c.project(Vec3::ONE);
    let c = Camera::look_at(Vec3::ZERO, Vec3::Y, Vec3::Y, f32::NAN, 10, 10);
    let _ = c.project(Vec3::new(0.0, 5.0, 0.1));
}
