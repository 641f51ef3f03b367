//! The uniform Catmull-Rom spline through a guide's control points, sampled at evenly spaced
//! parameters (Bertails 2005 §3.1's smoothing of a strand's control polygon).
//!
//! Between control points p1 and p2 (neighbours p0, p3) the curve is the cubic Hermite with
//! tangents (p2 − p0)/2 and (p3 − p1)/2:
//! c(t) = ½ [2p1 + (p2 − p0) t + (2p0 − 5p1 + 4p2 − p3) t² + (3p1 − p0 − 3p2 + p3) t³],
//! t ∈ [0, 1]. It passes through every control point and is C¹. At the ends phantom points
//! reflect the first and last links (p₋₁ = 2p0 − p1), so the curve passes through both ends
//! and collinear, evenly spaced points give the line itself.

use glam::Vec3;

/// Samples the uniform Catmull-Rom spline through `ctrl` (>= 2 points) at `out.len()` evenly
/// spaced parameters from the first to the last control point; end tangents use reflected
/// phantom points, so the curve passes through both ends.
pub fn catmull_rom_resample(ctrl: &[Vec3], out: &mut [Vec3]) {
    catmull_rom_resample_to(ctrl, 1.0, out);
}

/// [`catmull_rom_resample`] over the first `fraction` ∈ (0, 1] of the spline's parameter
/// range: a strand that stops short of its guides' tips, still sampled at `out.len()` points.
/// The guides' links are of equal length, so the parameter is proportional to arc length up to
/// the spline's bending.
pub fn catmull_rom_resample_to(ctrl: &[Vec3], fraction: f32, out: &mut [Vec3]) {
    let m = ctrl.len();
    let n = out.len();
    if n == 0 {
        return;
    }
    if m < 2 || n == 1 {
        out.fill(ctrl.first().copied().unwrap_or(Vec3::ZERO));
        return;
    }
    let at = |i: isize| -> Vec3 {
        if i < 0 {
            2.0 * ctrl[0] - ctrl[1]
        } else if i as usize >= m {
            2.0 * ctrl[m - 1] - ctrl[m - 2]
        } else {
            ctrl[i as usize]
        }
    };
    let fraction = if fraction.is_finite() {
        fraction.clamp(1e-3, 1.0)
    } else {
        1.0
    };
    let scale = (m - 1) as f32 * fraction / (n - 1) as f32;
    for (k, o) in out.iter_mut().enumerate() {
        let u = k as f32 * scale;
        let seg = (u as usize).min(m - 2);
        let t = u - seg as f32;
        let i = seg as isize;
        let (p0, p1, p2, p3) = (at(i - 1), at(i), at(i + 1), at(i + 2));
        // Uniform Catmull-Rom in Hermite form with tangents (p2 - p0)/2 and (p3 - p1)/2.
        let t2 = t * t;
        let t3 = t2 * t;
        *o = 0.5
            * ((2.0 * p1)
                + (p2 - p0) * t
                + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2
                + (3.0 * p1 - p0 - 3.0 * p2 + p3) * t3);
    }
}

#[cfg(test)]
mod tests;
