//! `wisp bench`: how the engine scales over cores and how much accuracy each millisecond buys.
//!
//! 1. **Scaling**: the whole pipeline (animation, simulation, interpolation, map, shading,
//!    raster) over `--frames` frames of the dance, once per thread count, in rayon pools built
//!    in this process; per-stage medians and the speed-up over one thread.
//! 2. **Speed against error**: one hair state (the dance at `--at-s`), the map built and every
//!    vertex shaded at each `--map-res`; error is the relative RMS difference of vertex
//!    luminance against a map 4x finer than the finest tested (the converged answer of the
//!    same estimator: the map's own discretisation error, not the physics'); time is map build
//!    + shading, median of `--repeats` runs.
//!
//! Results go to stdout as a table and, with `--json FILE`, as JSON.

use super::{AppError, SceneArgs};
use crate::frame::{Engine, StageTimings};
use crate::map::{CountModel, LightMap, MapBuildInput, MapGeometry};
use crate::shade::shade_vertices;
use glam::Vec3;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Frames of the dance timed per thread count.
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub frames: u32,
    /// Thread counts to compare, comma separated.
    #[arg(long, default_value = "1,2", value_delimiter = ',', value_parser = clap::value_parser!(u32).range(1..=256))]
    pub threads_list: Vec<u32>,
    /// Map resolutions (cells per axis) for speed against error, comma separated.
    #[arg(long, default_value = "32,64,96,128,192,256", value_delimiter = ',', value_parser = clap::value_parser!(u32).range(4..=1024))]
    pub map_res_list: Vec<u32>,
    /// Time in the dance of the hair state used for speed against error, seconds.
    #[arg(long, default_value_t = 4.0, value_parser = super::parse_finite_f32)]
    pub at_s: f32,
    /// Timed repetitions per map resolution.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub repeats: u32,
    /// Also write the results as JSON to this file.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

pub fn run(args: BenchArgs) -> Result<(), AppError> {
    let (style, motion, config) = args.scene.resolve()?;
    let mut json = serde_json::Map::new();
    println!(
        "wisp bench: {} ({} strands, {} segments), {}x{} px, {} frames of \"{}\"",
        style.name,
        style.wisps.count as u64 * style.wisps.strands_per_wisp as u64,
        style.wisps.count as u64
            * style.wisps.strands_per_wisp as u64
            * (style.strands.points as u64 - 1),
        config.width,
        config.height,
        args.frames,
        motion.clip_name()
    );

    // 1. Scaling over threads.
    println!("\nper-stage median ms per frame:");
    println!(
        "threads  {:>10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10}  speed-up",
        "animation", "simulation", "interp", "map", "shading", "raster", "total"
    );
    let mut base_total = None;
    let mut scaling = Vec::new();
    for &threads in &args.threads_list {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads as usize)
            .build()
            .map_err(AppError::other)?;
        let per_frame: Vec<StageTimings> = pool.install(|| {
            let mut engine = Engine::new(style.clone(), motion.clone(), config.clone());
            (0..args.frames)
                .map(|i| {
                    engine.frame(i as f64 / 30.0);
                    engine.timings
                })
                .collect()
        });
        let mut med = [0.0f64; 7];
        for (s, m) in med.iter_mut().enumerate().take(6) {
            let mut v: Vec<f64> = per_frame.iter().map(|t| t.as_array()[s]).collect();
            *m = median(&mut v) * 1e3;
        }
        let mut totals: Vec<f64> = per_frame.iter().map(|t| t.total_s() * 1e3).collect();
        med[6] = median(&mut totals);
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
        let mut row = serde_json::Map::new();
        row.insert("threads".into(), threads.into());
        for (name, v) in StageTimings::NAMES.iter().zip(&med[..6]) {
            row.insert(format!("{name}_ms"), (*v).into());
        }
        row.insert("total_ms".into(), med[6].into());
        row.insert("speedup".into(), (base / med[6]).into());
        scaling.push(serde_json::Value::Object(row));
    }
    json.insert("scaling".into(), scaling.into());

    // 2. Speed against error over map resolutions.
    let mut engine = Engine::new(style.clone(), motion.clone(), config.clone());
    engine.run_up_to(args.at_s as f64);
    engine.frame(args.at_s as f64);
    let eye = engine.camera().eye();
    let span = MapGeometry::span_m(style.max_length_m(), style.head_size_m());
    let finest = args.map_res_list.iter().copied().max().unwrap_or(128);
    let reference_res = (finest * 4).min(1024);
    let shade_at = |n: u32, colors: &mut Vec<Vec3>| -> f64 {
        let mut map = LightMap::new(MapGeometry::with_resolution(span, n), CountModel::Poisson);
        let t0 = Instant::now();
        map.build(&MapBuildInput {
            positions: &engine.strands.positions,
            tangents: &engine.strands.tangents,
            lengths_m: &engine.strands.lengths_m,
            fibers_per_strand: style.strands.fibers_per_strand,
            light_dir: config.lighting.light_dir,
            fiber: &engine.fiber,
        });
        shade_vertices(
            &engine.fiber,
            &map,
            &config.lighting,
            eye,
            &engine.strands.positions,
            &engine.strands.tangents,
            colors,
        );
        t0.elapsed().as_secs_f64() * 1e3
    };
    let lum = |c: &Vec3| c.dot(Vec3::new(0.2126, 0.7152, 0.0722)) as f64;
    let mut reference = Vec::new();
    shade_at(reference_res, &mut reference);
    let ref_rms = (reference.iter().map(|c| lum(c).powi(2)).sum::<f64>()
        / reference.len().max(1) as f64)
        .sqrt();
    println!(
        "\nspeed against error (map build + shading of {} vertices; reference: N = {reference_res}):",
        reference.len()
    );
    println!(
        "{:>6} {:>9} {:>12} {:>14}",
        "N", "ds (mm)", "time (ms)", "rel. RMS error"
    );
    let mut rows = Vec::new();
    let mut colors = Vec::new();
    for &n in &args.map_res_list {
        let mut times: Vec<f64> = (0..args.repeats)
            .map(|_| shade_at(n, &mut colors))
            .collect();
        let ms = median(&mut times);
        let err = (colors
            .iter()
            .zip(&reference)
            .map(|(a, b)| (lum(a) - lum(b)).powi(2))
            .sum::<f64>()
            / colors.len().max(1) as f64)
            .sqrt()
            / ref_rms.max(1e-12);
        println!(
            "{n:>6} {:>9.2} {ms:>12.2} {err:>14.4}",
            span / n as f32 * 1e3
        );
        rows.push(serde_json::json!({ "map_res": n, "ds_mm": span / n as f32 * 1e3, "ms": ms, "rel_rms_error": err }));
    }
    json.insert("speed_vs_error".into(), rows.into());
    json.insert("reference_map_res".into(), reference_res.into());
    json.insert("hairstyle".into(), style.name.clone().into());
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&serde_json::Value::Object(json))
            .map_err(AppError::other)?;
        std::fs::write(path, text)
            .map_err(|e| AppError::other(anyhow::anyhow!("{}: {e}", path.display())))?;
    }
    Ok(())
}
