//! Which centres of a row of pixels or texels a triangle can cover: the span both of wisp's
//! triangle rasters (the character's mesh on screen, `raster::solids::mesh`; the solids across the
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
mod tests;
