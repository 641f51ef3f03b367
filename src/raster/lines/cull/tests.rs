use glam::{Vec2, Vec3};
use proptest::prelude::*;

use super::*;
use crate::raster::camera::Camera;
use crate::raster::lines::bundle::{Bundle, Profiles};
use crate::raster::lines::composite::Band;
use crate::raster::lines::fibers::Fibers;
use crate::raster::lines::fragment::{BandSegs, Emitted, Rows, emit_fragments};
use crate::raster::lines::params::Params;
use crate::raster::lines::polyline::{LineWidth, Polylines};
use crate::raster::lines::segment::setup_segment;

const W: usize = 96;
const H: usize = 64;

/// Eye on +Z looking at the origin, 0.9 rad vertical fov, W × H.
fn camera() -> Camera {
    Camera::look_at(
        Vec3::new(0.0, 0.0, 2.0),
        Vec3::ZERO,
        Vec3::Y,
        0.9,
        W as u32,
        H as u32,
    )
}

/// Opaque depth per 4 × 4 block from `blocks` (row-major, 24 × 16 of them, smaller than
/// a tile so a tile mixes depths); `None` is background.
fn depth_of(blocks: &[Option<f32>]) -> Vec<f32> {
    (0..W * H)
        .map(|i| {
            let (x, y) = (i % W, i / W);
            blocks[(y / 4) * (W / 4) + x / 4].unwrap_or(f32::INFINITY)
        })
        .collect()
}

/// For every segment of one polyline and every band: when [`FarDepth::hides`] drops it,
/// the pixel loop would have emitted no fragment from it. Returns how many (segment,
/// band) pairs were dropped and how many were not.
fn check(points: &[Vec3], width_m: f32, bundle: bool, depth: &[f32]) -> (usize, usize) {
    let cam = camera();
    let disc: Vec<Vec2> = (0..12)
        .map(|k| {
            let (r, a) = (((k as f32 + 0.5) / 12.0).sqrt(), k as f32 * 2.4);
            Vec2::new(r * a.cos(), r * a.sin())
        })
        .collect();
    let colors = vec![Vec3::splat(0.5); points.len()];
    let widths = vec![width_m; points.len()];
    let lines = Polylines {
        points,
        colors: &colors,
        widths_m: &widths,
        points_per_line: points.len(),
        bundle: bundle.then_some(Bundle {
            radius_m: width_m,
            fiber_radius_m: width_m / 40.0,
            points: &disc,
        }),
    };
    let mut profiles = Profiles::default();
    let with_bundle = lines.bundle.is_some_and(|b| profiles.prepare(&b));
    let params = Params {
        view: cam.view(),
        width_model: LineWidth::Projected { min_px: 1.0 },
        opacity: 1.0,
        width: W,
        height: H,
        bundle: with_bundle.then_some(&profiles),
    };
    let mut fibers = vec![Fibers::default(); points.len()];
    let (mut color, mut coverage) = (vec![Vec3::ZERO; W * H], vec![0.0; W * H]);
    let (mut dropped, mut kept) = (0, 0);
    let mut out = Emitted::default();
    for k in 0..points.len() - 1 {
        let Some((seg, f, _)) = setup_segment(&params, &lines, k) else {
            continue;
        };
        fibers[k] = f;
        for b in (seg.row_lo as usize / 16)..=(seg.row_hi as usize / 16) {
            let rows = b * 16 * W..((b + 1) * 16 * W).min(W * H);
            let mut far = FarDepth::default();
            far.build(&depth[rows.clone()], W);
            let band = Band {
                color: &mut color[rows.clone()],
                depth: &depth[rows.clone()],
                coverage: &mut coverage[rows],
            };
            out.clear();
            emit_fragments(
                &params,
                BandSegs {
                    segs: &[seg],
                    keys: &[0],
                    fibers: &fibers,
                },
                Rows {
                    row0: b * 16,
                    depth: band.depth,
                },
                &mut Default::default(),
                &mut out,
                None,
            );
            if far.hides(&seg) {
                assert!(
                    out.frags.is_empty(),
                    "segment {k} band {b}: dropped, yet {} fragments",
                    out.frags.len()
                );
                dropped += 1;
            } else {
                kept += 1;
            }
        }
    }
    (dropped, kept)
}

