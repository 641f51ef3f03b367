//! Curls: a helix of radius R and period P added around a strand's centre line, in a frame
//! carried along it, p_i ← c_i + r(s_i) (cos a_i b1_i + sin a_i b2_i) with a_i = 2π s_i / P + φ
//! (s_i the arc length, φ the strand's phase, b2 = t × b1).
//!
//! The frame starts from the vector between two guide roots of the wisp (which turns with the
//! head, so curls do not spin when the head turns) and is carried along the strand by
//! projection onto each new normal plane, b1 ← normalize(b1 − (b1·t) t): a discrete parallel
//! transport that costs two dot products per point and never flips. The radius ramps up
//! linearly over the first 2 cm, r(s) = R min(s / 2 cm, 1), so roots stay on the scalp.

use crate::hairstyle::CurlSpec;
use glam::Vec3;

/// Adds a helix of `curl.radius_m` around the centre line `pos` (in place). The radius ramps up
/// over the first 2 cm so roots stay on the scalp.
pub(super) fn add_curl(pos: &mut [Vec3], reference: Vec3, curl: &CurlSpec, phase: f32) {
    const RAMP_M: f32 = 0.02;
    let n = pos.len();
    if n < 2 {
        return;
    }
    let mut prev = pos[0];
    let mut t = (pos[1] - pos[0]).normalize_or(Vec3::NEG_Y);
    let mut b1 = (reference - reference.dot(t) * t).normalize_or(t.any_orthonormal_vector());
    let mut s = 0.0f32;
    let k = std::f32::consts::TAU / curl.period_m;
    for i in 0..n {
        let centre = pos[i];
        if i > 0 {
            s += (centre - prev).length();
            let next = if i + 1 < n { pos[i + 1] } else { centre };
            let t_new = (next - prev).normalize_or(t);
            // Discrete parallel transport: project the old normal onto the new normal plane.
            b1 = (b1 - b1.dot(t_new) * t_new).normalize_or(t_new.any_orthonormal_vector());
            t = t_new;
        }
        prev = centre;
        let b2 = t.cross(b1);
        let r = curl.radius_m * (s / RAMP_M).min(1.0);
        let a = k * s + phase;
        pos[i] = centre + r * (a.cos() * b1 + a.sin() * b2);
    }
}
