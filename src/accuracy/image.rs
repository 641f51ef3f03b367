//! Image error of one frame against a more accurate one: how far a quality level's picture is
//! from another's, over the pixels the hair covers.
//!
//! Per pixel, the relative luminance error |Y − Y_ref| / max(Y_ref, floor), with Y the Rec. 709
//! luminance of linear RGB and the floor 1% of the reference's mean luminance over the pixels
//! compared, so that the darkest pixels, where a relative error means nothing, do not dominate;
//! the mean and the 95th percentile over the pixels compared. Which pixels is the caller's
//! choice (a mask: where hair covers at least half a pixel, for the quality report).
//!
//! Beside it, [`flip_mean`]: the perceived difference of the whole picture (ꟻLIP, `flip.rs`).

mod flip;

pub use flip::{FLIP_PIXELS_PER_DEGREE, flip_mean};

use crate::raster::Framebuffer;

/// The relative luminance error over the pixels compared.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageError {
    /// Pixels compared.
    pub pixels: usize,
    /// Mean relative luminance error.
    pub mean_rel_luminance: f64,
    /// Its 95th percentile.
    pub p95_rel_luminance: f64,
}

/// Rec. 709 luminance of linear RGB (the sum in f32, as every accuracy figure was taken).
pub fn luminance(c: glam::Vec3) -> f64 {
    c.dot(glam::Vec3::new(0.2126, 0.7152, 0.0722)) as f64
}

/// `image` against `reference` over the pixels where `mask` is true (the module doc); `None`
/// when the sizes differ or no pixel is compared. Non-finite pixels count as the largest error.
pub fn image_error(
    image: &Framebuffer,
    reference: &Framebuffer,
    mask: &[bool],
) -> Option<ImageError> {
    let n = reference.color.len();
    if image.color.len() != n || mask.len() != n {
        return None;
    }
    let picked: Vec<usize> = (0..n).filter(|&i| mask[i]).collect();
    if picked.is_empty() {
        return None;
    }
    let mean_ref = picked
        .iter()
        .map(|&i| luminance(reference.color[i]))
        .sum::<f64>()
        / picked.len() as f64;
    let floor = (0.01 * mean_ref).max(1e-12);
    let mut errors: Vec<f64> = picked
        .iter()
        .map(|&i| {
            let (y, y_ref) = (luminance(image.color[i]), luminance(reference.color[i]));
            let e = (y - y_ref).abs() / y_ref.max(floor);
            if e.is_finite() { e } else { f64::MAX }
        })
        .collect();
    errors.sort_by(f64::total_cmp);
    let mean = errors.iter().map(|e| e.min(1e300)).sum::<f64>() / errors.len() as f64;
    let p95 = errors[((errors.len() - 1) as f64 * 0.95).round() as usize];
    Some(ImageError {
        pixels: errors.len(),
        mean_rel_luminance: mean,
        p95_rel_luminance: p95,
    })
}

/// The pixels where `frame` (drawn without solids) is covered by at least half.
pub fn hair_mask(frame: &Framebuffer) -> Vec<bool> {
    frame.coverage.iter().map(|&c| c >= 0.5).collect()
}

#[cfg(test)]
mod tests;
