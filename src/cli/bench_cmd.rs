//! `wisp bench`: how the engine scales over cores and how much accuracy each millisecond buys.
//!
//! 1. **Scaling**: the whole pipeline (animation, simulation, interpolation, map, shading,
//!    raster) over `--frames` frames of the dance, once per thread count, in rayon pools built
//!    in this process; per-stage medians (means when the level builds its maps or light paths
//!    on some frames only) and the speed-up over the first count.
//! 2. **Self-collision**: peak cell volume fraction, hair volume (filled cells) and simulation
//!    time with and without the density repulsion of Bertails §4.1, and its share of a frame.
//! 3. **Speed against error**: one hair state (the dance at `--at-s`), the map built at each
//!    `--map-res-list` resolution and compared with the exact reference
//!    (`wisp::accuracy::exact`: ray shooting through the placed fibres) at 2,000 vertices: T_f
//!    error and bias, and the error of the shaded vertex luminance; time is map build + a
//!    lookup at every vertex, median of `--repeats` runs (`wisp accuracy` gives the same table
//!    with more control).
//!
//! 4. **Quality levels** (`--quality-list`): each level's per-stage time, its image and
//!    simulation error against a more accurate level, and its map's T_f against the exact
//!    reference ([`quality`]); with `--plot FILE.png`, time against image error as a picture
//!    ([`plot`]).
//!
//! `--parts` chooses among them. Results go to stdout as tables and, with `--json FILE`, as
//! JSON.

mod plot;
mod quality;
mod rate;

use super::{AppError, SceneArgs};
use std::path::PathBuf;
use wisp::accuracy::exact::Footprint;
use wisp::engine::{Engine, EngineConfig, MapPartTimings, StageTimings};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;
use wisp::quality::Quality;

#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    /// Frames of the dance timed per thread count, 1–10000
    #[arg(long, value_name = "N", default_value_t = 60, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub frames: u32,
    /// Frames per second of motion the timed frames are apart, 1–240 (the window draws 60)
    #[arg(long, value_name = "N", default_value_t = 30, value_parser = clap::value_parser!(u32).range(1..=240))]
    pub fps: u32,
    /// Thread counts to compare, comma separated, each 1–256
    #[arg(long, value_name = "N,…", default_value = "1,2", value_delimiter = ',', value_parser = clap::value_parser!(u32).range(1..=256))]
    pub threads_list: Vec<u32>,
    /// Map resolutions for speed against error
    #[arg(long, value_name = "N,…", default_value = "32,64,96,128,192,256", value_delimiter = ',', value_parser = clap::value_parser!(u32).range(4..=1024))]
    pub map_res_list: Vec<u32>,
    /// Time of the hair state for speed against error, seconds
    #[arg(long, value_name = "SECONDS", default_value_t = 4.0, value_parser = super::parse_finite_f32)]
    pub at_s: f32,
    /// Timed repetitions per map resolution, 1–1000
    #[arg(long, value_name = "N", default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub repeats: u32,
    /// Parts to run, comma separated: scaling, self-collision, accuracy, quality [default:
    /// quality with --quality-list, else the other three]
    #[arg(
        long,
        value_name = "PART,…",
        value_delimiter = ',',
        hide_possible_values = true
    )]
    pub parts: Option<Vec<BenchPart>>,
    /// Quality levels to time and compare (the quality part), comma separated [default:
    /// preview,final,reference]
    #[arg(long, value_name = "LEVEL,…", value_delimiter = ',', value_parser = super::parse_quality)]
    pub quality_list: Option<Vec<Quality>>,
    /// Also write the results as JSON to this file
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Also draw the quality part as a 960 × 640 PNG: mean ms a frame on the largest thread
    /// count (log axis) against the mean relative luminance error, a point per level, for this
    /// run's hairstyle and those of --plot-with
    #[arg(long, value_name = "FILE.png")]
    pub plot: Option<PathBuf>,
    /// Also draw in the plot the scenes of these earlier `--json` reports, comma separated (a
    /// curve per scene)
    #[arg(
        long,
        value_name = "FILE.json,…",
        value_delimiter = ',',
        requires = "plot"
    )]
    pub plot_with: Vec<PathBuf>,
    #[command(flatten)]
    pub scene: SceneArgs,
}

/// A part of the benchmark (`--parts`).
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum BenchPart {
    Scaling,
    SelfCollision,
    Accuracy,
    Quality,
}

