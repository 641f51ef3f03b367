use super::*;
use glam::Vec3;

fn frame(colors: &[Vec3]) -> Framebuffer {
    let mut fb = Framebuffer::new(colors.len() as u32, 1, Vec3::ZERO);
    fb.color.copy_from_slice(colors);
    fb
}

#[test]
fn the_same_image_has_no_error_and_a_scaled_one_its_scale() {
    let reference = frame(&[Vec3::splat(0.2), Vec3::new(0.5, 0.1, 0.0), Vec3::splat(1.0)]);
    let mask = vec![true; 3];
    let same = image_error(&reference, &reference, &mask).unwrap();
    assert_eq!(
        (same.mean_rel_luminance, same.p95_rel_luminance),
        (0.0, 0.0)
    );
    // Every pixel 10% brighter: a relative error of 0.1 everywhere (luminance is linear).
    let brighter = frame(&reference.color.iter().map(|c| *c * 1.1).collect::<Vec<_>>());
    let e = image_error(&brighter, &reference, &mask).unwrap();
    assert!((e.mean_rel_luminance - 0.1).abs() < 1e-6, "{e:?}");
    assert!((e.p95_rel_luminance - 0.1).abs() < 1e-6, "{e:?}");
}

#[test]
fn black_pixels_are_judged_against_the_floor_and_masked_pixels_not_at_all() {
    // Reference mean luminance 0.5 over the two compared pixels: floor 0.005. A black
    // reference pixel drawn at 0.005 reads an error of 1, not infinity.
    let reference = frame(&[Vec3::ZERO, Vec3::ONE, Vec3::splat(7.0)]);
    let image = frame(&[Vec3::splat(0.005), Vec3::ONE, Vec3::ZERO]);
    let e = image_error(&image, &reference, &[true, true, false]).unwrap();
    assert_eq!(e.pixels, 2);
    assert!((e.mean_rel_luminance - 0.5).abs() < 1e-6, "{e:?}");
    assert!((e.p95_rel_luminance - 1.0).abs() < 1e-6, "{e:?}");
    // A NaN pixel is the largest error, never a NaN figure.
    let nan = frame(&[Vec3::NAN, Vec3::ONE, Vec3::ZERO]);
    let e = image_error(&nan, &reference, &[true, true, false]).unwrap();
    assert!(e.p95_rel_luminance > 1e300 && e.mean_rel_luminance.is_finite());
    // Nothing to compare, or sizes that differ: no figure.
    assert!(image_error(&image, &reference, &[false; 3]).is_none());
    assert!(image_error(&frame(&[Vec3::ONE]), &reference, &[true; 3]).is_none());
}
