//! Scenes (issue 9): several lights, point lights through their angular map, scene files, and
//! golden images of each shader mode, a scene file and two lights.
//!
//! Golden images are small still frames (96 × 96, the smooth preset on a still head) compared
//! per channel with PNGs in `tests/golden/` within 2 levels of 255 (the frames are
//! deterministic on one machine; the slack absorbs a libm that rounds a transcendental
//! differently elsewhere). A diff image is written on failure; `WISP_UPDATE_GOLDEN=1` rewrites
//! them.

use crate::common;

use glam::{Affine3A, Vec3};
use wisp::accuracy::exact::Footprint;
use wisp::accuracy::{measure_map, sweep_geometries};
use wisp::engine::{Engine, EngineConfig};
use wisp::fiber::ShadingMode;
use wisp::hairstyle::Hairstyle;
use wisp::light::Light;
use wisp::map::{CountModel, LightMap, MapBuildInput, MapLight};
use wisp::motion::Motion;
use wisp::scene::SceneFile;

const SIDE: u32 = 96;
const TOLERANCE: u8 = 2;

fn still_engine(config: EngineConfig) -> Engine {
    Engine::new(
        Hairstyle::default_smooth(),
        Motion::still(Affine3A::IDENTITY),
        config,
    )
}

fn small() -> EngineConfig {
    EngineConfig::sized(SIDE, SIDE)
}

#[test]
fn golden_frames_of_each_shader_mode() {
    for (mode, name) in [
        (ShadingMode::DualScattering, "mode_dual_96.png"),
        (ShadingMode::SingleScattering, "mode_single_96.png"),
        (ShadingMode::KajiyaKay, "mode_kajiya_kay_96.png"),
    ] {
        let mut config = small();
        config.shading.mode = mode;
        let mut e = still_engine(config);
        let rgb = e.frame(0.0).to_srgb8();
        common::golden::assert_golden(name, SIDE, SIDE, &rgb, TOLERANCE);
    }
}

/// `tests/golden/two_lights.json`: a fixed camera, a directional and a point light, exposure.
fn two_light_scene() -> EngineConfig {
    let path = common::golden::golden_path("two_lights.json");
    let (_, scene) = SceneFile::load(&path).unwrap();
    EngineConfig::default().with_scene(&scene)
}

#[test]
fn golden_frame_of_a_scene_file_with_two_lights() {
    let config = two_light_scene();
    assert_eq!(config.scene.lights.len(), 2);
    let (w, h) = (config.scene.width, config.scene.height);
    let mut e = still_engine(config);
    let rgb = e.frame(0.0).to_srgb8();
    common::golden::assert_golden("two_lights_96.png", w, h, &rgb, TOLERANCE);
}

/// Light adds: with black background and no ambient, the frame of two lights is the sum of the
/// frames of each light alone (colours are premultiplied linear radiance and the coverage does
/// not depend on the light), to float rounding.
#[test]
fn two_lights_render_the_sum_of_each_alone() {
    let both = two_light_scene();
    let render = |lights: Vec<Light>| {
        let mut c = both.clone();
        c.scene.lights = lights;
        c.scene.ambient = Vec3::ZERO;
        c.scene.background = Vec3::ZERO;
        still_engine(c).frame(0.0).clone()
    };
    let ab = render(both.scene.lights.clone());
    let a = render(vec![both.scene.lights[0]]);
    let b = render(vec![both.scene.lights[1]]);
    let (mut worst, mut total) = (0.0f32, 0.0f32);
    for ((x, y), z) in ab.color.iter().zip(&a.color).zip(&b.color) {
        worst = worst.max((*x - (*y + *z)).abs().max_element());
        total += x.max_element();
    }
    assert!(total > 0.0);
    assert!(
        worst <= 1e-4 * (1.0 + total / ab.color.len() as f32),
        "{worst}"
    );
    assert_eq!(ab.coverage, a.coverage);
}

/// One frame with two lights (one a point light) is byte-identical on 1 and 2 threads.
#[test]
fn two_lights_are_deterministic_across_thread_counts() {
    let frame = |threads: usize| {
        common::on_threads(threads, || {
            still_engine(two_light_scene()).frame(0.0).to_srgb8()
        })
    };
    assert!(frame(1) == frame(2));
}

