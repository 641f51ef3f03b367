//! `wisp bench --quality-list`: each quality level's time and error, as one report.
//!
//! For each level: the per-stage medians over `--frames` frames of the dance on each thread
//! count; then frames of the dance at fixed times ([`SNAPSHOT_TIMES_S`]) compared with the same
//! frames of a more accurate level: every level against `reference` (what it leaves out) and
//! `preview` against `final` (what speed costs), as the relative luminance error over the hair's
//! pixels (`wisp::accuracy::image`: its mean and 95th percentile, each the mean over the
//! frames). Every level draws those frames from the same guides (as `final` simulates them),
//! seen by the same camera (as `final` frames its settled hair), so the image error is the
//! drawing's; the simulation's is the guides' tips over every 1/30 s up
//! to the last of those times against the more accurate level's own run, in frames of motion
//! (the RMS distance over the RMS tip displacement between consecutive frames of the more
//! accurate run, as ACCURACY.md §4). A level is the scene's (image, camera, lights) with that
//! level's pass configs; other pass flags are not applied.

use super::{BenchArgs, BenchScene, Json, scaling_row, time_stages};
use crate::cli::AppError;
use glam::Vec3;
use wisp::accuracy::image::{hair_mask, image_error};
use wisp::engine::{Engine, EngineConfig};
use wisp::quality::Quality;
use wisp::raster::Framebuffer;

/// Times of the frames compared, seconds of the dance: the hair swinging, at its fastest
/// head motions (4.2–4.9 s) and settling.
pub const SNAPSHOT_TIMES_S: [f64; 3] = [2.0, 4.5, 6.0];

/// A level's frames at the snapshot times and its guides' tips at every 1/30 s up to the last.
struct Snapshots {
    frames: Vec<Framebuffer>,
    tips: Vec<Vec<Vec3>>,
}

/// The last snapshot time, seconds: how far each level's run goes.
pub fn last_time_s() -> f64 {
    SNAPSHOT_TIMES_S[SNAPSHOT_TIMES_S.len() - 1]
}

/// The level's configuration for the bench's scene.
pub fn level_config(scene: &BenchScene, quality: Quality) -> EngineConfig {
    EngineConfig {
        scene: scene.config.scene.clone(),
        ..EngineConfig::at_quality(quality)
    }
}

/// The guide particles at each snapshot time, and every guide's tip at every 1/30 s up to the
/// last, as `engine` simulates them.
fn simulate(engine: &mut Engine) -> (Vec<Vec<Vec3>>, Vec<Vec<Vec3>>) {
    let frames_to_last = (last_time_s() * 30.0).round() as u32;
    let (mut states, mut tips) = (Vec::new(), Vec::new());
    for f in 1..=frames_to_last {
        engine.advance(f as f64 / 30.0);
        let ppg = engine.guides.points_per_guide;
        let positions = &engine.simulation.state.positions;
        tips.push(
            (0..engine.guides.count())
                .map(|g| positions[g * ppg + ppg - 1])
                .collect(),
        );
        if SNAPSHOT_TIMES_S
            .iter()
            .any(|&s| (s * 30.0).round() as u32 == f)
        {
            states.push(positions.clone());
        }
    }
    (states, tips)
}

/// The frames `engine` draws of the guide particles `states` at the snapshot times.
fn frames_of(engine: &mut Engine, states: &[Vec<Vec3>]) -> Vec<Framebuffer> {
    SNAPSHOT_TIMES_S
        .iter()
        .zip(states)
        .map(|(&t, positions)| {
            engine.set_guide_state(t, positions);
            engine.render().clone()
        })
        .collect()
}

/// The tips of `run` against `truth`, in frames of motion (the module doc).
fn tip_error_frames(run: &Snapshots, truth: &Snapshots) -> f64 {
    let (mut err2, mut motion2, mut n) = (0.0f64, 0.0f64, 0usize);
    for k in 1..truth.tips.len() {
        for g in 0..truth.tips[k].len() {
            err2 += run.tips[k][g].distance_squared(truth.tips[k][g]) as f64;
            motion2 += truth.tips[k][g].distance_squared(truth.tips[k - 1][g]) as f64;
            n += 1;
        }
    }
    if n == 0 || motion2 <= 0.0 {
        return 0.0;
    }
    (err2 / motion2).sqrt()
}

