//! The render target: linear-RGB colour plus view depth per pixel.
//!
//! What: row-major `Vec<Vec3>` colour (top row first), `Vec<f32>` depth in metres along the
//! view direction (`+inf` = nothing opaque there yet) and `Vec<f32>` coverage (alpha). Only
//! opaque solids (the head, body spheres) write depth; hair is blended into colour and tested
//! against depth. Everything drawn composites its coverage α into the coverage channel with
//! "over" (`a += (1 − a)·α`), the same operator as the colour, so after a frame
//! `colour = premultiplied + (1 − coverage)·background` holds exactly: with a black
//! background the colour is premultiplied by the coverage (what an RGBA EXR stores).
//!
//! How: [`Framebuffer::clear`] reuses the allocation between frames. The 8-bit conversions give
//! exactly what [`crate::color::linear_to_srgb8`] gives (NaN to 0, clamped, so a stray NaN
//! never reaches a PNG or a window as garbage), through a table built once from that function:
//! [0, 1] is cut into 4096 equal buckets, and since the sRGB curve never climbs more than 0.81
//! of an 8-bit level per bucket (its steepest slope is 12.92·255 per unit), each bucket holds
//! at most one level change, stored as a threshold found by bisection on the f32 bit patterns.
//! Rejected: calling `linear_to_srgb8` (one `powf` per channel) per pixel, 19 ms per
//! 1280x720 frame in `benches/raster.rs`, as long as drawing the hair.
//!
//! For compositing elsewhere, [`Framebuffer::premultiplied_into`] takes the background's share
//! back out of the colour with that identity (linear, premultiplied: what OpenEXR stores), and
//! [`Framebuffer::to_srgb16_rgba_into`] divides by the coverage (sRGB, straight alpha: what
//! PNG stores).
//!
//! Why `f32` linear colour: hair is many layers of low-coverage blends; doing them in 8-bit
//! sRGB would band and darken. The conversion to sRGB happens once, at the edge. The drawing
//! functions check that `color` and `depth` hold `width * height` entries (the fields are
//! public) and draw nothing otherwise, rather than index out of bounds.

use std::sync::OnceLock;

use glam::Vec3;
use rayon::prelude::*;

use crate::color::{linear_to_srgb8, linear_to_srgb16};

/// Pixels per parallel task of the 8-bit conversions.
const CONVERT_CHUNK: usize = 16 * 1024;

/// Buckets of the linear -> sRGB8 table over [0, 1].
const BUCKETS: usize = 4096;

/// `linear_to_srgb8` in table form: in bucket `b` (`v·BUCKETS` truncated), the result is
/// `base[b]`, plus one where `v ≥ threshold[b]`. Entry `BUCKETS` holds `v = 1` exactly.
struct Srgb8Table {
    base: [u8; BUCKETS + 1],
    threshold: [f32; BUCKETS + 1],
}

