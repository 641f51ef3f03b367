//! What a segment covers of a pixel: the two coverage models of the pixel loop, each a
//! closure `cover(d, qx, ry, along) -> (mask, α)` of the pixel centre's place relative to the
//! segment (d signed across its axis, `along` from its first end, (qx, ry) the offset from
//! that end, all in pixels), chosen once per segment so each pixel loop is compiled for one.
//!
//! - [`plain`]: the sub-samples (`samples.rs`) within half the drawn width of the axis and,
//!   along it, those with `0 ≤ s < len`: ends and joints cut square, so consecutive segments
//!   of one hair tile it without blending the joint pixel twice. A horizontal line of width
//!   w covers ⌊16w⌋ or ⌈16w⌉ sixteenths of each column, exact on average over positions.
//! - [`fibers`]: a bundle's segment drawn as its fibres keeps the analytic box filter of
//!   their profile (`bundle.rs`) blended with its band (`fibers.rs`), its joints on their
//!   mitres and its free ends box-filtered, over all 16 sub-samples at that α.

use glam::Vec4;

use super::bundle::Profiles;
use super::fast_float::{fmax, fmin};
use super::fibers::Fibers;
use super::samples::{ALL_SAMPLES, SAMPLE_X, SAMPLE_Y};
use super::segment::Seg;

/// The sub-samples of a pixel inside plain segment `s`'s strip, at its opacity.
#[inline(always)]
pub(super) fn plain(s: &Seg) -> impl Fn(f32, f32, f32, f32) -> (u16, f32) + '_ {
    let hw = Vec4::splat(s.half_w);
    let len = Vec4::splat(s.len);
    // Each sub-sample's offset across and along the line, four lanes at a time.
    let (mut off_d, mut off_a) = ([Vec4::ZERO; 4], [Vec4::ZERO; 4]);
    for g in 0..4 {
        let (ox, oy) = (SAMPLE_X[g], SAMPLE_Y[g]);
        off_d[g] = s.ux * oy - s.uy * ox;
        off_a[g] = s.ux * ox + s.uy * oy;
    }
    move |d: f32, _qx: f32, _ry: f32, along: f32| {
        let (d, a) = (Vec4::splat(d), Vec4::splat(along));
        let mut mask = 0u16;
        for g in 0..4 {
            let ak = a + off_a[g];
            let inside = (d + off_d[g]).abs().cmple(hw) & ak.cmpge(Vec4::ZERO) & ak.cmplt(len);
            mask |= (inside.bitmask() as u16) << (4 * g);
        }
        (mask, s.opacity)
    }
}

/// Segment `s` drawn as its fibres `f` (profiles `prof`): every sub-sample, at the fibres'
/// summed overlap with the pixel plus the band it is blended from, cut at the mitres of its
/// joints and box-filtered at its free ends.
#[inline(always)]
pub(super) fn fibers<'a>(
    prof: &'a Profiles,
    f: Fibers,
    s: &'a Seg,
) -> impl Fn(f32, f32, f32, f32) -> (u16, f32) + 'a {
    move |d: f32, qx: f32, ry: f32, along: f32| {
        let (ua, ub) = ((d - 0.5) * f.inv_r, (d + 0.5) * f.inv_r);
        let a = prof.cumulative(f.pattern, ub) - prof.cumulative(f.pattern, ua);
        let (e, bw) = (d.abs(), f.band_hw);
        let band = fmax(fmin(e + 0.5, bw) - fmax(e - 0.5, -bw), 0.0);
        let (ex, ey) = (qx - f.e.0, ry - f.e.1);
        let across = fmin(a * f.cov_scale + band * f.band_scale, 1.0);
        let lo = if s.cap0 {
            fmin(fmax(along + 0.5, 0.0), 1.0)
        } else {
            f32::from(u8::from(f.b0.0 * qx + f.b0.1 * ry >= 0.0))
        };
        let hi = if s.cap1 {
            fmin(fmax(s.len - along + 0.5, 0.0), 1.0)
        } else {
            f32::from(u8::from(f.b1.0 * ex + f.b1.1 * ey < 0.0))
        };
        (ALL_SAMPLES, across * fmax(lo + hi - 1.0, 0.0) * s.opacity)
    }
}