impl BenchArgs {
    /// The parts to run: `--parts`, else the quality part when `--quality-list` is given,
    /// else scaling, self-collision and accuracy.
    fn parts(&self) -> Vec<BenchPart> {
        match (&self.parts, &self.quality_list) {
            (Some(parts), _) => parts.clone(),
            (None, Some(_)) => vec![BenchPart::Quality],
            (None, None) => vec![
                BenchPart::Scaling,
                BenchPart::SelfCollision,
                BenchPart::Accuracy,
            ],
        }
    }

    /// The levels of the quality part.
    fn quality_levels(&self) -> Vec<Quality> {
        self.quality_list.clone().unwrap_or(Quality::ALL.to_vec())
    }
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

pub fn run(args: BenchArgs) -> Result<(), AppError> {
    let (style, hair, motion, config) = args.scene.resolve()?;
    if let Some(path) = &args.json {
        super::check_output_file("--json", path)?;
    }
    let earlier: Vec<plot::ScenePoints> = args
        .plot_with
        .iter()
        .map(|p| plot::read_report(p))
        .collect::<Result<_, _>>()?;
    if let Some(path) = &args.plot {
        check_plot(&args, path)?;
    }
    if let Some(&n) = args
        .threads_list
        .iter()
        .find(|&&n| n as usize > super::max_threads())
    {
        return Err(AppError::input(anyhow::anyhow!(
            "--threads-list: {n} threads is more than {} per core ({} here), which only measures oversubscription",
            super::THREADS_PER_CORE,
            super::max_threads()
        )));
    }
    // The clip loops: a time beyond one loop is wrapped into it (as `render --start-s`).
    let at_s =
        super::render_cmd::wrapped_start_s(args.at_s as f64, motion.duration_s(), motion.speed()).0;
    let mut config = config;
    check_budget(&args, &style, &motion, &mut config, at_s)?;
    let mut json = serde_json::Map::new();
    println!(
        "wisp bench: {} ({} strands, {} segments), {}x{} px, {} frames of \"{}\"",
        style.name,
        style.wisps.count as u64 * style.wisps.strands_per_wisp as u64,
        style.wisps.count as u64
            * style.wisps.strands_per_wisp as u64
            * (style.strands.points as u64 - 1),
        config.scene.width,
        config.scene.height,
        args.frames,
        motion.clip_name()
    );

    let levels = Quality::ALL.map(|q| {
        let mut c = args.scene.config(config.scene.clone(), q);
        c.simulation.settle_step_s = config.simulation.settle_step_s;
        c
    });
    let scene = BenchScene {
        style,
        hair,
        motion,
        levels,
        config,
    };
    let parts = args.parts();
    if parts.contains(&BenchPart::Scaling) {
        scaling_part(&args, &scene, &mut json)?;
    }
    if parts.contains(&BenchPart::SelfCollision) {
        self_collision_part(&args, &scene, &mut json);
    }
    if parts.contains(&BenchPart::Accuracy) {
        accuracy_part(&args, at_s, &scene, &mut json);
    }
    if parts.contains(&BenchPart::Quality) {
        let levels = args.quality_levels();
        for &level in &levels {
            let mut config = quality::level_config(&scene, level);
            check_one(
                &args,
                &scene.style,
                &scene.motion,
                &mut config,
                quality::last_time_s(),
            )?;
        }
        let points = quality::quality_part(&args, &scene, &levels, &mut json)?;
        if let Some(path) = &args.plot {
            let threads = args.threads_list.iter().copied().max().unwrap_or(1);
            let mut scenes = vec![plot::ScenePoints {
                name: scene.style.name.clone(),
                points,
            }];
            scenes.extend(earlier);
            let data = plot::PlotData {
                threads,
                scenes: &scenes,
            };
            plot::write_plot(path, &data)?;
            println!("\nplot written to {}", path.display());
        }
    }
    json.insert("hairstyle".into(), scene.style.name.clone().into());
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&serde_json::Value::Object(json))
            .map_err(AppError::other)?;
        std::fs::write(path, text)
            .map_err(|e| AppError::input(anyhow::anyhow!("--json {}: {e}", path.display())))?;
    }
    Ok(())
}

