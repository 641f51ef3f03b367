//! Per-strand rest offsets: how an imported render strand departs from its wisp's
//! interpolation, stored in a frame that moves with the guides.
//!
//! An imported strand is not exactly a blend of its wisp's three guides. Its difference from
//! the blend, point by point, is kept in a local frame of the blended centre line: the unit
//! tangent `t`, a normal `b1` that starts as the vector between the wisp's first two guide
//! roots (it turns with the head) and is carried along the strand by projection onto each new
//! normal plane (the discrete parallel transport of the curls, `curl.rs`), and
//! `b2 = t × b1`. The offset `(x, y, z)` means `x·b1 + y·b2 + z·t`. At rest the frame is
//! computed the same way from the rest guides, so adding the offsets back reproduces the
//! file's strand exactly (to rounding); when the guides move and bend, the offsets turn with
//! them.

use glam::Vec3;

/// Walks the transported frame along the centre line `centre` and calls `f(i, b1, b2, t)` at
/// every point. `reference` is the root's normal hint (need not be unit or normal).
#[inline]
fn for_each_frame(centre: &[Vec3], reference: Vec3, mut f: impl FnMut(usize, Vec3, Vec3, Vec3)) {
    let n = centre.len();
    if n == 0 {
        return;
    }
    let first = if n > 1 {
        centre[1] - centre[0]
    } else {
        Vec3::NEG_Y
    };
    let mut t = first.normalize_or(Vec3::NEG_Y);
    let mut b1 = (reference - reference.dot(t) * t).normalize_or(t.any_orthonormal_vector());
    for i in 0..n {
        if i > 0 {
            let prev = centre[i - 1];
            let next = if i + 1 < n { centre[i + 1] } else { centre[i] };
            let t_new = (next - prev).normalize_or(t);
            b1 = (b1 - b1.dot(t_new) * t_new).normalize_or(t_new.any_orthonormal_vector());
            t = t_new;
        }
        f(i, b1, t.cross(b1), t);
    }
}

/// Adds the local `offsets` (one per point) to the centre line `pos`, in place.
pub fn apply_rest_offsets(pos: &mut [Vec3], reference: Vec3, offsets: &[Vec3]) {
    let n = pos.len().min(offsets.len());
    // The frame is read from the centre line before it is moved: keep the original points of
    // the previous and the current index (the next one is not yet changed).
    let mut prev_centre = Vec3::ZERO;
    let mut t = Vec3::NEG_Y;
    let mut b1 = Vec3::X;
    for i in 0..n {
        let centre = pos[i];
        if i == 0 {
            let first = if n > 1 { pos[1] - pos[0] } else { Vec3::NEG_Y };
            t = first.normalize_or(Vec3::NEG_Y);
            b1 = (reference - reference.dot(t) * t).normalize_or(t.any_orthonormal_vector());
        } else {
            let next = if i + 1 < n { pos[i + 1] } else { centre };
            let t_new = (next - prev_centre).normalize_or(t);
            b1 = (b1 - b1.dot(t_new) * t_new).normalize_or(t_new.any_orthonormal_vector());
            t = t_new;
        }
        prev_centre = centre;
        let o = offsets[i];
        pos[i] = centre + o.x * b1 + o.y * t.cross(b1) + o.z * t;
    }
}

/// The local offsets that take the centre line `centre` onto `target` (same length): the
/// inverse of [`apply_rest_offsets`].
pub fn rest_offsets_of(centre: &[Vec3], reference: Vec3, target: &[Vec3], out: &mut [Vec3]) {
    for_each_frame(centre, reference, |i, b1, b2, t| {
        if let (Some(p), Some(o)) = (target.get(i), out.get_mut(i)) {
            let d = *p - centre[i];
            *o = Vec3::new(d.dot(b1), d.dot(b2), d.dot(t));
        }
    });
}

#[cfg(test)]
mod tests;