impl Srgb8Table {
    fn get() -> &'static Srgb8Table {
        static TABLE: OnceLock<Box<Srgb8Table>> = OnceLock::new();
        TABLE.get_or_init(|| {
            let mut t = Box::new(Srgb8Table {
                base: [0; BUCKETS + 1],
                threshold: [f32::INFINITY; BUCKETS + 1],
            });
            for b in 0..=BUCKETS {
                let lo = b as f32 / BUCKETS as f32;
                let base = linear_to_srgb8(lo);
                t.base[b] = base;
                if b == BUCKETS {
                    break;
                }
                // Largest f32 below the next bucket; positive floats order like their bits.
                let last = f32::from_bits(((b + 1) as f32 / BUCKETS as f32).to_bits() - 1);
                if linear_to_srgb8(last) > base {
                    let (mut a, mut z) = (lo.to_bits(), last.to_bits());
                    while z - a > 1 {
                        let m = a + (z - a) / 2;
                        if linear_to_srgb8(f32::from_bits(m)) > base {
                            z = m;
                        } else {
                            a = m;
                        }
                    }
                    t.threshold[b] = f32::from_bits(z);
                }
            }
            t
        })
    }

    /// Same value as `linear_to_srgb8(v)` for every `v` (tested).
    #[inline]
    fn srgb8(&self, v: f32) -> u8 {
        // NaN fails `>=` and maps to 0, like `linear_to_srgb8`.
        let v = if v >= 0.0 { v.min(1.0) } else { 0.0 };
        // Exact: scaling by a power of two, truncation of a value in [0, BUCKETS].
        let b = (v * BUCKETS as f32) as i32 as usize;
        match (self.base.get(b), self.threshold.get(b)) {
            (Some(&base), Some(&t)) => base + u8::from(v >= t),
            _ => linear_to_srgb8(v),
        }
    }
}

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
        let t = Srgb8Table::get();
        out.clear();
        out.resize(3 * self.color.len(), 0);
        out.par_chunks_mut(3 * CONVERT_CHUNK)
            .zip(self.color.par_chunks(CONVERT_CHUNK))
            .for_each(|(out, color)| {
                for (o, c) in out.chunks_exact_mut(3).zip(color) {
                    o.copy_from_slice(&[t.srgb8(c.x), t.srgb8(c.y), t.srgb8(c.z)]);
                }
            });
    }

    /// Linear colour premultiplied by coverage, and the coverage: `rgb = colour − (1 −
    /// coverage)·background` (the module doc's identity, so a pixel nothing covers is exactly
    /// 0), into reused buffers. Composited "over" any background `B` as `rgb + (1 − alpha)·B`,
    /// it gives this frame's colour when `B` is `background`. What an RGBA OpenEXR stores.
    /// NaN becomes 0; values are clamped to [0, f32::MAX] (rounding may leave −1e-9) and the
    /// coverage to [0, 1].
    pub fn premultiplied_into(&self, background: Vec3, rgb: &mut Vec<Vec3>, alpha: &mut Vec<f32>) {
        rgb.clear();
        rgb.resize(self.color.len(), Vec3::ZERO);
        alpha.clear();
        alpha.resize(self.color.len(), 0.0);
        rgb.par_chunks_mut(CONVERT_CHUNK)
            .zip(alpha.par_chunks_mut(CONVERT_CHUNK))
            .zip(self.color.par_chunks(CONVERT_CHUNK))
            .zip(self.coverage.par_chunks(CONVERT_CHUNK))
            .for_each(|(((rgb, alpha), color), coverage)| {
                for (((o, oa), c), a) in rgb.iter_mut().zip(alpha).zip(color).zip(coverage) {
                    let a = unit(*a);
                    *o = premultiplied(*c, a, background);
                    *oa = a;
                }
            });
    }

    /// 16-bit RGBA, 4 samples per pixel, rows top to bottom (what `write_png_rgba16` takes):
    /// sRGB-encoded colour with straight (not premultiplied) alpha = coverage, the PNG
    /// convention. The colour is [`Framebuffer::premultiplied_into`]'s divided by the
    /// coverage, so `alpha·colour + (1 − alpha)·background` (in linear) gives this frame's
    /// colour again; a pixel whose alpha rounds to 0 is written (0, 0, 0, 0). Straight colour
    /// above 1 (a bright highlight on a partly covered pixel) is clamped like the 8-bit
    /// conversion's: such a pixel composites darker than the frame shows.
    pub fn to_srgb16_rgba_into(&self, background: Vec3, out: &mut Vec<u16>) {
        out.clear();
        out.resize(4 * self.color.len(), 0);
        out.par_chunks_mut(4 * CONVERT_CHUNK)
            .zip(self.color.par_chunks(CONVERT_CHUNK))
            .zip(self.coverage.par_chunks(CONVERT_CHUNK))
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

    /// `0x00RRGGBB` sRGB per pixel (the layout a minifb window takes), into a reused buffer.
    pub fn to_argb_u32_into(&self, out: &mut Vec<u32>) {
        let t = Srgb8Table::get();
        out.clear();
        out.resize(self.color.len(), 0);
        out.par_chunks_mut(CONVERT_CHUNK)
            .zip(self.color.par_chunks(CONVERT_CHUNK))
            .for_each(|(out, color)| {
                for (o, c) in out.iter_mut().zip(color) {
                    let (r, g, b) = (t.srgb8(c.x), t.srgb8(c.y), t.srgb8(c.z));
                    *o = (u32::from(r) << 16) | (u32::from(g) << 8) | u32::from(b);
                }
            });
    }
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

#[cfg(test)]
mod tests;
