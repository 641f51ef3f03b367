//! Quality levels (`wisp::quality`, `EngineConfig::at_quality`): a level is a set of pass
//! configs; `final` is the engine's defaults but for the shader (light paths, where the
//! library's default stays dual scattering); `preview` draws half the strands with the fibres
//! of all, the same on any thread count; the budget's estimate follows the level. Their time
//! and image error are measured by `wisp bench --quality-list` (BENCHMARKS.md), not here.

use crate::common;
use glam::Vec3;
use wisp::budget::RunPlan;
use wisp::engine::{Engine, EngineConfig, estimate};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;
use wisp::quality::Quality;

#[test]
fn final_is_the_default_configuration_and_each_level_says_its_name() {
    let default = EngineConfig::default();
    let fin = EngineConfig::at_quality(Quality::Final);
    assert_eq!(fin.simulation, default.simulation);
    assert_eq!(fin.interpolation, default.interpolation);
    assert_eq!(fin.hair_map, default.hair_map);
    assert_eq!(fin.skin_texture, default.skin_texture);
    // The shader is the one choice final makes over the library's defaults: light paths
    // (ACCURACY.md §2) where `EngineConfig::default()` keeps dual scattering.
    assert_eq!(
        default.shading.mode,
        wisp::fiber::ShadingMode::DualScattering
    );
    assert_eq!(fin.shading.mode, wisp::fiber::ShadingMode::Volume);
    assert!(fin.shading.light_paths.paths < reference_paths());
    assert_eq!(default.level, Quality::Final);
    for q in Quality::ALL {
        assert_eq!(EngineConfig::at_quality(q).level, q);
        assert_eq!(Quality::from_name(q.name()), Some(q));
        assert_eq!(q.next().next().next(), q, "three levels in the cycle");
    }
    assert_eq!(Quality::from_name("fast"), None);
    // The levels differ where their table says (src/engine/quality.rs).
    let preview = EngineConfig::at_quality(Quality::Preview);
    let reference = EngineConfig::at_quality(Quality::Reference);
    assert!(preview.interpolation.strand_fraction < 1.0);
    assert!(preview.simulation.step_s > Some(1.0 / 480.0));
    assert!(reference.simulation.step_s < Some(1.0 / 480.0));
    assert_eq!(reference.shading.mode, wisp::fiber::ShadingMode::Volume);
    // final builds its light paths 6 times a second of motion, reference for every frame.
    assert!((fin.shading.paths_interval_s - 1.0 / 6.0).abs() < 1e-12);
    assert_eq!(reference.shading.paths_interval_s, 0.0);
}

fn reference_paths() -> u32 {
    EngineConfig::at_quality(Quality::Reference)
        .shading
        .light_paths
        .paths
}

fn preview_at(width: u32) -> EngineConfig {
    let mut config = EngineConfig::at_quality(Quality::Preview);
    config.scene.width = width;
    config.scene.height = width;
    config.simulation.settle_s = 0.3;
    config
}

#[test]
fn preview_draws_half_the_strands_the_same_on_one_and_two_threads() {
    let render = |threads: usize| {
        common::on_threads(threads, || {
            let mut engine = Engine::new(
                Hairstyle::default_smooth(),
                Motion::default_dance(),
                preview_at(96),
            );
            let strands = engine.strands().strand_count();
            (strands, engine.frame(0.5).to_srgb8())
        })
    };
    let (strands, a) = render(1);
    let (_, b) = render(2);
    // 134 wisps of 25 strands: 13 of each kept (ceil 12.5).
    assert_eq!(strands, 134 * 13);
    assert!(a == b, "preview frames differ between 1 and 2 threads");
}

#[test]
fn half_the_strands_cover_the_image_as_all_of_them_do() {
    // The kept strands are drawn twice as wide (twice the fibres side by side), so the hair's
    // summed coverage is about what all the strands leave: measured 1.013 of all the strands'
    // (smooth, hair alone, 128 × 128, 0.5 s into the dance).
    let coverage = |fraction: f32| {
        let mut config = preview_at(128);
        config.interpolation.strand_fraction = fraction;
        config.scene.draw_solids = false;
        config.scene.background = Vec3::ZERO;
        let mut engine = Engine::new(Hairstyle::default_smooth(), Motion::default_dance(), config);
        engine
            .frame(0.5)
            .coverage
            .iter()
            .map(|c| *c as f64)
            .sum::<f64>()
    };
    let (all, half) = (coverage(1.0), coverage(0.5));
    let ratio = half / all;
    println!("summed hair coverage, half the strands / all: {ratio:.3}");
    assert!((0.9..=1.1).contains(&ratio), "{ratio}");
}

#[test]
fn the_estimate_follows_the_level() {
    let (style, motion) = (Hairstyle::default_curly(), Motion::default_dance());
    let plan = RunPlan::default();
    let bytes = |q: Quality| estimate(&style, &motion, &EngineConfig::at_quality(q), &plan);
    let (preview, fin) = (bytes(Quality::Preview), bytes(Quality::Final));
    let part = |e: &wisp::budget::Estimate, what: &str| {
        e.memory
            .iter()
            .filter(|p| p.what == what)
            .map(|p| p.bytes)
            .sum::<u64>()
    };
    // The render strands (and what is kept per strand point) halve with the strands.
    let (p, f) = (
        part(&preview, "render strands"),
        part(&fin, "render strands"),
    );
    assert!(
        p > 0 && (p as f64 / f as f64 - 0.52).abs() < 0.05,
        "{p} of {f}"
    );
    assert!(preview.memory_bytes() < fin.memory_bytes());
}

/// `preview` builds the hair maps 30 times a second of motion: at 60 frames a second every
/// other frame's hair is lit by the maps of the frame before (its hair map part reads 0 and
/// the maps are the same bits), a snapshot set from outside builds at once, and the frames
/// stay the same on one and two threads.
#[test]
fn preview_builds_the_maps_every_other_frame_at_sixty_frames_a_second() {
    let run = |threads: usize| {
        common::on_threads(threads, || {
            let mut engine = Engine::new(
                Hairstyle::default_smooth(),
                Motion::default_dance(),
                preview_at(64),
            );
            let mut built = Vec::new();
            let mut frames = Vec::new();
            for i in 1..=6 {
                let before = engine.map().stats().clone();
                frames.push(engine.frame(0.5 + i as f64 / 60.0).to_srgb8());
                built.push(engine.map_parts.hair_s > 0.0);
                if !built[built.len() - 1] {
                    assert_eq!(&before, engine.map().stats());
                }
            }
            let positions = engine.state().positions.clone();
            engine.set_guide_state(0.5 + 7.0 / 60.0, &positions);
            engine.render();
            built.push(engine.map_parts.hair_s > 0.0);
            (built, frames)
        })
    };
    let (built, a) = run(1);
    let (_, b) = run(2);
    assert_eq!(built, [true, false, true, false, true, false, true]);
    assert!(a == b, "preview frames differ between 1 and 2 threads");
}

/// `preview`'s map has cells 1.5 times as wide as `final`'s, with as many columns per cell.
#[test]
fn preview_map_is_coarser_with_the_same_columns_per_cell() {
    let geom = |q: Quality| {
        let style = Hairstyle::default_smooth();
        wisp::engine::map_geometry(&style, &EngineConfig::at_quality(q).hair_map)
    };
    let (p, f) = (geom(Quality::Preview), geom(Quality::Final));
    assert_eq!(p.lateral, f.lateral);
    let ratio = f.n as f32 / p.n as f32;
    assert!((ratio - 1.5).abs() < 0.03, "{} / {}", f.n, p.n);
}
