use glam::{Vec2, Vec3};
use proptest::prelude::*;

use super::*;
use crate::raster::camera::Camera;
use crate::raster::lines::bins::{BAND_ROWS, band_key};
use crate::raster::lines::composite::{Band, composite};
use crate::raster::lines::fibers::Fibers;
use crate::raster::lines::fragment::{BandSegs, Emitted, Rows, emit_fragments};
use crate::raster::lines::params::Params;
use crate::raster::lines::pixel_runs::{band_colors, sort_by_pixel};
use crate::raster::lines::polyline::{LineWidth, Polylines};
use crate::raster::lines::segment::setup_segment;

const W: usize = 64;
const H: usize = 32;

/// One band drawn twice: as the raster draws it (hidden hair dropped), and from every
/// fragment each segment emits on its own (nothing can hide anything) in the same order.
/// Returns both images (colour and coverage bits) and both fragment counts, and how many
/// segments the band's final state says its tiles hide.
struct Drawn {
    culled: Vec<u32>,
    every: Vec<u32>,
    kept: usize,
    emitted: usize,
    tile_hidden: usize,
}

/// Lines of `per_line` points from `points`, `width_m` wide (projected, at least half a
/// pixel) at `opacity`, over an opaque depth of `depth_m` on the left half of the image
/// (background on the right).
fn draw(points: &[Vec3], per_line: usize, width_m: f32, opacity: f32, depth_m: f32) -> Drawn {
    let cam = Camera::look_at(
        Vec3::new(0.0, 0.0, 2.0),
        Vec3::ZERO,
        Vec3::Y,
        0.6,
        W as u32,
        H as u32,
    );
    let colors: Vec<Vec3> = (0..points.len())
        .map(|i| Vec3::new((i % 7) as f32 / 7.0, (i % 5) as f32 / 5.0, 0.3))
        .collect();
    let widths = vec![width_m; points.len()];
    let lines = Polylines {
        points,
        colors: &colors,
        widths_m: &widths,
        points_per_line: per_line,
        bundle: None,
    };
    let params = Params {
        view: cam.view(),
        width_model: LineWidth::Projected { min_px: 0.5 },
        opacity,
        width: W,
        height: H,
        bundle: None,
    };
    let depth: Vec<f32> = (0..W * H)
        .map(|i| {
            if i % W < W / 2 {
                depth_m
            } else {
                f32::INFINITY
            }
        })
        .collect();
    let mut colors = vec![[Vec3::ZERO; 2]; lines.segment_count()];
    let segs_all: Vec<Seg> = (0..lines.segment_count())
        .filter_map(|k| {
            let (s, _, c) = setup_segment(&params, &lines, k)?;
            colors[k] = c;
            Some(s)
        })
        .collect();
    let fibers: Vec<Fibers> = Vec::new();
    let mut drawn = Drawn {
        culled: Vec::new(),
        every: Vec::new(),
        kept: 0,
        emitted: 0,
        tile_hidden: 0,
    };
    for b in 0..H / BAND_ROWS {
        let (r0, r1) = (b * BAND_ROWS, (b + 1) * BAND_ROWS);
        let segs: Vec<Seg> = segs_all
            .iter()
            .filter(|s| (s.row_lo as usize) < r1 && s.row_hi as usize >= r0)
            .copied()
            .collect();
        let mut keys: Vec<u64> = segs
            .iter()
            .enumerate()
            .map(|(i, s)| band_key(s, i))
            .collect();
        keys.sort_unstable();
        let rows = r0 * W..r1 * W;
        let mut images = Vec::new();
        for cull in [true, false] {
            let (mut color, mut coverage) = (vec![Vec3::splat(0.1); W * H], vec![0.0; W * H]);
            let band = Band {
                color: &mut color[rows.clone()],
                depth: &depth[rows.clone()],
                coverage: &mut coverage[rows.clone()],
            };
            let mut hiding = Hiding::default();
            let mut out = Emitted::default();
            let band_rows = Rows {
                row0: r0,
                depth: band.depth,
            };
            if cull {
                emit_fragments(
                    &params,
                    BandSegs {
                        segs: &segs,
                        keys: &keys,
                        fibers: &fibers,
                    },
                    band_rows,
                    &mut hiding,
                    &mut out,
                    None,
                );
                drawn.kept += out.frags.len();
                drawn.tile_hidden += segs.iter().filter(|s| hiding.hides(s)).count();
            } else {
                // Near to far, as the raster emits, each segment alone (the hiding is
                // reset for each, and the fragments appended).
                for &k in keys.iter().rev() {
                    emit_fragments(
                        &params,
                        BandSegs {
                            segs: &segs,
                            keys: &[k],
                            fibers: &fibers,
                        },
                        band_rows,
                        &mut hiding,
                        &mut out,
                        None,
                    );
                }
                drawn.emitted += out.frags.len();
            }
            let (mut sorted, mut starts) = (Vec::new(), Vec::new());
            let mut band_table = Vec::new();
            band_colors(&out.ids, &colors, &mut band_table);
            sort_by_pixel(
                &out.frags,
                &band_table,
                &mut sorted,
                &mut starts,
                band.color.len(),
            );
            composite(&mut sorted, &starts, &mut Vec::new(), &mut Vec::new(), band);
            let bits: Vec<u32> = color[rows.clone()]
                .iter()
                .flat_map(|c| c.to_array())
                .chain(coverage[rows.clone()].iter().copied())
                .map(f32::to_bits)
                .collect();
            images.push(bits);
        }
        drawn.culled.extend_from_slice(&images[0]);
        drawn.every.extend_from_slice(&images[1]);
    }
    drawn
}

