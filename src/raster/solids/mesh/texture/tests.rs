use glam::{Vec2, Vec3};

use super::*;

#[test]
fn texture_sampling_is_bilinear_and_wraps() {
    let t = Texture {
        width: 2,
        height: 2,
        texels: vec![Vec3::ZERO, Vec3::ONE, Vec3::ONE, Vec3::ZERO],
    };
    // Texel centres.
    assert_eq!(t.sample(Vec2::new(0.25, 0.25)), Vec3::ZERO);
    assert_eq!(t.sample(Vec2::new(0.75, 0.25)), Vec3::ONE);
    // Half-way between the four: the mean; one period further: the same.
    assert!((t.sample(Vec2::new(0.5, 0.5)) - Vec3::splat(0.5)).length() < 1e-6);
    assert!((t.sample(Vec2::new(1.5, -0.5)) - Vec3::splat(0.5)).length() < 1e-6);
    // Non-finite coordinates read at (0, 0), between the four texels.
    assert!((t.sample(Vec2::NAN) - Vec3::splat(0.5)).length() < 1e-6);
}
