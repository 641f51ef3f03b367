//! The render strands as the raster draws them: each point's physical width and the bundle a
//! strand of several fibres stands for.

use glam::{Vec2, Vec3};

use crate::hairstyle::Hairstyle;
use crate::interp::StrandGeometry;
use crate::raster::{Bundle, Camera, Framebuffer, LineScratch, LineStyle, Polylines};

/// A hair line draw: `raster::draw_polylines` or `raster::draw_seen_polylines`.
pub(super) type DrawLines = fn(&mut Framebuffer, &Camera, &Polylines, &LineStyle, &mut LineScratch);

/// Each point's physical width in metres into `widths_m`: its strand's F fibres of radius r
/// side by side (F·2r, the most they can cover), times the share of fibres left there (tapered
/// tips thin).
pub(super) fn strand_widths_m(
    style: &Hairstyle,
    strands: &StrandGeometry,
    widths_m: &mut Vec<f32>,
) {
    let strand_width_m = style.strands.fibers_per_strand * 2.0 * style.fiber.radius_m;
    widths_m.clear();
    widths_m.extend(
        strands
            .fiber_share
            .iter()
            .map(|share| strand_width_m * share),
    );
}

/// The render strands as the raster draws them: their points, colours and physical widths, and
/// with F ≥ 2 fibres a bundle whose fibres spread over half the strand spacing (as the map's
/// surface texture and the exact reference spread them).
pub(super) fn hair_lines<'a>(
    strands: &'a StrandGeometry,
    colors: &'a [Vec3],
    widths_m: &'a [f32],
    bundle_points: &'a [Vec2],
    style: &Hairstyle,
) -> Polylines<'a> {
    Polylines {
        points: &strands.positions,
        colors,
        widths_m,
        points_per_line: strands.points_per_strand,
        bundle: (!bundle_points.is_empty()).then_some(Bundle {
            radius_m: 0.5 * style.strand_spacing_m(),
            fiber_radius_m: style.fiber.radius_m,
            points: bundle_points,
        }),
    }
}
