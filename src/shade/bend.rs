//! Bent strands: the directions a vertex's colour stands for.
//!
//! The raster draws a render strand as straight segments between its points and colours each
//! linearly between its two vertices, so a vertex's colour covers half a segment to each side,
//! along the segment before it and the segment after it. Shaded once at its central tangent,
//! between the two, a vertex stands for a direction the drawn strand does not have there.
//! Where the strand curves evenly this does not bias the picture: the vertices' tangents are
//! the segments' directions shifted half a step along the curve, the same directions drawn a
//! little further on. At a corner it does: the dense scene's strands leave the scalp and turn
//! 60–120° within one or two segments onto the head, all alike, so the crown's vertices sample
//! directions between the segments', phase-locked, and miss the highlights of the segments the
//! path tracer draws. There the vertices' fibre term read 0.93–0.95 of the exact far field at
//! the same hits, and 0.98 with this module (the rest of the picture 0.98–1.00 before and
//! after); side-lit single scattering of dense brown went from 0.89 / 0.88 / 0.87 to
//! 0.91 / 0.91 / 0.90 of the path tracer (ACCURACY.md §2, "Bent strands").
//!
//! So a corner is shaded along each of its two segments and the two colours are averaged,
//! with the light it receives looked up once (the light depends on the point, not the
//! direction). With every inner vertex so shaded and equal segments, the raster's integral
//! along a strand is exactly the sum of each segment shaded along its own direction
//! (`tests/lib/shade_bend.rs`). A vertex is a corner where its segments turn by more than β_R
//! (below that its half turn is within the narrowest lobe's width, TT's β_R/2 in θh:
//! Marschner 2003 Table 1, the Chiang model's v₀/4 in `fiber::chiang`) and by more than twice
//! the smaller of its neighbours' turns (a strand's end counts as straight). Rejected,
//! measured: every vertex turning by more than β_R, corner or not, read the same table within
//! 0.01 and cost the curly preset, whose curls turn about 21° per segment, 45 ms more shading
//! a frame instead of 9 (BENCHMARKS.md).

use glam::Vec3;

/// The fibre directions one vertex's colour averages over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Directions {
    /// Straight enough: the vertex's tangent alone.
    One(Vec3),
    /// Bent: the directions of the segment before and the segment after the vertex (unit).
    Two(Vec3, Vec3),
}

/// When a vertex counts as bent (module doc): the cosine of the largest angle between its two
/// segments that one evaluation at its tangent stands for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct BendTest {
    cos_max_bend: f32,
}

impl BendTest {
    /// For a fibre whose R lobe has longitudinal width `beta_r_deg` (degrees, validated in
    /// (0.5°, 45°)): two directions where the segments turn by more than β_R.
    pub(super) fn for_beta_r_deg(beta_r_deg: f32) -> Self {
        let max_bend_rad = beta_r_deg.to_radians();
        Self {
            cos_max_bend: if max_bend_rad.is_finite() {
                max_bend_rad.clamp(0.0, std::f32::consts::FRAC_PI_2).cos()
            } else {
                1.0
            },
        }
    }

    /// The directions of vertex `i` of render strands of `points_per_strand` points each,
    /// `tangent` its central tangent, each segment of the groom cut into `pieces` (0 or 1:
    /// none; the added points lie on straight segments, so only every piece-th point can
    /// turn, and the groom's neighbours are that many points away). Strand ends, degenerate
    /// segments and non-finite points have one direction, the tangent.
    #[inline]
    pub(super) fn directions(
        &self,
        positions: &[Vec3],
        tangent: Vec3,
        points_per_strand: usize,
        pieces: usize,
        i: usize,
    ) -> Directions {
        let s = pieces.max(1);
        if points_per_strand < 3 {
            return Directions::One(tangent);
        }
        let k = i % points_per_strand;
        if !k.is_multiple_of(s) || k < s || k + s >= points_per_strand {
            return Directions::One(tangent);
        }
        let (Some(&prev), Some(&here), Some(&next)) =
            (positions.get(i - s), positions.get(i), positions.get(i + s))
        else {
            return Directions::One(tangent);
        };
        let before = (here - prev).normalize_or_zero();
        let after = (next - here).normalize_or_zero();
        if before == Vec3::ZERO || after == Vec3::ZERO {
            return Directions::One(tangent);
        }
        // A non-finite point keeps its one direction (NaN is not less).
        let cos_turn = before.dot(after);
        if cos_turn.is_nan() || cos_turn >= self.cos_max_bend {
            return Directions::One(tangent);
        }
        // A corner: the turn here is more than twice the smaller of its neighbours' turns (a
        // strand's end counts as straight). Where the strand curves evenly the vertices'
        // tangents are its segments' directions shifted half a step along the curve, the
        // same directions drawn in other places, and one evaluation stands (module doc).
        // In cosines, with c the larger neighbour cosine: turn > 2·acos c ⇔ c > 0 and
        // cos(turn) < 2c² − 1.
        // k ≥ 2s puts i − 2s on this strand (and i − s exists, so it does too).
        let cos_before = if k >= 2 * s {
            cos_or_straight((prev - positions[i - 2 * s]).normalize_or_zero(), before)
        } else {
            1.0
        };
        let cos_after = match positions.get(i + 2 * s) {
            Some(&n2) if k + 2 * s < points_per_strand => {
                cos_or_straight(after, (n2 - next).normalize_or_zero())
            }
            _ => 1.0,
        };
        let c = cos_before.max(cos_after);
        if c > 0.0 && cos_turn < 2.0 * c * c - 1.0 {
            Directions::Two(before, after)
        } else {
            Directions::One(tangent)
        }
    }
}

/// The cosine of the turn between two unit directions; 1 (straight) when either is zero.
#[inline]
fn cos_or_straight(a: Vec3, b: Vec3) -> f32 {
    if a == Vec3::ZERO || b == Vec3::ZERO {
        1.0
    } else {
        a.dot(b).clamp(-1.0, 1.0)
    }
}

#[cfg(test)]
mod tests;
