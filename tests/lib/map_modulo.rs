//! Bertails 2005 §2.2: the modulo-indexed map does not care where the hair is. Translating the
//! whole scene by whole cells (also across the wrap at N cells) must give the same per-vertex
//! light; other offsets change only how the trilinear filter samples the hair.

use crate::common::*;
use glam::Vec3;
use wisp::hairstyle::Hairstyle;
use wisp::map::{LightFrame, MapGeometry};

fn lookups(
    geo: &wisp::interp::StrandGeometry,
    offset: Vec3,
    light: Vec3,
    geom: MapGeometry,
) -> Vec<[f32; 7]> {
    let fiber = default_fiber();
    let mut moved = geo.clone();
    for p in &mut moved.positions {
        *p += offset;
    }
    let map = build_map(&moved, &fiber, geom, light, 30.0);
    moved
        .positions
        .iter()
        .map(|p| {
            let l = map.light_at(*p);
            [
                l.direct_fraction,
                l.tf.x,
                l.tf.y,
                l.tf.z,
                l.sigma_f2.x,
                l.sigma_f2.y,
                l.sigma_f2.z,
            ]
        })
        .collect()
}

#[test]
fn whole_cell_translations_give_identical_light_also_across_the_wrap() {
    // Exact arithmetic by construction: positions on a 2^-16 m grid, a power-of-two cell
    // (2^-6 m = 15.6 mm, N = 64: a 1 m map), light along -Y (whose frame axes are exactly ±X,
    // ±Z), and offsets of whole cells. Every sum, product and floor is then exact in f32, so
    // any difference would come from the map itself.
    let style = Hairstyle::default_smooth();
    let mut geo = rest_strands(&style);
    for p in &mut geo.positions {
        *p = (*p * 65536.0).round() / 65536.0;
    }
    let light = Vec3::NEG_Y;
    let frame = LightFrame::new(light);
    let geom = MapGeometry {
        n: 64,
        ds_m: 1.0 / 64.0,
        lateral: 1,
    };
    let base = lookups(&geo, Vec3::ZERO, light, geom);
    let n = geom.n as f32;
    for cells in [
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(3.0, -7.0, 5.0),
        Vec3::new(n / 2.0 + 3.0, n - 1.0, -(n + 5.0)),
        Vec3::new(2.0 * n, 0.0, 3.0 * n),
    ] {
        let offset = frame.to_world(cells * geom.ds_m);
        let moved = lookups(&geo, offset, light, geom);
        assert!(base == moved, "offset {cells} cells changed the light");
    }
}

#[test]
fn whole_cell_translations_under_oblique_light_differ_only_by_rounding() {
    // With an oblique light the offset is not representable, so a few samples lying within
    // ~1e-7 m of a cell face round into the neighbouring cell. The mean difference stays at
    // rounding level; the worst single vertex is bounded by one sample's share of a cell.
    let style = Hairstyle::default_smooth();
    let geo = rest_strands(&style);
    let light = Vec3::new(0.4, -0.8, -0.45);
    let frame = LightFrame::new(light);
    let geom = MapGeometry::with_resolution(
        MapGeometry::span_m(style.max_length_m(), style.head_size_m()),
        64,
    );
    let base = lookups(&geo, Vec3::ZERO, light, geom);
    let n = geom.n as f32;
    let offset = frame.to_world(Vec3::new(n / 2.0 + 3.0, n - 1.0, -(n + 5.0)) * geom.ds_m);
    let moved = lookups(&geo, offset, light, geom);
    let (mut worst, mut sum) = (0.0f32, 0.0f64);
    for (a, b) in base.iter().zip(&moved) {
        let d = (a[1] - b[1]).abs();
        worst = worst.max(d);
        sum += d as f64;
    }
    let mean = sum / base.len() as f64;
    println!("oblique whole-cell offset: mean |dTf| = {mean:.2e}, worst {worst:.2e}");
    assert!(mean < 1e-4, "mean {mean}");
    assert!(worst < 0.05, "worst {worst}");
}

#[test]
fn fractional_offsets_stay_within_the_filter_error() {
    let style = Hairstyle::default_smooth();
    let geo = rest_strands(&style);
    let light = Vec3::new(0.4, -0.8, -0.45);
    let frame = LightFrame::new(light);
    let geom = MapGeometry::with_resolution(
        MapGeometry::span_m(style.max_length_m(), style.head_size_m()),
        64,
    );
    let base = lookups(&geo, Vec3::ZERO, light, geom);
    // Half a cell along every axis is the worst case for a cell-based filter: the samples fall
    // in different cells and the filter blends different neighbours. Documented bound (measured
    // on this preset at N = 64, ds = 15 mm: mean |ΔTf| = 0.047, 99th percentile 0.31): mean
    // below 0.06, 99th percentile below 0.4.
    let offset = frame.to_world(Vec3::splat(0.5) * geom.ds_m);
    let moved = lookups(&geo, offset, light, geom);
    let mut diffs: Vec<f32> = base
        .iter()
        .zip(&moved)
        .map(|(a, b)| (a[1] - b[1]).abs())
        .collect();
    let mean = diffs.iter().sum::<f32>() / diffs.len() as f32;
    diffs.sort_by(f32::total_cmp);
    let p99 = diffs[diffs.len() * 99 / 100];
    println!("half-cell offset: mean |dTf| = {mean:.4}, p99 = {p99:.4}");
    assert!(mean < 0.06, "mean {mean}");
    assert!(p99 < 0.4, "p99 {p99}");
    assert!(
        mean > 0.0,
        "a half-cell shift must change the sampling somewhere"
    );
}
