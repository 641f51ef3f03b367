//! The render target: linear-RGB colour, view depth and coverage per pixel, shared by the
//! solids' raster and the hair's.
//!
//! What: row-major `Vec<Vec3>` colour (top row first), `Vec<f32>` depth in metres along the
//! view direction (`+inf` = nothing opaque there yet) and `Vec<f32>` coverage (alpha). Only
//! opaque solids (the head, body spheres, meshes) write depth; hair is blended into colour and
//! tested against depth. Everything drawn composites its coverage α into the coverage channel
//! with "over" (`a += (1 − a)·α`), the same operator as the colour, so after a frame
//! `colour = premultiplied + (1 − coverage)·background` holds exactly: with a black
//! background the colour is premultiplied by the coverage (what an RGBA EXR stores).
//!
//! How: [`Framebuffer::clear`] reuses the allocation between frames. The conversions at the
//! edge (`convert`) take the background's share back out of the colour with that identity:
//! [`Framebuffer::premultiplied_into`] (linear, premultiplied: what OpenEXR stores) and
//! [`Framebuffer::to_srgb16_rgba_into`] (sRGB, straight alpha: what PNG stores); the 8-bit
//! ones give exactly what [`crate::color::linear_to_srgb8`] gives (NaN to 0, clamped), through
//! a table (`srgb8`).
//!
//! Why `f32` linear colour: hair is many layers of low-coverage blends; doing them in 8-bit
//! sRGB would band and darken. The conversion to sRGB happens once, at the edge. The drawing
//! functions check that `color`, `depth` and `coverage` hold `width * height` entries (the
//! fields are public) and draw nothing otherwise, rather than index out of bounds.

mod convert;
mod srgb8;

use glam::Vec3;
use rayon::prelude::*;

/// A linear-RGB colour buffer with depth and coverage buffers.
#[derive(Clone, Debug, PartialEq)]
pub struct Framebuffer {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear RGB, row-major, top row first; `width * height` entries.
    pub color: Vec<Vec3>,
    /// Depth along the camera's view direction in metres; `+inf` where empty.
    pub depth: Vec<f32>,
    /// Coverage (alpha) in [0, 1]: the fraction of the pixel covered by what was drawn,
    /// composited with "over" (`1 − Π(1 − αᵢ)`); 0 where nothing was drawn.
    pub coverage: Vec<f32>,
}

impl Framebuffer {
    /// A `width` x `height` buffer filled with `background` and infinite depth.
    pub fn new(width: u32, height: u32, background: Vec3) -> Framebuffer {
        let n = width as usize * height as usize;
        Framebuffer {
            width,
            height,
            color: vec![background; n],
            depth: vec![f32::INFINITY; n],
            coverage: vec![0.0; n],
        }
    }

    /// Bytes of a `width` × `height` framebuffer: linear RGB (`Vec3`), depth and coverage
    /// (`f32` each) per pixel; for the run's memory budget (`crate::budget`).
    pub fn estimated_bytes(width: u32, height: u32) -> u64 {
        width as u64 * height as u64 * (size_of::<Vec3>() + 2 * size_of::<f32>()) as u64
    }

    /// Number of pixels, `width * height`.
    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// True when all three buffers hold exactly `width * height` entries (drawing requires it).
    pub fn is_consistent(&self) -> bool {
        let n = self.pixel_count();
        self.color.len() == n && self.depth.len() == n && self.coverage.len() == n
    }

    /// Refills with `background`, infinite depth and zero coverage, keeping (and if needed
    /// fixing the size of) the allocations.
    pub fn clear(&mut self, background: Vec3) {
        // 20 bytes a pixel (18 MB at 1280×720): filled in parallel stripes, not by one thread.
        const STRIPE: usize = 1 << 14;
        let n = self.pixel_count();
        self.color.resize(n, background);
        self.depth.resize(n, f32::INFINITY);
        self.coverage.resize(n, 0.0);
        self.color
            .par_chunks_mut(STRIPE)
            .zip(self.depth.par_chunks_mut(STRIPE))
            .zip(self.coverage.par_chunks_mut(STRIPE))
            .for_each(|((c, d), a)| {
                c.fill(background);
                d.fill(f32::INFINITY);
                a.fill(0.0);
            });
    }

    /// Colour at pixel `(x, y)`, if inside.
    pub fn pixel(&self, x: u32, y: u32) -> Option<Vec3> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.color
            .get(y as usize * self.width as usize + x as usize)
            .copied()
    }

    /// 8-bit sRGB, 3 bytes per pixel, rows top to bottom (what `write_png_rgb8` takes).
    pub fn to_srgb8(&self) -> Vec<u8> {
        let mut out = Vec::new();
        self.to_srgb8_into(&mut out);
        out
    }

    /// As [`Framebuffer::to_srgb8`], into a reused buffer.
    pub fn to_srgb8_into(&self, out: &mut Vec<u8>) {
        convert::srgb8_into(&self.color, out);
    }

    /// Linear colour premultiplied by coverage, and the coverage: `rgb = colour − (1 −
    /// coverage)·background` (the module doc's identity, so a pixel nothing covers is exactly
    /// 0), into reused buffers. Composited "over" any background `B` as `rgb + (1 − alpha)·B`,
    /// it gives this frame's colour when `B` is `background`. What an RGBA OpenEXR stores.
    /// NaN becomes 0; values are clamped to [0, f32::MAX] (rounding may leave −1e-9) and the
    /// coverage to [0, 1].
    pub fn premultiplied_into(&self, background: Vec3, rgb: &mut Vec<Vec3>, alpha: &mut Vec<f32>) {
        convert::premultiplied_into(&self.color, &self.coverage, background, rgb, alpha);
    }

    /// 16-bit RGBA, 4 samples per pixel, rows top to bottom (what `write_png_rgba16` takes):
    /// sRGB-encoded colour with straight (not premultiplied) alpha = coverage, the PNG
    /// convention. The colour is [`Framebuffer::premultiplied_into`]'s divided by the
    /// coverage, so `alpha·colour + (1 − alpha)·background` (in linear) gives this frame's
    /// colour again; a pixel whose alpha rounds to 0 is written (0, 0, 0, 0). Straight colour
    /// above 1 (a bright highlight on a partly covered pixel) is clamped like the 8-bit
    /// conversion's: such a pixel composites darker than the frame shows.
    pub fn to_srgb16_rgba_into(&self, background: Vec3, out: &mut Vec<u16>) {
        convert::srgb16_rgba_into(&self.color, &self.coverage, background, out);
    }

    /// `0x00RRGGBB` sRGB per pixel (the layout a minifb window takes), into a reused buffer.
    pub fn to_argb_u32_into(&self, out: &mut Vec<u32>) {
        convert::argb_u32_into(&self.color, out);
    }
}

#[cfg(test)]
mod tests;
