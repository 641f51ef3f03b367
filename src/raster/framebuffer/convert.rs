//! A frame's pixels converted at the edge, in parallel stripes: 8-bit sRGB (a PNG, a
//! window), linear premultiplied colour with its coverage (an RGBA EXR), 16-bit sRGB with
//! straight alpha (an RGBA PNG). All read the identity the compositing keeps,
//! `colour = premultiplied + (1 − coverage)·background` (`framebuffer.rs`), and none lets a
//! NaN through as garbage.

use glam::Vec3;
use rayon::prelude::*;

use super::srgb8::Srgb8Table;
use crate::color::linear_to_srgb16;

/// Pixels per parallel task of the conversions.
const CHUNK: usize = 16 * 1024;

/// 8-bit sRGB of `color`, 3 bytes a pixel, into `out`.
pub(super) fn srgb8_into(color: &[Vec3], out: &mut Vec<u8>) {
    let t = Srgb8Table::get();
    out.clear();
    out.resize(3 * color.len(), 0);
    out.par_chunks_mut(3 * CHUNK)
        .zip(color.par_chunks(CHUNK))
        .for_each(|(out, color)| {
            for (o, c) in out.chunks_exact_mut(3).zip(color) {
                o.copy_from_slice(&[t.srgb8(c.x), t.srgb8(c.y), t.srgb8(c.z)]);
            }
        });
}

/// `0x00RRGGBB` sRGB of `color`, one `u32` a pixel, into `out`.
pub(super) fn argb_u32_into(color: &[Vec3], out: &mut Vec<u32>) {
    let t = Srgb8Table::get();
    out.clear();
    out.resize(color.len(), 0);
    out.par_chunks_mut(CHUNK)
        .zip(color.par_chunks(CHUNK))
        .for_each(|(out, color)| {
            for (o, c) in out.iter_mut().zip(color) {
                let (r, g, b) = (t.srgb8(c.x), t.srgb8(c.y), t.srgb8(c.z));
                *o = (u32::from(r) << 16) | (u32::from(g) << 8) | u32::from(b);
            }
        });
}

/// Each pixel of `color` and `coverage` premultiplied against `background` into `rgb`, its
/// coverage (in [0, 1]) into `alpha`.
pub(super) fn premultiplied_into(
    color: &[Vec3],
    coverage: &[f32],
    background: Vec3,
    rgb: &mut Vec<Vec3>,
    alpha: &mut Vec<f32>,
) {
    rgb.clear();
    rgb.resize(color.len(), Vec3::ZERO);
    alpha.clear();
    alpha.resize(color.len(), 0.0);
    rgb.par_chunks_mut(CHUNK)
        .zip(alpha.par_chunks_mut(CHUNK))
        .zip(color.par_chunks(CHUNK))
        .zip(coverage.par_chunks(CHUNK))
        .for_each(|(((rgb, alpha), color), coverage)| {
            for (((o, oa), c), a) in rgb.iter_mut().zip(alpha).zip(color).zip(coverage) {
                let a = unit(*a);
                *o = premultiplied(*c, a, background);
                *oa = a;
            }
        });
}

/// Each pixel of `color` and `coverage` as 16-bit sRGB with straight alpha, 4 samples a
/// pixel, into `out`: the premultiplied colour over its coverage; (0, 0, 0, 0) where the
/// alpha rounds to 0.
pub(super) fn srgb16_rgba_into(
    color: &[Vec3],
    coverage: &[f32],
    background: Vec3,
    out: &mut Vec<u16>,
) {
    out.clear();
    out.resize(4 * color.len(), 0);
    out.par_chunks_mut(4 * CHUNK)
        .zip(color.par_chunks(CHUNK))
        .zip(coverage.par_chunks(CHUNK))
        .for_each(|((out, color), coverage)| {
            for ((o, c), a) in out.chunks_exact_mut(4).zip(color).zip(coverage) {
                let a = unit(*a);
                let a16 = (a * 65535.0 + 0.5) as u16;
                if a16 == 0 {
                    o.copy_from_slice(&[0; 4]);
                    continue;
                }
                let s = premultiplied(*c, a, background) / a;
                let e = linear_to_srgb16;
                o.copy_from_slice(&[e(s.x), e(s.y), e(s.z), a16]);
            }
        });
}

/// A coverage in [0, 1] (NaN to 0).
#[inline]
fn unit(a: f32) -> f32 {
    if a >= 0.0 { a.min(1.0) } else { 0.0 }
}

/// What was drawn at a pixel of colour `c` and coverage `a`, premultiplied: `c − (1 −
/// a)·background`, NaN to 0, within [0, f32::MAX].
#[inline]
fn premultiplied(c: Vec3, a: f32, background: Vec3) -> Vec3 {
    let p = c - (1.0 - a) * background;
    // glam's `max` is `if x > y { x } else { y }`: NaN gives 0.
    p.max(Vec3::ZERO).min(Vec3::splat(f32::MAX))
}
