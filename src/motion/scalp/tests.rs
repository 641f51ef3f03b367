use super::*;

/// Hand-placed points against the triangle (0,0,0), (1,0,0), (0,1,0): above its inside,
/// beyond an edge, beyond a corner, and a degenerate (collinear) triangle.
#[test]
fn nearest_points_on_a_triangle() {
    let (a, b, c) = (Vec3::ZERO, Vec3::X, Vec3::Y);
    let q = closest_on_triangle(Vec3::new(0.2, 0.3, 5.0), a, b, c);
    assert!((q - Vec3::new(0.2, 0.3, 0.0)).length() < 1e-6);
    let q = closest_on_triangle(Vec3::new(0.5, -2.0, 1.0), a, b, c);
    assert!((q - Vec3::new(0.5, 0.0, 0.0)).length() < 1e-6);
    let q = closest_on_triangle(Vec3::new(1.0, 1.0, 0.0), a, b, c);
    assert!((q - Vec3::new(0.5, 0.5, 0.0)).length() < 1e-6);
    let q = closest_on_triangle(Vec3::new(-1.0, -1.0, 0.0), a, b, c);
    assert_eq!(q, a);
    let q = closest_on_triangle(Vec3::new(0.5, 1.0, 0.0), a, Vec3::X, Vec3::X * 2.0);
    assert!((q - Vec3::new(0.5, 0.0, 0.0)).length() < 1e-6);
}
