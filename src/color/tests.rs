use super::*;

#[test]
fn srgb_endpoints_and_midpoint() {
    assert_eq!(linear_to_srgb8(0.0), 0);
    assert_eq!(linear_to_srgb8(1.0), 255);
    // sRGB(0.5 linear) = 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5 -> 188
    assert_eq!(linear_to_srgb8(0.5), 188);
    assert_eq!(linear_to_srgb8(f32::NAN), 0);
    assert_eq!(linear_to_srgb8(f32::INFINITY), 255);
    assert_eq!(linear_to_srgb8(-3.0), 0);
}

#[test]
fn srgb16_endpoints_and_agreement_with_8_bit() {
    assert_eq!(linear_to_srgb16(0.0), 0);
    assert_eq!(linear_to_srgb16(1.0), 65535);
    // 1.055 * 0.5^(1/2.4) - 0.055 = 0.735357 (to 6 places), × 65535 = 48191.6 -> 48192
    assert_eq!(linear_to_srgb16(0.5), 48192);
    assert_eq!(linear_to_srgb16(f32::NAN), 0);
    assert_eq!(linear_to_srgb16(f32::INFINITY), 65535);
    assert_eq!(linear_to_srgb16(-3.0), 0);
    // The same curve: rescaled to 8 bits, within half a level of the 8-bit value.
    for i in 0..=10_000 {
        let v = i as f32 / 10_000.0;
        let s16 = linear_to_srgb16(v) as f32 * 255.0 / 65535.0;
        assert!(
            (s16 - linear_to_srgb8(v) as f32).abs() <= 0.5 + 1e-3,
            "v = {v}"
        );
    }
}

#[test]
fn radiance_saturates_instead_of_overflowing() {
    let v = saturate_radiance(Vec3::new(f32::INFINITY, f32::NAN, -2.0));
    assert_eq!(v, Vec3::new(RADIANCE_MAX, 0.0, 0.0));
    // Ordinary radiance passes unchanged, to the bit.
    assert_eq!(
        saturate_radiance(Vec3::new(0.25, 7.0, 3e29)),
        Vec3::new(0.25, 7.0, 3e29)
    );
    // The headroom the ceiling is chosen for: 16 lights' worth of terms at the ceiling, each
    // times a scattering of 1e6, stay finite.
    assert!((RADIANCE_MAX * 1e6 * 16.0).is_finite());
}