/// A thick fan of lines over one spot, some in front of the solid and some behind it, and a
/// curtain of lines in front of them: dropping the hidden hair leaves every pixel's colour
/// and coverage the same to the bit, while it drops over a quarter of the fragments and
/// whole segments.
#[test]
fn dropping_hidden_hair_changes_no_bit() {
    let per_line = 5;
    let mut points = Vec::new();
    for l in 0..60 {
        let a = l as f32 * 0.37;
        let z = 0.3 - 0.01 * l as f32;
        let c = Vec2::new(0.05 * a.cos(), 0.05 * a.sin());
        for i in 0..per_line {
            let t = i as f32 / (per_line - 1) as f32 - 0.5;
            points.push(Vec3::new(
                c.x + 0.5 * t * a.sin(),
                c.y - 0.4 * t * a.cos(),
                z + 0.05 * t,
            ));
        }
    }
    // A curtain of opaque lines side by side in front of the upper half hides whole tiles.
    for j in 0..19 {
        let y = -0.02 + 0.03 * j as f32;
        for i in 0..per_line {
            let x = -1.0 + 2.0 * i as f32 / (per_line - 1) as f32;
            points.push(Vec3::new(x, y, 0.5));
        }
    }
    let d = draw(&points, per_line, 0.12, 1.0, 1.9);
    assert_eq!(d.culled, d.every);
    assert!(
        4 * d.kept < 3 * d.emitted,
        "kept {} of {}",
        d.kept,
        d.emitted
    );
    assert!(d.tile_hidden > 0, "no segment behind wholly hidden tiles");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    /// Random lines, widths and opacities, near and far, partly behind the solid: the
    /// same bits with and without dropping what nearer hair hides.
    #[test]
    fn same_bits_for_random_hair(
        raw in prop::collection::vec((-0.4f32..0.4, -0.3f32..0.3, -0.5f32..0.5), 8..80),
        width_mm in 0.1f32..150.0,
        opacity in 0.05f32..1.0,
        solid_m in 1.5f32..2.6,
    ) {
        let per_line = 4;
        let n = raw.len() / per_line * per_line;
        let points: Vec<Vec3> = raw[..n].iter().map(|&(x, y, z)| Vec3::new(x, y, z)).collect();
        let d = draw(&points, per_line, width_mm * 1e-3, opacity, solid_m);
        prop_assert_eq!(d.culled, d.every);
    }
}
