//! `wisp bench --quality-list`: each quality level's time and error, as one report.
//!
//! For each level: the per-stage means over `--frames` frames of the dance (`--fps` a second)
//! on each thread count (means, since a level may build its maps on some frames only); then frames of the dance at fixed times ([`SNAPSHOT_TIMES_S`]) compared with the same
//! frames of a more accurate level: every level against `reference` (what it leaves out) and
//! `preview` against `final` (what speed costs), as the relative luminance error over the hair's
//! pixels (`wisp::accuracy::image`: its mean and 95th percentile, each the mean over the
//! frames). Every level draws those frames from the same guides (as `final` simulates them),
//! seen by the same camera (as `final` frames its settled hair), so the image error is the
//! drawing's; the simulation's is the guides' tips over every 1/30 s up
//! to the last of those times against the more accurate level's own run, in frames of motion
//! (the RMS distance over the RMS tip displacement between consecutive frames of the more
//! accurate run, as ACCURACY.md §4). Beside the luminance error, the mean ꟻLIP of the whole
//! frame (`wisp::accuracy::image::flip_mean`: the perceived difference, as rendering papers
//! report it), also the mean over the frames. And at the first snapshot, the key light's T_f
//! read from each level's map where the full hair is, against the exact reference of that
//! hair (`wisp::accuracy::LevelTfReference`: [`TF_VERTICES`] vertices of `final`'s strands,
//! the accuracy part's placements and rays): the map's error, whatever the level draws. A
//! level is the scene's (image, camera, lights) with that level's pass configs; other pass
//! flags are not applied.

use super::rate::{
    CONVERGED_PATHS, EXPORT_FPS, RateError, SPAN_S, WINDOW_FPS, map_rate_error, paths_rate_error,
};
use super::{BenchArgs, BenchScene, Json, Timed, scaling_row, time_stages};
use crate::cli::AppError;
use glam::Vec3;
use std::time::Instant;
use wisp::accuracy::comparison::Comparison;
use wisp::accuracy::image::{flip_mean, hair_mask, image_error};
use wisp::accuracy::{DEFAULT_PLACEMENTS, LevelTfReference, default_rays};
use wisp::engine::{CameraPass, Engine, EngineConfig};
use wisp::quality::Quality;
use wisp::raster::Framebuffer;

/// Times of the frames compared, seconds of the dance: the hair swinging, at its fastest
/// head motions (4.2–4.9 s) and settling.
pub const SNAPSHOT_TIMES_S: [f64; 3] = [2.0, 4.5, 6.0];

/// Vertices of the full hair at which each level's map is compared with the exact reference.
pub const TF_VERTICES: usize = 1000;

/// A level's frames at the snapshot times and its guides' tips at every 1/30 s up to the last.
struct Snapshots {
    frames: Vec<Framebuffer>,
    tips: Vec<Vec<Vec3>>,
}

/// What the report measured of one level, for the plot (`--plot`).
#[derive(Clone, Copy, Debug)]
pub struct LevelPoint {
    pub level: Quality,
    /// Mean ms a frame on the largest thread count measured.
    pub ms: f64,
    /// Mean relative luminance error against `reference` (0 for `reference` itself), when
    /// `reference` was run.
    pub vs_reference: Option<f64>,
    /// The same against `final`, for `preview` and `final` (0) when both were run.
    pub vs_final: Option<f64>,
}

/// The mean over the snapshot frames of the figures of one level against another.
#[derive(Clone, Copy, Debug)]
struct FrameError {
    mean_rel_luminance: f64,
    p95_rel_luminance: f64,
    flip: f64,
}

/// The last snapshot time, seconds: how far each level's run goes.
pub fn last_time_s() -> f64 {
    SNAPSHOT_TIMES_S[SNAPSHOT_TIMES_S.len() - 1]
}

