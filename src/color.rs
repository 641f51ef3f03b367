//! Colour encodings shared by the stages that turn linear radiance into pixels (the raster's
//! conversions, the output files): the sRGB transfer curve of IEC 61966-2-1,
//! C' = 12.92 C for C ≤ 0.0031308 and C' = 1.055 C^{1/2.4} − 0.055 above, applied to the
//! linear value clamped to [0, 1] (NaN as 0) and rounded to the nearest 8- or 16-bit code;
//! and the ceiling every shaded radiance saturates at before it reaches a pixel
//! ([`saturate_radiance`]).

use glam::Vec3;

/// Largest radiance a shaded point (hair or skin) or a light's irradiance at a point takes,
/// linear: brighter saturates here. Scene values are only checked to be finite after the
/// exposure (up to `f32::MAX` ≈ 3.4e38), and a light's irradiance times a fibre's scattering
/// (several times 1 at a glint) summed over 16 lights plus the ambient can overflow to
/// infinity, which compositing turns into NaN (∞ − ∞, 0·∞) and the pixel into black. Below
/// 1e30 sums of up to f32::MAX / 1e30 ≈ 3.4e8 such terms stay finite, and compositing only
/// averages colours (weights summing to at most 1) and adds the background seen through, so
/// no pixel overflows. Every output saturates far lower: a PNG at 1, an EXR reader shows 1e30
/// as white.
pub const RADIANCE_MAX: f32 = 1e30;

/// `v` within [0, [`RADIANCE_MAX`]] per channel: infinity saturates to the ceiling, a NaN
/// (no radiance was defined) is 0.
#[inline]
pub fn saturate_radiance(v: Vec3) -> Vec3 {
    // glam's `max` is `if x > y { x } else { y }`: a NaN channel gives 0.
    v.max(Vec3::ZERO).min(Vec3::splat(RADIANCE_MAX))
}

/// Linear [0, 1] -> sRGB-encoded [0, 1] (IEC 61966-2-1); NaN maps to 0 and values outside
/// [0, 1] are clamped, so no invalid value reaches a pixel.
#[inline]
fn srgb_encode(v: f32) -> f32 {
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

/// Linear [0, 1] -> 8-bit sRGB, rounding to nearest ([`srgb_encode`]).
#[inline]
pub fn linear_to_srgb8(v: f32) -> u8 {
    (srgb_encode(v) * 255.0 + 0.5) as u8
}

/// Linear [0, 1] -> 16-bit sRGB (the same curve as [`linear_to_srgb8`], scaled to 65535),
/// rounding to nearest.
#[inline]
pub fn linear_to_srgb16(v: f32) -> u16 {
    (srgb_encode(v) * 65535.0 + 0.5) as u16
}

#[cfg(test)]
mod tests;