/// A point light far away is a directional light: at 1 km along the same direction (the
/// rays' spread over the hair is under 0.03°, the projection's lateral scale varies by under
/// 0.05% across it), the map reads what the directional map reads, up to the phase of its
/// slices along the light: no bias, and per point no more difference than moving the hair by a
/// fraction of a slice makes.
#[test]
fn a_far_point_light_reads_as_the_directional_light() {
    let style = Hairstyle::default_smooth();
    let geo = common::rest_strands(&style);
    let fiber = common::default_fiber();
    let travel = Vec3::new(-0.6, -0.5, -0.4).normalize();
    let geom = wisp::engine::map_geometry(&style, &EngineConfig::default().hair_map);
    let build = |light: MapLight| {
        let mut map = LightMap::new(geom, CountModel::Poisson);
        map.build(&MapBuildInput {
            positions: &geo.positions,
            tangents: &geo.tangents,
            lengths_m: &geo.lengths_m,
            fiber_share: &geo.fiber_share,
            fibers_per_strand: style.strands.fibers_per_strand,
            light,
            fiber: &fiber,
        });
        map
    };
    let directional = build(MapLight::Directional(travel));
    let point = build(MapLight::Point {
        position_m: -1000.0 * travel,
        aim_m: Vec3::ZERO,
    });
    // The same directional light with the hair moved along it by a fraction of a slice: the
    // point light's slices lie at another phase along the light (1 km is no whole number of
    // slices), and that alone moves single points.
    let shift = 0.37 * geom.ds_m * travel;
    let moved: Vec<Vec3> = geo.positions.iter().map(|p| *p + shift).collect();
    let mut shifted = LightMap::new(geom, CountModel::Poisson);
    shifted.build(&MapBuildInput {
        positions: &moved,
        tangents: &geo.tangents,
        lengths_m: &geo.lengths_m,
        fiber_share: &geo.fiber_share,
        fibers_per_strand: style.strands.fibers_per_strand,
        light: MapLight::Directional(travel),
        fiber: &fiber,
    });
    let (mut diff_point, mut diff_shift, mut bias, mut n, mut shadowed) = (0.0, 0.0, 0.0, 0, 0);
    for p in geo.positions.iter().step_by(7) {
        let (a, b, c) = (
            directional.light_at(*p),
            point.light_at(*p),
            shifted.light_at(*p + shift),
        );
        diff_point += (a.tf - b.tf).abs().element_sum() as f64 / 3.0;
        diff_shift += (a.tf - c.tf).abs().element_sum() as f64 / 3.0;
        bias += (b.tf - a.tf).element_sum() as f64 / 3.0;
        n += 1;
        shadowed += (a.direct_fraction < 0.5) as usize;
    }
    let (diff_point, diff_shift, bias) = (
        diff_point / n as f64,
        diff_shift / n as f64,
        bias / n as f64,
    );
    println!(
        "mean |ΔT_f|: far point light {diff_point:.5}, slice phase alone {diff_shift:.5}; bias {bias:+.5}"
    );
    assert!(
        shadowed > 100,
        "the test needs shadowed points ({shadowed})"
    );
    assert!(
        diff_point <= 1.5 * diff_shift + 1e-3,
        "{diff_point} vs {diff_shift}"
    );
    assert!(bias.abs() <= 0.002, "bias {bias}");
}

/// The point light's map against the exact reference (rays toward the light through explicit
/// fibres, `map::exact` in the same projection), on the smooth preset lit from 0.79 m behind
/// and to the left (ACCURACY.md, "Point lights": T_f MAE 0.0117, luminance ratio 0.994 at
/// 3,000 vertices × 128 rays). Bounds as the directional presets' (`map_accuracy.rs`):
/// MAE ≤ 0.02, overall bias within 0.01, shaded luminance within 3%.
#[test]
fn point_light_map_against_the_exact_reference() {
    let mut config = small();
    config.scene.lights = vec![Light::point(Vec3::new(-0.7, 0.2, -0.3), Vec3::ONE).unwrap()];
    let mut engine = still_engine(config);
    engine.frame(0.0);
    let fp = Footprint::Fibers { rays: 64 };
    let rows = measure_map(
        &engine,
        &sweep_geometries(&engine, &[]),
        1500,
        &fp,
        1,
        1,
        engine.hair_map.config.contact,
    )
    .rows;
    let row = rows.iter().find(|r| r.is_default).expect("default row");
    let c = &row.comparison;
    println!(
        "point light: MAE {:.4}, bias {:+.4}, luminance ratio {:.3}",
        c.mae, c.overall_bias, row.luminance_ratio
    );
    assert!(c.mae <= 0.02, "T_f MAE {}", c.mae);
    assert!(c.overall_bias.abs() <= 0.01, "bias {}", c.overall_bias);
    assert!(
        (row.luminance_ratio - 1.0).abs() <= 0.03,
        "luminance ratio {}",
        row.luminance_ratio
    );
}

