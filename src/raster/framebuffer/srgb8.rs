//! `linear_to_srgb8` in table form, for the 8-bit conversions of whole frames: the same
//! value for every input, without a `powf` per channel.
//!
//! How: [0, 1] is cut into [`BUCKETS`] equal buckets; the sRGB curve never climbs more than
//! 0.81 of an 8-bit level per bucket (its steepest slope is 12.92·255 per unit), so each bucket
//! holds at most one level change, stored as a threshold found once by bisection on the f32
//! bit patterns. Why: calling `linear_to_srgb8` per pixel took 19 ms per 1280x720 frame in
//! `benches/raster.rs`, as long as drawing the hair.

use std::sync::OnceLock;

use crate::color::linear_to_srgb8;

/// Buckets of the linear -> sRGB8 table over [0, 1].
pub(super) const BUCKETS: usize = 4096;

/// `linear_to_srgb8` in table form: in bucket `b` (`v·BUCKETS` truncated), the result is
/// `base[b]`, plus one where `v ≥ threshold[b]`. Entry `BUCKETS` holds `v = 1` exactly.
pub(super) struct Srgb8Table {
    base: [u8; BUCKETS + 1],
    threshold: [f32; BUCKETS + 1],
}

impl Srgb8Table {
    pub(super) fn get() -> &'static Srgb8Table {
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
    pub(super) fn srgb8(&self, v: f32) -> u8 {
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

#[cfg(test)]
mod tests;
