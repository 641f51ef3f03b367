//! Polylines by arc length: a strand's length `L = Σ |pᵢ₊₁ − pᵢ|`, and its resampling at
//! points evenly spaced in arc length (`s_k = L·k/(n−1)`, linear between the polyline's
//! vertices), the first and last on its ends. Imported strands are resampled this way for
//! guides (equal rigid links) and for render strands.

use glam::Vec3;

/// Polyline length.
pub fn arc_length(p: &[Vec3]) -> f32 {
    p.windows(2).map(|w| (w[1] - w[0]).length()).sum()
}

/// Resamples the polyline `p` (>= 2 points, length > 0) at `out.len()` points evenly spaced
/// in arc length, first and last on its ends.
pub fn resample_by_arc_length(p: &[Vec3], out: &mut [Vec3]) {
    let n = out.len();
    let total = arc_length(p);
    if n == 0 {
        return;
    }
    if n == 1 || p.len() < 2 || total.is_nan() || total <= 0.0 {
        out.fill(p.first().copied().unwrap_or(Vec3::ZERO));
        return;
    }
    let mut seg = 0usize;
    let mut seg_start = 0.0f32;
    let mut seg_len = (p[1] - p[0]).length();
    for (k, o) in out.iter_mut().enumerate() {
        let s = total * k as f32 / (n - 1) as f32;
        while seg + 2 < p.len() && s > seg_start + seg_len {
            seg_start += seg_len;
            seg += 1;
            seg_len = (p[seg + 1] - p[seg]).length();
        }
        let t = if seg_len > 0.0 {
            ((s - seg_start) / seg_len).clamp(0.0, 1.0)
        } else {
            0.0
        };
        *o = p[seg].lerp(p[seg + 1], t);
    }
    out[n - 1] = p[p.len() - 1];
}
