//! Float operations of the pixel loops, cheaper than the standard library's for the values
//! those loops see: `min`/`max` without NaN handling and `ceil` to an index without libm.
//!
//! Why: the loops visit every pixel centre a segment's strip can reach, so each instruction
//! counts. `f32::min/max` return the non-NaN operand, three extra instructions a call. A row's
//! `ceil` is a libm call on baseline x86-64, and a saturating f32 → usize conversion a dozen
//! instructions where f32 → i32 is one: callgrind counted the two per row at 6% of all
//! instructions.

/// `ceil(v)` for `0 ≤ v < 2³¹` as an index: a truncation and a compare, no libm call and no
/// saturating conversion.
#[inline]
pub(super) fn ceil_index(v: f32) -> usize {
    let t = v as i32;
    (t + i32::from((t as f32) < v)) as usize
}

/// `min` as `minss`: the result is `b` when either is NaN (the pixel loops see finite values).
#[inline(always)]
pub(super) fn fmin(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

/// `max` as `maxss`: the result is `b` when either is NaN.
#[inline(always)]
pub(super) fn fmax(a: f32, b: f32) -> f32 {
    if a > b { a } else { b }
}

#[cfg(test)]
mod tests;