/// No NaN or infinity reaches a pixel with a point light just outside the hair and one far
/// away, whatever the hair does (nearest hair at a few centimetres: the projection's scale is
/// largest there).
#[test]
fn point_lights_near_and_far_keep_pixels_finite() {
    let mut config = small();
    config.scene.lights = vec![
        Light::point(Vec3::new(0.0, 0.0, 0.42), Vec3::splat(0.5)).unwrap(),
        Light::point(Vec3::new(1e4, 1e4, 0.0), Vec3::splat(2e8)).unwrap(),
    ];
    let mut e = still_engine(config);
    let fb = e.frame(0.0);
    assert!(fb.color.iter().all(|c| c.is_finite()));
    assert!(fb.color.iter().any(|c| c.max_element() > 0.05));
}

/// The maps are kept when nothing they are made of changed (`frame::map_reuse`): on a still
/// head whose hair is at rest the second frame reuses them, and every frame is byte-identical
/// to a fresh engine's (which builds its maps), also after the light moved (the maps rebuild).
#[test]
fn reused_maps_give_the_same_frames_as_rebuilt_ones() {
    let mut e = still_engine(small());
    let first = e.frame(0.0).to_srgb8();
    assert!(!e.map_reused());
    let second = e.frame(1.0 / 30.0).to_srgb8();
    assert!(e.map_reused(), "the hair at rest did not move");
    assert!(first == second);
    let mut fresh = still_engine(small());
    fresh.run_up_to(1.0 / 30.0);
    assert!(fresh.frame(1.0 / 30.0).to_srgb8() == second);
    // Move the light: the maps must rebuild, and match a fresh engine lit that way.
    let turned = Light::directional(Vec3::new(0.5, -0.6, -0.4), Vec3::splat(6.0)).unwrap();
    e.scene.lights = vec![turned];
    let relit = e.frame(2.0 / 30.0).to_srgb8();
    assert!(!e.map_reused());
    let mut config = small();
    config.scene.lights = vec![turned];
    let mut fresh = still_engine(config);
    fresh.run_up_to(2.0 / 30.0);
    assert!(fresh.frame(2.0 / 30.0).to_srgb8() == relit);
}

/// Shading in map order (issue 12: vertices sorted by the map column they read, colours put
/// back) gives every vertex exactly the colour of shading them one by one in vertex order.
#[test]
fn shading_in_map_order_is_shading_in_vertex_order() {
    let mut e = Engine::new(
        Hairstyle::default_smooth(),
        Motion::default_dance(),
        EngineConfig::sized(64, 64),
    );
    e.frame(0.5);
    // A frame shades only the points the raster can show; this shades them all, in map order.
    e.shade();
    let eye = e.camera().eye();
    let r = e.fiber.params().radius_m;
    let tangents = e.strands().tangents.clone();
    let shadows = e.shadows();
    let mut natural = Vec::new();
    wisp::shade::shade_vertices_with(
        &e.fiber,
        &e.shading.lighting(&e.scene),
        eye,
        wisp::shade::VertexGeometry {
            positions: &e.strands().positions,
            tangents: &tangents,
            points_per_strand: e.strands().points_per_strand,
            segment_pieces: e.strands().segment_pieces,
        },
        |k, i, p| {
            let shadow = shadows.light(k).expect("a map per light");
            shadow.light_at_seen(p, eye - p, tangents[i], r)
        },
        &mut natural,
    );
    assert_eq!(natural.len(), e.colors().len());
    // Partly shadowed vertices exercise every branch of the lookup (cells, depth CDF, taps).
    let partial = e
        .strands()
        .positions
        .iter()
        .filter(|p| (0.05..0.95).contains(&shadows.light(0).expect("one light").light_at(**p).tf.x))
        .count();
    assert!(partial > 1000, "only {partial} partly shadowed vertices");
    for (i, (a, b)) in natural.iter().zip(e.colors()).enumerate() {
        assert_eq!(
            a.to_array().map(f32::to_bits),
            b.to_array().map(f32::to_bits),
            "vertex {i}"
        );
    }
}