/// Hair behind a wall is dropped, hair in front of it or over a hole in it is not, and
/// whatever is dropped would have drawn nothing: the test can fail both ways.
#[test]
fn drops_exactly_hidden_hair_over_a_wall() {
    let line: Vec<Vec3> = (0..8)
        .map(|i| Vec3::new(-0.5 + i as f32 * 0.14, 0.05, 0.0))
        .collect();
    // The line lies at depth 2 m. A wall at 1.5 m hides it; one at 2.5 m does not.
    let (dropped, kept) = check(&line, 0.004, false, &depth_of(&[Some(1.5); 384]));
    assert!(dropped > 0 && kept == 0, "{dropped} {kept}");
    let (dropped, kept) = check(&line, 0.004, false, &depth_of(&[Some(2.5); 384]));
    assert!(dropped == 0 && kept > 0, "{dropped} {kept}");
    // A hole (background) under the line keeps the segments that reach it.
    let mut holed = vec![Some(1.5); 384];
    holed[7 * 24 + 12] = None;
    let (dropped, kept) = check(&line, 0.004, false, &depth_of(&holed));
    assert!(dropped > 0 && kept > 0, "{dropped} {kept}");
    // Wide bundles drawn as their fibres, with mitred joints, as well.
    let (dropped, kept) = check(&line, 0.05, true, &depth_of(&[Some(1.5); 384]));
    assert!(dropped > 0 && kept == 0, "{dropped} {kept}");
}

/// A wide diagonal line reaches past its end points' columns by its width: sweeping it
/// across walls and holes one tile wide finds ends that only the reach keeps.
#[test]
fn the_reach_covers_wide_diagonal_lines() {
    // Two tiles of wall in front of the line, then a tile of background.
    let blocks: Vec<Option<f32>> = (0..384)
        .map(|i| ((i % 24) / 4 % 3 != 2).then_some(1.5))
        .collect();
    let depth = depth_of(&blocks);
    let (mut dropped, mut kept) = (0, 0);
    for step in 0..200 {
        let x = -0.7 + step as f32 * 0.007;
        let line = [Vec3::new(x, -0.1, 0.0), Vec3::new(x + 0.08, -0.02, 0.0)];
        let (d, k) = check(&line, 0.06, false, &depth);
        (dropped, kept) = (dropped + d, kept + k);
    }
    assert!(dropped > 0 && kept > 0, "{dropped} {kept}");
}

proptest! {
    /// Whatever is dropped draws nothing, for random polylines (thin, wide, bundles drawn
    /// as their fibres) over random blocks of opaque depth and background.
    #[test]
    fn dropped_segments_emit_no_fragment(
        pts in prop::collection::vec((-0.8f32..0.8, -0.6f32..0.6, -1.2f32..0.9), 2..8),
        width_m in 0.0005f32..0.08,
        bundle in any::<bool>(),
        blocks in prop::collection::vec(prop::option::weighted(0.95, 0.5f32..4.0), 384),
    ) {
        let points: Vec<Vec3> = pts.into_iter().map(|(x, y, z)| Vec3::new(x, y, z)).collect();
        check(&points, width_m, bundle, &depth_of(&blocks));
    }
}

/// With no tiles (nothing built) every segment is kept: never drop what might show.
#[test]
fn empty_band_drops_nothing() {
    let far = FarDepth::default();
    let cam = camera();
    let pts = [Vec3::ZERO, Vec3::X * 0.1];
    let lines = Polylines {
        points: &pts,
        colors: &[Vec3::ONE; 2],
        widths_m: &[],
        points_per_line: 2,
        bundle: None,
    };
    let params = Params {
        view: cam.view(),
        width_model: LineWidth::Pixels(1.0),
        opacity: 1.0,
        width: W,
        height: H,
        bundle: None,
    };
    let (seg, _, _) = setup_segment(&params, &lines, 0).expect("on screen");
    assert!(!far.hides(&seg));
}