/// The level's configuration for the bench's scene, the flags given written over the
/// level's choices (`--shading`, `--volume-paths`, `--map-res`, …, as `render --quality`).
pub fn level_config(scene: &BenchScene, quality: Quality) -> EngineConfig {
    scene.levels[quality as usize].clone()
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

/// The frames `engine` draws of the guide particles `states` at the snapshot times; `first`
/// sees the engine once it has drawn the first.
fn frames_of(
    engine: &mut Engine,
    states: &[Vec<Vec3>],
    mut first: impl FnMut(&Engine),
) -> Vec<Framebuffer> {
    let mut frames = Vec::new();
    for (&t, positions) in SNAPSHOT_TIMES_S.iter().zip(states) {
        engine.set_guide_state(t, positions);
        frames.push(engine.render().clone());
        if frames.len() == 1 {
            first(engine);
        }
    }
    frames
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
/// luminance error of `run` against `truth`, over the hair's pixels of each frame in `masks`,
/// and of the mean ꟻLIP over each whole frame.
fn frame_error(run: &Snapshots, truth: &Snapshots, masks: &[Vec<bool>]) -> FrameError {
    let errors: Vec<_> = (0..masks.len())
        .filter_map(|i| image_error(&run.frames[i], &truth.frames[i], &masks[i]))
        .collect();
    let n = errors.len().max(1) as f64;
    let flips: Vec<f64> = (0..masks.len())
        .filter_map(|i| flip_mean(&run.frames[i], &truth.frames[i]))
        .collect();
    FrameError {
        mean_rel_luminance: errors.iter().map(|e| e.mean_rel_luminance).sum::<f64>() / n,
        p95_rel_luminance: errors.iter().map(|e| e.p95_rel_luminance).sum::<f64>() / n,
        flip: flips.iter().sum::<f64>() / flips.len().max(1) as f64,
    }
}

/// One level's run: its timings (the JSON rows) and mean ms a frame on the largest thread
/// count, its snapshots, and its map's T_f against the exact reference.
struct LevelRun {
    level: Quality,
    timings: Vec<serde_json::Value>,
    ms: f64,
    snapshots: Snapshots,
    tf: Comparison,
}

/// The exact reference the levels' maps are compared with, and what it took.
struct TfReference {
    reference: LevelTfReference,
    ms: f64,
}

impl TfReference {
    /// The reference of `full`'s hair (every strand) drawn from the guide particles of the
    /// first snapshot, `states[0]`.
    fn of(full: &mut Engine, states: &[Vec<Vec3>]) -> Self {
        let t0 = Instant::now();
        if let Some(first) = states.first() {
            full.set_guide_state(SNAPSHOT_TIMES_S[0], first);
        }
        let reference = LevelTfReference::new(full, TF_VERTICES, DEFAULT_PLACEMENTS);
        TfReference {
            reference,
            ms: t0.elapsed().as_secs_f64() * 1e3,
        }
    }
}

/// The report (the module doc) for `levels`, in the order given; what the plot draws.
pub fn quality_part(
    args: &BenchArgs,
    scene: &BenchScene,
    levels: &[Quality],
    json: &mut Json,
) -> Result<Vec<LevelPoint>, AppError> {
    println!(
        "\nquality levels, mean ms per frame over {} frames, {} a second:",
        args.frames, args.fps
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
    let tf_reference = TfReference::of(&mut truth, &states);
    let drawn_by = |config: EngineConfig, first: &mut dyn FnMut(&Engine)| {
        let mut engine = scene.engine_with(config);
        engine.camera = camera.clone();
        frames_of(&mut engine, &states, first)
    };
    let mut runs = Vec::new();
    for &level in levels {
        let config = level_config(scene, level);
        let (timings, ms) = time_level(args, scene, level, &config)?;
        let tips = simulate(&mut scene.engine_with(config.clone())).1;
        let mut tf = Comparison::default();
        let frames = drawn_by(config, &mut |engine| {
            tf = tf_reference.reference.compare(engine)
        });
        runs.push(LevelRun {
            level,
            timings,
            ms,
            snapshots: Snapshots { frames, tips },
            tf,
        });
    }
    let masks: Vec<Vec<bool>> = {
        let mut config = level_config(scene, Quality::Final);
        config.scene.draw_solids = false;
        drawn_by(config, &mut |_| ())
            .iter()
            .map(hair_mask)
            .collect()
    };
    let (mut entries, points) = print_errors(&runs, &masks);
    print_tf(&runs, &tf_reference, json);
    print_rates(scene, levels, &camera, &mut entries);
    for (&level, entry) in levels.iter().zip(entries.iter_mut()) {
        // What the level ran with, the flags written over its choices.
        let shading = level_config(scene, level).shading;
        entry["shading"] = serde_json::json!({"mode": format!("{:?}", shading.mode),
            "volume_paths": shading.light_paths.paths});
    }
    json.insert("quality".into(), entries.into());
    Ok(points)
}

/// Prints the error of each level's lower rates (`rate`): its hair maps and its light paths
/// where they are built on some frames only, and adds them to the level's JSON entry.
fn print_rates(
    scene: &BenchScene,
    levels: &[Quality],
    camera: &CameraPass,
    entries: &mut [serde_json::Value],
) {
    let configs: Vec<EngineConfig> = levels.iter().map(|&l| level_config(scene, l)).collect();
    let maps = levels.iter().zip(&configs).filter_map(|(&level, config)| {
        let e = map_rate_error(scene, config, camera)?;
        Some((level, 1.0 / config.hair_map.rebuild_interval_s, e, None))
    });
    let heading =
        format!("hair maps built at the level's rate against every frame, {WINDOW_FPS} frames");
    print_rate_table(
        &heading,
        "map_rate",
        WINDOW_FPS,
        maps.collect(),
        levels,
        entries,
    );
    let paths = levels.iter().zip(&configs).filter_map(|(&level, config)| {
        let (e, every) = paths_rate_error(scene, config, camera)?;
        Some((level, 1.0 / config.shading.paths_interval_s, e, Some(every)))
    });
    let heading = format!(
        "light paths built at the level's rate, and for every frame, against {CONVERGED_PATHS}× the paths built for every frame, {EXPORT_FPS} frames"
    );
    print_rate_table(
        &heading,
        "paths_rate",
        EXPORT_FPS,
        paths.collect(),
        levels,
        entries,
    );
}

/// A level's rate error: the level, builds a second, the error of its rate and, for the light
/// paths (whose rate is measured against converged paths), the error of a build for every
/// frame.
type RateRow = (Quality, f64, RateError, Option<RateError>);

/// One stage's rate errors `rows`, printed under `heading` and written as `key` into the
/// levels' JSON entries.
fn print_rate_table(
    heading: &str,
    key: &str,
    fps: f64,
    rows: Vec<RateRow>,
    levels: &[Quality],
    entries: &mut [serde_json::Value],
) {
    if rows.is_empty() {
        return;
    }
    println!(
        "\n{heading} a second over {:.1}–{:.1} s of the dance (the late light alone):",
        SPAN_S.0, SPAN_S.1
    );
    println!(
        "{:>10} {:>8} {:>14} {:>14} {:>8}",
        "level", "builds/s", "mean rel. lum.", "95th pct", "FLIP"
    );
    let json = |e: &RateError| {
        serde_json::json!({"frames": e.frames, "mean_rel_luminance": e.mean_rel_luminance,
            "p95_rel_luminance": e.p95_rel_luminance, "flip_mean": e.flip})
    };
    for (level, hz, e, every) in rows {
        let line = |what: &str, e: &RateError| {
            println!(
                "{:>10} {:>8} {:>13.2}% {:>13.2}% {:>8.4}",
                level.name(),
                what,
                e.mean_rel_luminance * 100.0,
                e.p95_rel_luminance * 100.0,
                e.flip
            )
        };
        line(&format!("{hz:.1}"), &e);
        if let Some(n) = &every {
            line("every", n);
        }
        if let Some(i) = levels.iter().position(|&l| l == level) {
            let mut v = json(&e);
            v["hz"] = hz.into();
            v["fps"] = fps.into();
            if let Some(n) = &every {
                v["every_frame"] = json(n);
            }
            entries[i][key] = v;
        }
    }
}

/// `level`'s per-stage means on each thread count, printed: its JSON rows and its mean ms a
/// frame on the largest thread count.
fn time_level(
    args: &BenchArgs,
    scene: &BenchScene,
    level: Quality,
    config: &EngineConfig,
) -> Result<(Vec<serde_json::Value>, f64), AppError> {
    let mut timings = Vec::new();
    let mut base = None;
    let mut largest = (0, 0.0);
    for &threads in &args.threads_list {
        let timed = Timed {
            mean: true,
            ..Timed::for_config(args, config)
        };
        let (stage_ms, parts_ms) =
            time_stages(timed, || scene.engine_with(config.clone()), threads)?;
        let b = *base.get_or_insert(stage_ms[6]);
        let [_, sim, interp, map, shading, raster, total] = stage_ms;
        println!(
            "{:>10} {threads:>7} {sim:>10.2} {interp:>10.2} {map:>10.2} {shading:>10.2} \
             {raster:>10.2} {total:>10.2}  {:.2}x",
            level.name(),
            b / total
        );
        if threads > largest.0 {
            largest = (threads, total);
        }
        timings.push(scaling_row(threads, &stage_ms, b, parts_ms));
    }
    Ok((timings, largest.1))
}

/// Prints each level's error against `reference` and `preview`'s against `final` (where those
/// levels were run); returns the report's JSON entries (with each level's T_f figures) and the
/// plot's points.
fn print_errors(
    runs: &[LevelRun],
    masks: &[Vec<bool>],
) -> (Vec<serde_json::Value>, Vec<LevelPoint>) {
    let find = |q: Quality| runs.iter().find(|r| r.level == q).map(|r| &r.snapshots);
    println!(
        "\nimage error at t = {SNAPSHOT_TIMES_S:?} s (mean of the frames): relative luminance \
         over the hair's pixels, ꟻLIP over the whole frame; guide tips in frames of motion:"
    );
    println!(
        "{:>10} {:>10} {:>14} {:>14} {:>8} {:>12}",
        "level", "against", "mean rel. lum.", "95th pct", "FLIP", "tips"
    );
    let (mut entries, mut points) = (Vec::new(), Vec::new());
    for run in runs {
        let level = run.level;
        let mut entry = serde_json::json!({"level": level.name(), "timings": run.timings,
            "tf_mae": run.tf.mae, "tf_overall_bias": run.tf.overall_bias});
        let mut point = LevelPoint {
            level,
            ms: run.ms,
            vs_reference: find(Quality::Reference).map(|_| 0.0),
            vs_final: None,
        };
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
            let e = frame_error(&run.snapshots, truth, masks);
            let tips = tip_error_frames(&run.snapshots, truth);
            println!(
                "{:>10} {:>10} {:>13.2}% {:>13.2}% {:>8.4} {:>12.2}",
                level.name(),
                truth_level.name(),
                e.mean_rel_luminance * 100.0,
                e.p95_rel_luminance * 100.0,
                e.flip,
                tips
            );
            entry[key] = serde_json::json!({"mean_rel_luminance": e.mean_rel_luminance,
                "p95_rel_luminance": e.p95_rel_luminance, "flip_mean": e.flip,
                "tip_error_frames": tips});
            match truth_level {
                Quality::Reference => point.vs_reference = Some(e.mean_rel_luminance),
                _ => point.vs_final = Some(e.mean_rel_luminance),
            }
        }
        if level == Quality::Final && find(Quality::Preview).is_some() {
            point.vs_final = Some(0.0);
        }
        entries.push(entry);
        points.push(point);
    }
    (entries, points)
}

/// Prints each level's T_f against the exact reference, and writes what the reference was.
fn print_tf(runs: &[LevelRun], tf: &TfReference, json: &mut Json) {
    let r = &tf.reference;
    let rays = default_rays(r.placements());
    println!(
        "\nkey light's T_f at t = {:.1} s against the exact reference of the full hair ({} vertices \
         of final's strands, {rays} rays on each of {} placement(s) of the fibres, {:.0} ms), \
         each level's map read there:",
        SNAPSHOT_TIMES_S[0],
        r.vertices(),
        r.placements(),
        tf.ms
    );
    println!("{:>10} {:>8} {:>8}", "level", "Tf MAE", "bias");
    for run in runs {
        println!(
            "{:>10} {:>8.4} {:>+8.4}",
            run.level.name(),
            run.tf.mae,
            run.tf.overall_bias
        );
    }
    json.insert(
        "quality_tf_reference".into(),
        serde_json::json!({"t_s": SNAPSHOT_TIMES_S[0], "vertices": r.vertices(),
            "placements": r.placements(), "rays": rays, "ms": tf.ms}),
    );
}
