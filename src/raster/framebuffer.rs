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
//! exactly what [`crate::colour::linear_to_srgb8`] gives (NaN to 0, clamped, so a stray NaN
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

use crate::colour::{linear_to_srgb8, linear_to_srgb16};

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
mod tests {
    use super::*;

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

    /// The table reproduces `linear_to_srgb8` exactly: at every level change and one ulp
    /// either side, at every bucket boundary, on 2M bit patterns spread over [0, 1], and on
    /// out-of-range and non-finite values.
    #[test]
    fn srgb_table_matches_transfer_function() {
        let t = Srgb8Table::get();
        let check = |v: f32| assert_eq!(t.srgb8(v), linear_to_srgb8(v), "v = {v:e}");
        let mut changes = 0;
        for b in 0..=BUCKETS {
            let lo = b as f32 / BUCKETS as f32;
            check(lo);
            check(f32::from_bits(lo.to_bits().saturating_sub(1)));
            let th = t.threshold[b];
            if th.is_finite() {
                changes += 1;
                check(th);
                check(f32::from_bits(th.to_bits() - 1));
                check(f32::from_bits(th.to_bits() + 1));
            }
        }
        // Every level 1..=255 starts somewhere, each in its own bucket.
        assert_eq!(changes, 255);
        let one = 1.0_f32.to_bits();
        for i in 0..2_000_000_u32 {
            check(f32::from_bits(
                (u64::from(i) * u64::from(one) / 2_000_000) as u32,
            ));
        }
        for v in [
            -0.0,
            -1e-30,
            -5.0,
            1.0,
            1.000_001,
            7.0,
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
        ] {
            check(v);
        }
        check(f32::NEG_INFINITY);
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
}