/// Refuses `--plot` before any work when the run has nothing to draw (no quality part, or
/// levels that compare none) or the file could never be written.
fn check_plot(args: &BenchArgs, path: &std::path::Path) -> Result<(), AppError> {
    if !args.parts().contains(&BenchPart::Quality) {
        return Err(AppError::input(anyhow::anyhow!(
            "--plot draws the quality part: give --quality-list (or --parts quality)"
        )));
    }
    if !plot::has_comparison(&args.quality_levels()) {
        return Err(AppError::input(anyhow::anyhow!(
            "--plot: the levels compare none; give reference and another level, or preview and \
             final, in --quality-list"
        )));
    }
    super::check_output_file("--plot", path)
}

/// Refuses the benchmark when one of its runs is over the budget: every map of the speed
/// against error sweep, and the scene's own (an automatic resolution is lowered to fit, with
/// a warning). `at_s` is the time of the sweep's hair state.
fn check_budget(
    args: &BenchArgs,
    style: &Hairstyle,
    motion: &Motion,
    config: &mut EngineConfig,
    at_s: f64,
) -> Result<(), AppError> {
    for &n in &args.map_res_list {
        let mut sweep = {
            let mut config = config.clone();
            config.hair_map.map_res = Some(n);
            config
        };
        check_one(args, style, motion, &mut sweep, at_s)?;
    }
    check_one(args, style, motion, config, at_s)
}

/// Refuses the benchmark when a run of `config` up to `at_s` is over the budget.
fn check_one(
    args: &BenchArgs,
    style: &Hairstyle,
    motion: &Motion,
    config: &mut EngineConfig,
    at_s: f64,
) -> Result<(), AppError> {
    let plan = wisp::budget::RunPlan {
        frame_interval_s: 1.0 / 30.0,
        warm_up_s: at_s,
        export_png: false,
        cache: wisp::budget::CacheUse::None,
    };
    args.scene.budget.check(style, motion, config, &plan)
}

type Json = serde_json::Map<String, serde_json::Value>;

/// What every part of the benchmark runs: the resolved hairstyle, hair, motion and engine
/// configuration, and each quality level's configuration with the flags given written over
/// its choices (as `render --quality` does).
struct BenchScene {
    style: Hairstyle,
    hair: super::ImportedHair,
    motion: Motion,
    config: EngineConfig,
    /// In the order of `Quality::ALL` (its declaration order: `level as usize`).
    levels: [EngineConfig; 3],
}

impl BenchScene {
    fn engine(&self) -> Engine {
        self.engine_with(self.config.clone())
    }

    fn engine_with(&self, config: EngineConfig) -> Engine {
        super::engine(
            self.style.clone(),
            self.hair.clone(),
            self.motion.clone(),
            config,
        )
    }
}

/// Scaling over threads: the whole pipeline over `--frames` frames once per thread count,
/// per-stage medians (means when some frames build what the others reuse: a median would
/// leave the builds out) and the speed-up over the first count; then the map stage by part.
fn scaling_part(args: &BenchArgs, scene: &BenchScene, json: &mut Json) -> Result<(), AppError> {
    let timed = Timed::for_config(args, &scene.config);
    let summary = if timed.mean { "mean" } else { "median" };
    println!("\nper-stage {summary} ms per frame:");
    println!(
        "threads  {:>10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10}  speed-up",
        "animation", "simulation", "interp", "map", "shading", "raster", "total"
    );
    let mut base_total = None;
    let mut scaling = Vec::new();
    let mut map_parts = Vec::new();
    for &threads in &args.threads_list {
        let (med, parts_ms) = time_stages(timed, || scene.engine(), threads)?;
        map_parts.push((threads, parts_ms));
        let base = *base_total.get_or_insert(med[6]);
        println!(
            "{threads:>7}  {:>10.2} {:>10.2} {:>10.2} {:>10.2} {:>10.2} {:>10.2} {:>10.2}  {:.2}x",
            med[0],
            med[1],
            med[2],
            med[3],
            med[4],
            med[5],
            med[6],
            base / med[6]
        );
        scaling.push(scaling_row(threads, &med, base, parts_ms));
    }
    print_map_parts(&map_parts);
    json.insert("scaling".into(), scaling.into());
    Ok(())
}

/// Which frames [`time_stages`] times and how it sums them up.
#[derive(Clone, Copy)]
struct Timed {
    frames: u32,
    /// Frames per second of motion.
    fps: u32,
    /// Means instead of medians: for levels that build their maps on some frames only, whose
    /// cost per frame is the mean.
    mean: bool,
}

