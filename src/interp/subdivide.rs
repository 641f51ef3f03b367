//! Segments cut into pieces: the same polyline with evenly spaced points added along each
//! segment, so that every stage that reads hair point by point (map fill, contact shadows,
//! shading) reads it more often along the strand while the drawn geometry stays the same.
//!
//! n points cut into m pieces a segment become (n − 1)·m + 1: point i·m + k is
//! p_i + (k/m)(p_{i+1} − p_i), k = 0..m, in place from the tip down.

use glam::Vec3;

/// Points of a strand whose `coarse` points' segments are each cut into `pieces`.
pub fn subdivided_points(coarse: usize, pieces: usize) -> usize {
    if coarse < 2 {
        coarse
    } else {
        (coarse - 1) * pieces.max(1) + 1
    }
}

/// Cuts each segment of the polyline held in `pos[..coarse]` into `pieces` equal straight
/// pieces, in place: `pos` (of [`subdivided_points`]`(coarse, pieces)` points) then holds the
/// same polyline with `pieces − 1` points added evenly along each segment. The drawn geometry
/// is unchanged; what changes is that every stage reading points (map fill, contact shadows,
/// shading) reads them `pieces` times as often along the hair. The raster interpolates a
/// segment's colour between its ends, so light that varies along a segment (a fibre crossing
/// in front of its middle, a map cell boundary) is only seen where a point is.
pub fn subdivide_in_place(pos: &mut [Vec3], coarse: usize, pieces: usize) {
    let pieces = pieces.max(1);
    if pieces == 1 || coarse < 2 {
        return;
    }
    debug_assert_eq!(pos.len(), subdivided_points(coarse, pieces));
    // From the tip down, so no groom point is overwritten before it is read (point i moves
    // to i × pieces ≥ i).
    for i in (1..coarse).rev() {
        let (a, b) = (pos[i - 1], pos[i]);
        pos[i * pieces] = b;
        for k in 1..pieces {
            pos[(i - 1) * pieces + k] = a.lerp(b, k as f32 / pieces as f32);
        }
    }
}

#[cfg(test)]
mod tests;
