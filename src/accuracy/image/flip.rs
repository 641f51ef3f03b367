//! ꟻLIP (Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström and Fairchild 2020, "FLIP: A
//! Difference Evaluator for Alternating Images"), the LDR form: how different two pictures look
//! to a viewer flipping between them, per pixel in [0, 1], from a colour difference in a
//! perceptual space after contrast-sensitivity filtering and a difference of edges and points.
//! The figure rendering papers report, so the quality levels' error can be set beside theirs.
//!
//! Computed by NVIDIA's C++ implementation (the `nv-flip` crate builds it), on the 8-bit sRGB
//! the PNG writer writes ([`Framebuffer::to_srgb8`]: what a viewer of the exported frames
//! sees), at the library's standard viewing conditions: 67 pixels per degree, a 0.7 m wide
//! 3840-pixel monitor seen from 0.7 m. The figure is the mean of the per-pixel error over the
//! whole image (hair, head and background), the single number the method's authors recommend.

use crate::raster::Framebuffer;

/// Pixels per degree of visual angle the error is taken at (the FLIP library's default).
pub const FLIP_PIXELS_PER_DEGREE: f32 = nv_flip::DEFAULT_PIXELS_PER_DEGREE;

/// The mean ꟻLIP of `image` against `reference` over the whole image (the module doc): 0 for
/// the same picture, towards 1 for pictures that share nothing. `None` when the sizes differ,
/// the image is empty, or a buffer does not hold `width × height` pixels.
pub fn flip_mean(image: &Framebuffer, reference: &Framebuffer) -> Option<f64> {
    let (width, height) = (reference.width, reference.height);
    let pixels = width as usize * height as usize;
    let sized = |f: &Framebuffer| f.width == width && f.height == height && f.color.len() == pixels;
    if pixels == 0 || !sized(image) || !sized(reference) {
        return None;
    }
    let as_flip = |f: &Framebuffer| nv_flip::FlipImageRgb8::with_data(width, height, &f.to_srgb8());
    let error = nv_flip::flip(as_flip(reference), as_flip(image), FLIP_PIXELS_PER_DEGREE);
    let values = error.to_vec();
    Some(values.iter().map(|&e| e as f64).sum::<f64>() / values.len().max(1) as f64)
}
