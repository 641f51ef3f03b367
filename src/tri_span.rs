//! Which centres of a row of pixels or texels a triangle can cover: the span both of wisp's
//! triangle rasters (the character's mesh on screen, `raster::mesh`; the solids across the
//! light, `map::occluders`) visit instead of the triangle's whole box.
//!
//! Both rasters test a centre with edge functions, so a span must hold every centre that
//! test accepts, rounding included, for the span to change no bit. The span is the
//! triangle's exact extent over the row and [`MARGIN`] rows either side, widened by
//! [`MARGIN`]: a centre q outside it lies at least [`MARGIN`] from the triangle. Some edge
//! (a, b) then separates q from it, with an edge function of d·L (d: q's distance from that
//! edge's line, L: the edge's length) against a rounding of about 2ε|a − q||b − q|
//! (ε = 2⁻²⁴). The tight case is q past a sharp corner v of angle θ, where d ≈ |v − q|·sin(θ/2)
//! and the rounding ≈ 2ε|v − q|·L: it is rejected as long as sin(θ/2) > 2ε ≈ 1.2e-7. A
//! triangle whose edges are all at least [`MIN_EDGE`] and whose corners lie within
//! [`MAX_COORD`] of the origin has sin θ ≥ [`MIN_EDGE`] over its longest edge (law of
//! sines), so sin(θ/2) ≥ 5e-7: four times that. Other triangles ([`narrowable`] says no) keep
//! their whole box. Each raster's tests hold its old whole-box loop as reference, bit for
//! bit, on random, sliver and far-off triangles.

use glam::Vec2;

/// Units (pixels or texels) a span adds on either side of the triangle's extent, and rows
/// either side of the row whose part of the triangle it takes.
const MARGIN: f32 = 2.0;
/// Corners farther than this from the origin (in pixels or texels) keep the whole box.
const MAX_COORD: f32 = 16_384.0;
/// A triangle with an edge shorter than this keeps the whole box.
const MIN_EDGE: f32 = 0.05;

/// Whether a triangle with corners `p` may be rasterised by spans (moderate coordinates, no
/// edge of almost no length).
pub(crate) fn narrowable(p: [Vec2; 3]) -> bool {
    let [a, b, c] = p;
    p.iter().all(|q| q.abs().max_element() < MAX_COORD)
        && [b - a, c - b, a - c].iter().all(|e| e.length() >= MIN_EDGE)
}

/// The span of a row whose centres have `.x` in `[from, to]`: the `.y` range that every
/// centre the triangle's edge functions can accept lies in (see the module doc), that is its
/// extent over `[from − MARGIN, to + MARGIN]` widened by [`MARGIN`] either side; `None`
/// where the triangle has no part there. Only for [`narrowable`] triangles.
pub(crate) fn span(p: [Vec2; 3], (from, to): (f32, f32)) -> Option<(f32, f32)> {
    extent_across(p, (from - MARGIN, to + MARGIN)).map(|(lo, hi)| (lo - MARGIN, hi + MARGIN))
}

/// The range of `.y` that triangle `p` covers where `.x` lies in `[from, to]`, or `None`
/// where it has no part there. Its part there is the convex hull of its corners in the band
/// and its edges' crossings of the band's bounds, so the range is the extremes of those.
fn extent_across(p: [Vec2; 3], (from, to): (f32, f32)) -> Option<(f32, f32)> {
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for i in 0..3 {
        let (a, b) = (p[i], p[(i + 1) % 3]);
        let (start, end) = (a.x.min(b.x).max(from), a.x.max(b.x).min(to));
        if start > end {
            continue;
        }
        // The edge's .y over its part in the band; a level edge, or one too steep to
        // interpolate, gives its whole .y range, which holds that part.
        let slope = (b.y - a.y) / (b.x - a.x);
        let (u, v) = if slope.is_finite() {
            (a.y + (start - a.x) * slope, a.y + (end - a.x) * slope)
        } else {
            (a.y, b.y)
        };
        lo = lo.min(u.min(v));
        hi = hi.max(u.max(v));
    }
    (lo <= hi).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Every point of the triangle whose .x is in the band has its .y in the range
        /// (points drawn by barycentric weights; a hair of rounding allowed).
        #[test]
        fn the_extent_holds_every_point_of_the_band(
            p in prop::array::uniform3((-50.0f32..50.0, -50.0f32..50.0)),
            w in (0.0f32..1.0, 0.0f32..1.0),
            band in (0.0f32..3.0, 0.0f32..3.0),
        ) {
            let p = p.map(|(x, y)| Vec2::new(x, y));
            let (u, v) = if w.0 + w.1 > 1.0 { (1.0 - w.0, 1.0 - w.1) } else { w };
            let q = p[0] + (p[1] - p[0]) * u + (p[2] - p[0]) * v;
            let (from, to) = (q.x - band.0, q.x + band.1);
            let (lo, hi) = extent_across(p, (from, to)).expect("a point lies in the band");
            prop_assert!(q.y >= lo - 1e-3 && q.y <= hi + 1e-3, "{} not in {}..{}", q.y, lo, hi);
        }
    }

    /// Hand cases: a band missing the triangle, a level edge, a corner alone in the band.
    #[test]
    fn hand_cases() {
        let t = [
            Vec2::new(0.0, 0.0),
            Vec2::new(10.0, 0.0),
            Vec2::new(0.0, 10.0),
        ];
        assert_eq!(extent_across(t, (11.0, 12.0)), None);
        assert_eq!(extent_across(t, (0.0, 0.0)), Some((0.0, 10.0)));
        assert_eq!(extent_across(t, (5.0, 5.0)), Some((0.0, 5.0)));
        assert_eq!(extent_across(t, (9.0, 20.0)), Some((0.0, 1.0)));
        assert_eq!(span(t, (5.0, 6.0)), Some((-2.0, 9.0)));
        assert!(narrowable(t));
        assert!(!narrowable([t[0], t[0] + Vec2::new(0.01, 0.0), t[2]]));
        assert!(!narrowable([t[0], t[1], Vec2::new(0.0, 1e6)]));
    }
}