impl Timed {
    /// `args`' frames, summed up by their median unless `config` builds its hair maps or its
    /// light paths on some frames only.
    fn for_config(args: &BenchArgs, config: &EngineConfig) -> Self {
        Self {
            frames: args.frames,
            fps: args.fps,
            mean: config.shading.paths_at_rate() || config.hair_map.rebuild_interval_s > 0.0,
        }
    }
}

/// `timed.frames` frames of the dance `timed.fps` a second apart on a pool of `threads`, after
/// one untimed frame, from the engine `make` builds in the pool: the median (or mean)
/// milliseconds of each stage
/// (`StageTimings::NAMES`) and of the total, and of each part of the map stage
/// (`MapPartTimings::NAMES`).
fn time_stages(
    timed: Timed,
    make: impl Fn() -> Engine + Send + Sync,
    threads: u32,
) -> Result<([f64; 7], [f64; 3]), AppError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads as usize)
        .build()
        .map_err(AppError::other)?;
    let per_frame: Vec<(StageTimings, MapPartTimings)> = pool.install(|| {
        let mut engine = make();
        // One frame untimed: the first allocates the passes' buffers.
        engine.frame(0.0);
        (1..=timed.frames)
            .map(|i| {
                engine.frame(i as f64 / timed.fps as f64);
                (engine.timings, engine.map_parts)
            })
            .collect()
    });
    let (per_frame, parts): (Vec<StageTimings>, Vec<MapPartTimings>) =
        per_frame.into_iter().unzip();
    let summary = |v: &mut Vec<f64>| {
        if timed.mean {
            v.iter().sum::<f64>() / v.len().max(1) as f64
        } else {
            median(v)
        }
    };
    let parts_ms = [0, 1, 2].map(|k| {
        let mut v: Vec<f64> = parts.iter().map(|p| p.as_array()[k]).collect();
        summary(&mut v) * 1e3
    });
    let mut stage_ms = [0.0f64; 7];
    for (s, m) in stage_ms.iter_mut().enumerate().take(6) {
        let mut v: Vec<f64> = per_frame.iter().map(|t| t.as_array()[s]).collect();
        *m = summary(&mut v) * 1e3;
    }
    let mut totals: Vec<f64> = per_frame.iter().map(|t| t.total_s() * 1e3).collect();
    stage_ms[6] = summary(&mut totals);
    Ok((stage_ms, parts_ms))
}

/// One thread count's row of the JSON: the stages' ms `stage_ms` (medians or means, as
/// [`time_stages`] gave them), the speed-up over `base`, the map stage's parts.
fn scaling_row(
    threads: u32,
    stage_ms: &[f64; 7],
    base: f64,
    parts_ms: [f64; 3],
) -> serde_json::Value {
    let mut row = serde_json::Map::new();
    row.insert("threads".into(), threads.into());
    for (name, v) in StageTimings::NAMES.iter().zip(&stage_ms[..6]) {
        row.insert(format!("{name}_ms"), (*v).into());
    }
    row.insert("total_ms".into(), stage_ms[6].into());
    row.insert("speedup".into(), (base / stage_ms[6]).into());
    for (key, v) in ["map_hair_ms", "map_occluders_ms", "map_skin_texture_ms"]
        .iter()
        .zip(parts_ms)
    {
        row.insert((*key).into(), v.into());
    }
    serde_json::Value::Object(row)
}

/// The map stage by part, per thread count (medians of each part, so they need not add up
/// to the map's).
fn print_map_parts(map_parts: &[(u32, [f64; 3])]) {
    println!("\nmap stage by part, median ms per frame (0 where the maps were reused):");
    println!(
        "threads  {:>12} {:>12} {:>12}",
        MapPartTimings::NAMES[0],
        MapPartTimings::NAMES[1],
        MapPartTimings::NAMES[2]
    );
    for (threads, ms) in map_parts {
        println!(
            "{threads:>7}  {:>12.2} {:>12.2} {:>12.2}",
            ms[0], ms[1], ms[2]
        );
    }
}