/// The mean over the snapshot frames of the mean and of the 95th percentile of the relative
/// luminance error of `run` against `truth`, over the hair's pixels of each frame in `masks`.
fn frame_error(run: &Snapshots, truth: &Snapshots, masks: &[Vec<bool>]) -> (f64, f64) {
    let errors: Vec<_> = (0..masks.len())
        .filter_map(|i| image_error(&run.frames[i], &truth.frames[i], &masks[i]))
        .collect();
    let n = errors.len().max(1) as f64;
    (
        errors.iter().map(|e| e.mean_rel_luminance).sum::<f64>() / n,
        errors.iter().map(|e| e.p95_rel_luminance).sum::<f64>() / n,
    )
}

/// The report (the module doc) for `levels`, in the order given.
pub fn quality_part(
    args: &BenchArgs,
    scene: &BenchScene,
    levels: &[Quality],
    json: &mut Json,
) -> Result<(), AppError> {
    println!(
        "\nquality levels, median ms per frame over {} frames:",
        args.frames
    );
    println!(
        "{:>10} {:>7} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10}  speed-up",
        "level", "threads", "simulation", "interp", "map", "shading", "raster", "total"
    );
    // Every level draws the guides as `final` simulates them, so that the image error is the
    // drawing's alone; each level's own simulation is compared by its tips.
    let mut truth = scene.engine_with(level_config(scene, Quality::Final));
    let camera = truth.camera.clone();
    let states = simulate(&mut truth).0;
    let drawn_by = |config: EngineConfig| {
        let mut engine = scene.engine_with(config);
        engine.camera = camera.clone();
        frames_of(&mut engine, &states)
    };
    let mut rows = Vec::new();
    let mut runs = Vec::new();
    for &level in levels {
        let config = level_config(scene, level);
        let mut timings = Vec::new();
        let mut base = None;
        for &threads in &args.threads_list {
            let (med, parts_ms) =
                time_stages(args.frames, || scene.engine_with(config.clone()), threads)?;
            let b = *base.get_or_insert(med[6]);
            let [_, sim, interp, map, shading, raster, total] = med;
            println!(
                "{:>10} {threads:>7} {sim:>10.2} {interp:>10.2} {map:>10.2} {shading:>10.2} \
                 {raster:>10.2} {total:>10.2}  {:.2}x",
                level.name(),
                b / total
            );
            timings.push(scaling_row(threads, &med, b, parts_ms));
        }
        let tips = simulate(&mut scene.engine_with(config.clone())).1;
        let frames = drawn_by(config);
        runs.push((level, Snapshots { frames, tips }));
        rows.push((level, timings));
    }
    let masks: Vec<Vec<bool>> = {
        let mut config = level_config(scene, Quality::Final);
        config.scene.draw_solids = false;
        drawn_by(config).iter().map(hair_mask).collect()
    };
    print_errors(&runs, &masks, rows, json);
    Ok(())
}

/// Prints each level's error against `reference` and `preview`'s against `final` (where those
/// levels were run), and writes the report's JSON.
fn print_errors(
    runs: &[(Quality, Snapshots)],
    masks: &[Vec<bool>],
    rows: Vec<(Quality, Vec<serde_json::Value>)>,
    json: &mut Json,
) {
    let find = |q: Quality| runs.iter().find(|(l, _)| *l == q).map(|(_, s)| s);
    println!(
        "\nimage error over the hair's pixels at t = {SNAPSHOT_TIMES_S:?} s (mean of the frames), \
         guide tips in frames of motion:"
    );
    println!(
        "{:>10} {:>10} {:>14} {:>14} {:>12}",
        "level", "against", "mean rel. lum.", "95th pct", "tips"
    );
    let mut out = Vec::new();
    for (level, timings) in rows {
        let run = find(level).expect("every level was run");
        let mut entry = serde_json::json!({"level": level.name(), "timings": timings});
        for (truth_level, key) in [
            (Quality::Reference, "vs_reference"),
            (Quality::Final, "vs_final"),
        ] {
            let against_final_only_for_preview =
                truth_level == Quality::Final && level != Quality::Preview;
            let Some(truth) = find(truth_level) else {
                continue;
            };
            if level == truth_level || against_final_only_for_preview {
                continue;
            }
            let (mean, p95) = frame_error(run, truth, masks);
            let tips = tip_error_frames(run, truth);
            println!(
                "{:>10} {:>10} {:>13.2}% {:>13.2}% {:>12.2}",
                level.name(),
                truth_level.name(),
                mean * 100.0,
                p95 * 100.0,
                tips
            );
            entry[key] = serde_json::json!({"mean_rel_luminance": mean, "p95_rel_luminance": p95,
                "tip_error_frames": tips});
        }
        out.push(entry);
    }
    json.insert("quality".into(), out.into());
}
