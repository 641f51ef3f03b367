//! The render target: linear-RGB colour plus view depth per pixel.
//!
//! What: row-major `Vec<Vec3>` colour (top row first) and `Vec<f32>` depth in metres along the
//! view direction (`+inf` = nothing opaque there yet). Only opaque solids (the head, body
//! spheres) write depth; hair is blended into colour and tested against depth.
//!
//! How: [`Framebuffer::clear`] reuses the allocation between frames; the 8-bit conversions go
//! through [`crate::output::linear_to_srgb8`], which maps NaN to 0 and clamps, so a stray NaN
//! never reaches a PNG or a window as garbage.
//!
//! Why `f32` linear colour: hair is many layers of low-coverage blends; doing them in 8-bit
//! sRGB would band and darken. The conversion to sRGB happens once, at the edge. The drawing
//! functions check that `color` and `depth` hold `width * height` entries (the fields are
//! public) and draw nothing otherwise, rather than index out of bounds.

use glam::Vec3;

use crate::output::linear_to_srgb8;

/// A linear-RGB colour buffer with a depth buffer.
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
        }
    }

    /// Number of pixels, `width * height`.
    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// True when both buffers hold exactly `width * height` entries (drawing requires it).
    pub fn is_consistent(&self) -> bool {
        let n = self.pixel_count();
        self.color.len() == n && self.depth.len() == n
    }

    /// Refills with `background` and infinite depth, keeping (and if needed fixing the size
    /// of) the allocations.
    pub fn clear(&mut self, background: Vec3) {
        let n = self.pixel_count();
        self.color.clear();
        self.color.resize(n, background);
        self.depth.clear();
        self.depth.resize(n, f32::INFINITY);
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
        out.clear();
        out.reserve(3 * self.color.len());
        for c in &self.color {
            out.extend_from_slice(&[
                linear_to_srgb8(c.x),
                linear_to_srgb8(c.y),
                linear_to_srgb8(c.z),
            ]);
        }
    }

    /// `0x00RRGGBB` sRGB per pixel (the layout a minifb window takes), into a reused buffer.
    pub fn to_argb_u32_into(&self, out: &mut Vec<u32>) {
        out.clear();
        out.reserve(self.color.len());
        out.extend(self.color.iter().map(|c| {
            (u32::from(linear_to_srgb8(c.x)) << 16)
                | (u32::from(linear_to_srgb8(c.y)) << 8)
                | u32::from(linear_to_srgb8(c.z))
        }));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_clear_and_convert() {
        let mut fb = Framebuffer::new(3, 2, Vec3::new(1.0, 0.0, 0.5));
        assert!(fb.is_consistent());
        assert_eq!(fb.color.len(), 6);
        assert!(fb.depth.iter().all(|d| *d == f32::INFINITY));
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
    }

    #[test]
    fn empty_buffers() {
        let fb = Framebuffer::new(0, 5, Vec3::ONE);
        assert!(fb.to_srgb8().is_empty());
        assert!(fb.is_consistent());
    }
}
