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

/// A 48 × 32 picture with structure at several scales (a red ramp across, green stripes 4 px
/// wide, a constant blue), with `amplitude` added to every channel of the 8 × 8 blocks of one
/// colour of a checkerboard: a visible change of low spatial frequency.
fn textured(amplitude: f32) -> Framebuffer {
    let (w, h) = (48u32, 32u32);
    let mut fb = Framebuffer::new(w, h, Vec3::ZERO);
    for y in 0..h {
        for x in 0..w {
            let stripe = if (x / 4) % 2 == 0 { 0.15 } else { 0.35 };
            let block = ((x / 8) + (y / 8)) % 2 == 0;
            let base = Vec3::new(x as f32 / w as f32 * 0.8, stripe, 0.25);
            fb.color[(y * w + x) as usize] =
                base + Vec3::splat(if block { amplitude } else { 0.0 });
        }
    }
    fb
}

#[test]
fn flip_is_zero_for_the_same_picture_and_grows_with_the_difference() {
    let reference = textured(0.0);
    assert_eq!(flip_mean(&reference, &reference), Some(0.0));
    // Black against white: the largest colour difference there is, everywhere.
    let black = Framebuffer::new(48, 32, Vec3::ZERO);
    let white = Framebuffer::new(48, 32, Vec3::ONE);
    let opposite = flip_mean(&black, &white).unwrap();
    assert!(opposite > 0.5, "black against white: {opposite}");
    // A small change is a small error, and a larger change a larger one (measured: 0.967 for
    // black against white; 0.027, 0.038, 0.065, 0.124, 0.203 for these amplitudes).
    let errors: Vec<f64> = [0.005, 0.01, 0.02, 0.05, 0.1]
        .iter()
        .map(|&a| flip_mean(&textured(a), &reference).unwrap())
        .collect();
    assert!(errors[0] > 0.0 && errors[0] < 0.05, "{errors:?}");
    assert!(errors.windows(2).all(|p| p[1] > p[0]), "{errors:?}");
    assert!(errors[4] < opposite, "{errors:?} against {opposite}");
}

#[test]
fn flip_of_pictures_that_cannot_be_compared_is_no_figure() {
    let reference = textured(0.0);
    assert_eq!(
        flip_mean(&Framebuffer::new(32, 48, Vec3::ZERO), &reference),
        None
    );
    let empty = Framebuffer::new(0, 0, Vec3::ZERO);
    assert_eq!(flip_mean(&empty, &empty), None);
    // A buffer whose pixels do not fill its size (the fields are public).
    let mut short = textured(0.0);
    short.color.pop();
    assert_eq!(flip_mean(&short, &reference), None);
    assert_eq!(flip_mean(&reference, &short), None);
}