/// Self-collision (Bertails §4.1): the same dance with and without density repulsion.
fn self_collision_part(args: &BenchArgs, scene: &BenchScene, json: &mut Json) {
    println!(
        "\nself-collision over {} frames (mean of per-frame figures):",
        args.frames
    );
    println!(
        "{:>16} {:>14} {:>16} {:>14} {:>14}",
        "self-collision", "peak vol. frac", "hair volume (L)", "sim (ms)", "frame (ms)"
    );
    let mut sc = Vec::new();
    let mut sim_ms = [0.0f64; 2];
    let mut frame_ms = 0.0f64;
    for (k, on) in [false, true].into_iter().enumerate() {
        let mut cfg = scene.config.clone();
        cfg.simulation.self_collision = on;
        let mut engine = scene.engine_with(cfg);
        let (mut peak, mut volume, mut sims, mut totals) = (0.0f64, 0.0f64, Vec::new(), Vec::new());
        for i in 0..args.frames {
            engine.frame(i as f64 / 30.0);
            peak += engine.map_stats().peak_volume_fraction as f64;
            volume += engine.map_stats().hair_volume_m3 as f64;
            sims.push(engine.timings.simulation_s * 1e3);
            totals.push(engine.timings.total_s() * 1e3);
        }
        let f = args.frames as f64;
        sim_ms[k] = median(&mut sims);
        frame_ms = median(&mut totals);
        println!(
            "{:>16} {:>14.3} {:>16.3} {:>14.2} {:>14.2}",
            if on { "on" } else { "off" },
            peak / f,
            volume / f * 1e3,
            sim_ms[k],
            frame_ms
        );
        sc.push(serde_json::json!({ "self_collision": on, "peak_volume_fraction": peak / f, "hair_volume_l": volume / f * 1e3, "sim_ms": sim_ms[k], "frame_ms": frame_ms }));
    }
    let share = (sim_ms[1] - sim_ms[0]).max(0.0) / frame_ms.max(1e-9);
    println!(
        "self-collision share of the frame time: {:.1}% (Bertails 2005: 2.5%)",
        share * 100.0
    );
    json.insert("self_collision".into(), sc.into());
    json.insert("self_collision_share".into(), share.into());
}

/// Speed against error over map resolutions, against the exact reference.
fn accuracy_part(args: &BenchArgs, at_s: f64, scene: &BenchScene, json: &mut Json) {
    let mut engine = scene.engine();
    engine.run_up_to(at_s);
    engine.frame(at_s);
    let default_n = engine.map_geometry().n;
    let geometries = wisp::accuracy::sweep_geometries(&engine, &args.map_res_list);
    // 32 rays on each of 8 placements of the bundles' fibres, 128 on one-fibre strands' one.
    let placements =
        wisp::accuracy::placements_used(&engine.style, wisp::accuracy::DEFAULT_PLACEMENTS);
    let rays = wisp::accuracy::default_rays(placements);
    let footprint = Footprint::Fibers { rays };
    let wisp::accuracy::MapMeasurement {
        rows, reference_ms, ..
    } = wisp::accuracy::measure_map(
        &engine,
        &geometries,
        2000,
        &footprint,
        placements,
        args.repeats,
        engine.hair_map.config.contact,
    );
    println!(
        "\nspeed against error at t = {} s: map build + a lookup at all {} vertices, against the \
         exact reference (ray shooting through the placed fibres, 2,000 vertices, {} rays asked \
         on each of {placements} placement(s) of the fibres, {:.0} ms; see ACCURACY.md); the \
         scene's own choice is N = {default_n}:\n",
        at_s,
        engine.strands().positions.len(),
        rays,
        reference_ms,
    );
    print!("{}", wisp::accuracy::markdown(&rows));
    let rows: Vec<serde_json::Value> = rows
        .iter()
        .map(|r| {
            serde_json::json!({
                "map_res": r.n, "lateral": r.lateral, "default": r.is_default, "ds_mm": r.ds_mm, "ms": r.ms,
                "tf_mae": r.comparison.mae, "tf_overall_bias": r.comparison.overall_bias,
                "tf_bias_by_true_bin": r.comparison.by_truth.iter().map(|b| b.bias).collect::<Vec<_>>(),
                "tf_bias_by_map_bin": r.comparison.by_estimate.iter().map(|b| b.bias).collect::<Vec<_>>(),
                "luminance_rel_rms": r.luminance_rel_rms, "luminance_ratio": r.luminance_ratio,
            })
        })
        .collect();
    json.insert("speed_vs_error".into(), rows.into());
    json.insert("reference_ms".into(), reference_ms.into());
    json.insert("reference_placements".into(), placements.into());
}
