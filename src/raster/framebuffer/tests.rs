use super::*;
use crate::color::linear_to_srgb16;

#[test]
fn new_clear_and_convert() {
    let mut fb = Framebuffer::new(3, 2, Vec3::new(1.0, 0.0, 0.5));
    assert!(fb.is_consistent());
    assert_eq!(fb.color.len(), 6);
    assert!(fb.depth.iter().all(|d| *d == f32::INFINITY));
    assert!(fb.coverage.iter().all(|a| *a == 0.0));
    fb.coverage[1] = 0.5;
    fb.color[4] = Vec3::new(f32::NAN, 2.0, -1.0);
    fb.depth[4] = 1.0;
    let rgb = fb.to_srgb8();
    assert_eq!(&rgb[0..3], &[255, 0, 188]);
    assert_eq!(&rgb[12..15], &[0, 255, 0]);
    let mut argb = Vec::new();
    fb.to_argb_u32_into(&mut argb);
    assert_eq!(argb[0], 0x00FF_00BC);
    assert_eq!(argb[4], 0x0000_FF00);
    assert_eq!(fb.pixel(2, 0), Some(fb.color[2]));
    assert_eq!(fb.pixel(3, 0), None);
    let cap = fb.color.capacity();
    fb.clear(Vec3::ZERO);
    assert_eq!(fb.color.capacity(), cap);
    assert!(fb.color.iter().all(|c| *c == Vec3::ZERO));
    assert!(fb.depth.iter().all(|d| *d == f32::INFINITY));
    assert!(fb.coverage.iter().all(|a| *a == 0.0));
    fb.coverage.pop();
    assert!(!fb.is_consistent());
}

/// Layers composited with "over" by hand (colour and coverage, as the raster does) come
/// back out: premultiplied = Σ of what was drawn, straight = that over the coverage, and
/// the straight sRGB16 colour composited over the background again gives the frame's
/// colour.
#[test]
fn premultiplied_and_straight_alpha_undo_the_background() {
    let bg = Vec3::new(0.012, 0.014, 0.018);
    let mut fb = Framebuffer::new(4, 1, bg);
    let layers = [
        (Vec3::new(0.5, 0.25, 0.125), 0.6),
        (Vec3::new(0.9, 0.3, 0.05), 0.3),
    ];
    // Pixel 0: two layers; 1: nothing; 2: fully covered; 3: NaN colour, coverage 1e-6.
    let (mut p, mut a) = (Vec3::ZERO, 0.0f32);
    for (src, alpha) in layers {
        let c = fb.color[0];
        fb.color[0] = c + (src - c) * alpha;
        fb.coverage[0] += (1.0 - fb.coverage[0]) * alpha;
        p = p * (1.0 - alpha) + src * alpha;
        a += (1.0 - a) * alpha;
    }
    fb.color[2] = Vec3::new(0.2, 0.4, 0.8);
    fb.coverage[2] = 1.0;
    fb.color[3] = Vec3::new(f32::NAN, 0.5, 0.5);
    fb.coverage[3] = 1e-6;
    let (mut rgb, mut alpha) = (Vec::new(), Vec::new());
    fb.premultiplied_into(bg, &mut rgb, &mut alpha);
    assert!((rgb[0] - p).abs().max_element() < 1e-6, "{} vs {p}", rgb[0]);
    assert_eq!(alpha[0], a);
    assert_eq!((rgb[1], alpha[1]), (Vec3::ZERO, 0.0));
    assert_eq!((rgb[2], alpha[2]), (fb.color[2], 1.0));
    assert_eq!(rgb[3].x, 0.0);
    let mut rgba = Vec::new();
    fb.to_srgb16_rgba_into(bg, &mut rgba);
    assert_eq!(rgba.len(), 16);
    let straight = p / a;
    assert_eq!(
        &rgba[0..4],
        &[
            linear_to_srgb16(straight.x),
            linear_to_srgb16(straight.y),
            linear_to_srgb16(straight.z),
            (a * 65535.0).round() as u16
        ]
    );
    assert_eq!(&rgba[4..8], &[0; 4]);
    assert_eq!(
        rgba[8..12],
        [
            linear_to_srgb16(0.2),
            linear_to_srgb16(0.4),
            linear_to_srgb16(0.8),
            65535
        ]
    );
    // 1e-6 × 65535 rounds to alpha 0: transparent black, whatever the colour.
    assert_eq!(&rgba[12..16], &[0; 4]);
    // Decoded (sRGB -> linear) and composited over the background: the frame's colour.
    let decode = |v: u16| {
        let s = v as f64 / 65535.0;
        if s <= 0.04045 {
            s / 12.92
        } else {
            ((s + 0.055) / 1.055).powf(2.4)
        }
    };
    let a16 = rgba[3] as f64 / 65535.0;
    for k in 0..3 {
        let back = a16 * decode(rgba[k]) + (1.0 - a16) * bg[k] as f64;
        assert!(
            (back - fb.color[0][k] as f64).abs() < 1e-4,
            "channel {k}: {back}"
        );
    }
}

#[test]
fn empty_buffers() {
    let fb = Framebuffer::new(0, 5, Vec3::ONE);
    assert!(fb.to_srgb8().is_empty());
    assert!(fb.is_consistent());
}
