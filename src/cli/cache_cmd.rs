//! `wisp simulate` (a simulation cache of a run) and `wisp render --cache` (frames, a frame
//! range or one shard of them, rendered from a cache without simulating). See `wisp::cache`
//! for the format and why a cached frame is the same bytes as a frame of a single run.
//!
//! `simulate` makes exactly the calls `render` makes, minus shading and raster: the engine is
//! built and settled, advanced to the first frame, then advanced frame by frame. The motion
//! depends on nothing the render chooses (self-collision reads the simulator's own density
//! grid, not the light map), so a cache renders in any light, map size or image size and
//! gives the frames a single run with those flags would. Each frame's guide state is written
//! as soon as it exists.

use super::render_cmd::{
    FrameOutput, MAX_FRAMES, RenderArgs, Tidy, default_frame_count, export_frames, wrapped_start_s,
};
use super::shard::Shard;
use super::{AppError, SceneArgs, printable};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::time::Instant;
use wisp::budget::{CacheUse, RunPlan};
use wisp::cache::{CacheError, CacheHeader, CacheReader, CacheWriter, Expected};
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

#[derive(clap::Args, Debug)]
pub struct SimulateArgs {
    /// Cache file to write (as FILE.tmp, renamed when complete)
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Frames, at most 100000 [default: one loop of the clip; 1 with --still]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=MAX_FRAMES as i64))]
    pub frames: Option<u32>,
    /// Frames per second of the motion, in (0, 1000]
    #[arg(long, default_value_t = 30.0, value_parser = super::parse_fps, allow_hyphen_values = true)]
    pub fps: f32,
    /// First frame's time, seconds, wrapped into the clip's loop
    #[arg(long, value_name = "SECONDS", default_value_t = 0.0, value_parser = super::parse_finite_f64, allow_hyphen_values = true)]
    pub start_s: f64,
    /// Print only errors
    #[arg(long)]
    pub quiet: bool,
    #[command(flatten)]
    pub scene: SceneArgs,
}

/// A cache error with its exit code (2 for a bad or mismatched file, 1 for a failed write).
fn cache_error(e: CacheError) -> AppError {
    if e.is_bad_input() {
        AppError::input(e)
    } else {
        AppError::other(e)
    }
}

/// The simulation cache is keyed by a generated hairstyle (its guides are regenerated when the
/// cache is read); an imported groom's guides come from its files, which a cache does not
/// hold, so a groom is refused (exit code 2).
fn refuse_imported(hair: &super::ImportedHair) -> Result<(), AppError> {
    match hair {
        Some(_) => Err(AppError::input(anyhow::anyhow!(
            "--hairstyle: the simulation cache (simulate, render --cache) works with generated hairstyles only; render an imported groom (.tfx, .hair, .ply, .data) without --cache"
        ))),
        None => Ok(()),
    }
}

/// `wisp simulate`: the settled state and every frame's guide state, written to the cache.
pub fn simulate(args: SimulateArgs) -> Result<(), AppError> {
    let (style, hair, motion, mut config) = args.scene.resolve()?;
    refuse_imported(&hair)?;
    let frames = args
        .frames
        .unwrap_or_else(|| default_frame_count(args.scene.motion.still, &motion, args.fps));
    let (start_s, wrapped) = wrapped_start_s(args.start_s, motion.duration_s(), motion.speed());
    if wrapped && !args.quiet {
        eprintln!(
            "wisp: --start-s {} is wrapped to {start_s:.3} s (one loop of the clip, or 0 for a still motion)",
            args.start_s
        );
    }
    let plan = RunPlan {
        frame_interval_s: 1.0 / args.fps as f64,
        warm_up_s: start_s,
        export_png: false,
        cache: CacheUse::Write,
    };
    args.scene
        .budget
        .check(&style, &motion, &mut config, &plan)?;
    let header = cache_header(&args, &style, &motion, &config, frames, start_s);
    // Created before the work starts, so a bad --out is refused at once.
    let mut writer = CacheWriter::create(&args.out, header.clone()).map_err(cache_error)?;
    let started = Instant::now();
    let name = style.name.clone();
    let mut engine = Engine::new(style, motion, config);
    if engine.simulation.state.positions.len() != header.particles as usize {
        return Err(AppError::other(anyhow::anyhow!(
            "the engine has {} guide particles, the hairstyle implies {}",
            engine.simulation.state.positions.len(),
            header.particles
        )));
    }
    writer
        .write_sim_state(0.0, &engine.simulation.state)
        .map_err(cache_error)?;
    engine.run_up_to(start_s);
    if !args.quiet {
        eprintln!(
            "wisp: simulating {} ({} guide particles), clip \"{}\", {frames} frames at {} fps from {start_s:.3} s into {}",
            printable(&name),
            header.particles,
            printable(engine.motion().clip_name()),
            args.fps,
            args.out.display()
        );
    }
    let (sim_s, write_s) = simulate_frames(&mut engine, writer, &header, args.quiet)?;
    if !args.quiet {
        report_cache(&args.out, &header, sim_s, write_s, started);
    }
    Ok(())
}

/// The header of the cache `args` asks for, of the run of `style`, `motion` and `config`:
/// what it holds, and what it was simulated from (checked when it is read).
fn cache_header(
    args: &SimulateArgs,
    style: &Hairstyle,
    motion: &Motion,
    config: &EngineConfig,
    frames: u32,
    start_s: f64,
) -> CacheHeader {
    let label = args.scene.motion.label(motion, !config.scene.draw_solids);
    let expected = Expected::new(style, motion, &label);
    CacheHeader {
        frames,
        particles: expected.particles,
        points_per_guide: expected.points_per_guide,
        fps: args.fps,
        start_s,
        settle_s: config.simulation.settle_s,
        hairstyle_digest: expected.hairstyle_digest,
        motion_digest: expected.motion_digest,
        light_dir: config
            .scene
            .lights
            .first()
            .and_then(|l| l.travel())
            .unwrap_or(glam::Vec3::NEG_Y),
        map_res: wisp::engine::map_geometry(style, &config.hair_map).n,
        simulated: config.simulation.simulate,
        self_collision: config.simulation.self_collision,
        draw_solids: config.scene.draw_solids,
        hairstyle_name: style.name.clone(),
        motion_label: label,
    }
}

/// Advances the engine through the header's frames, writing each guide state as soon as it
/// exists, and finishes the file; returns the seconds spent simulating and writing.
fn simulate_frames(
    engine: &mut Engine,
    mut writer: CacheWriter,
    header: &CacheHeader,
    quiet: bool,
) -> Result<(f64, f64), AppError> {
    let frames = header.frames;
    let mut sim_s = 0.0;
    let mut write_s = 0.0;
    for i in 0..frames {
        let t = header.frame_time_s(i);
        let t0 = Instant::now();
        engine.advance(t);
        let t1 = Instant::now();
        writer
            .write_sim_state(t, &engine.simulation.state)
            .map_err(cache_error)?;
        write_s += t1.elapsed().as_secs_f64();
        sim_s += (t1 - t0).as_secs_f64();
        if !quiet && (i + 1) % 30 == 0 {
            eprintln!("wisp: frame {}/{frames} (t = {t:.2} s)", i + 1);
        }
    }
    let t0 = Instant::now();
    writer.finish().map_err(cache_error)?;
    write_s += t0.elapsed().as_secs_f64();
    Ok((sim_s, write_s))
}

/// The cache's summary on stderr: time per frame and what was written where.
fn report_cache(out: &Path, header: &CacheHeader, sim_s: f64, write_s: f64, started: Instant) {
    let frames = header.frames;
    eprintln!(
        "wisp: per frame: simulation {:.1} ms, writing {:.2} ms ({:.1} KB a frame); wall {:.1} s",
        sim_s * 1e3 / frames as f64,
        write_s * 1e3 / frames as f64,
        header.record_bytes() as f64 / 1e3,
        started.elapsed().as_secs_f64()
    );
    eprintln!(
        "wisp: wrote {} ({}, {frames} frames and the settled state)",
        out.display(),
        wisp::input::human_bytes(header.file_bytes())
    );
}

/// `wisp render --cache FILE [--first-frame F] [--frames N] [--shard I/N]`.
pub fn render_from_cache(args: RenderArgs) -> Result<(), AppError> {
    let Some(path) = args.cache.clone() else {
        return Err(AppError::other(anyhow::anyhow!("no --cache given")));
    };
    let (style, hair, motion, mut config) = args.scene.resolve()?;
    refuse_imported(&hair)?;
    let label = args.scene.motion.label(&motion, !config.scene.draw_solids);
    let expected = Expected::new(&style, &motion, &label);
    let mut reader = CacheReader::open(&path, &expected).map_err(cache_error)?;
    let header = reader.header().clone();
    let Some(part) = frames_of_cache(&args, &path, &header)? else {
        return Ok(());
    };
    let plan = RunPlan {
        frame_interval_s: 1.0 / header.fps as f64,
        warm_up_s: 0.0,
        export_png: true,
        cache: CacheUse::Read,
    };
    args.scene
        .budget
        .check(&style, &motion, &mut config, &plan)?;
    let output = FrameOutput::of(&args, f64::from(header.fps), header.start_s);
    let tidy = tidy_for_cache(&args, &header, &part);
    let Some(todo) = output.prepare(&tidy, part.clone(), &config.scene)? else {
        return Ok(());
    };
    let started = Instant::now();
    let settled = reader.read_settled(&motion).map_err(cache_error)?.to_vec();
    let mut engine = Engine::from_settled(style, motion, config, &settled);
    if engine.simulation.state.positions.len() != settled.len() {
        return Err(AppError::input(anyhow::anyhow!(
            "{}: holds {} guide particles, this hairstyle makes {}",
            path.display(),
            settled.len(),
            engine.simulation.state.positions.len()
        )));
    }
    if !args.quiet {
        let shard = args.shard.map_or(String::new(), |s| {
            format!(", shard {}/{}", s.index, s.count)
        });
        eprintln!(
            "wisp: rendering frames {} to {} of {}{shard} ({}x{} px, map {}^3), set-up {:.2} s",
            part.start,
            part.end - 1,
            path.display(),
            engine.scene.width,
            engine.scene.height,
            engine.map_geometry().n,
            started.elapsed().as_secs_f64()
        );
    }
    export_frames(&mut engine, &todo, &output, started, |engine, i| {
        light_paths_from_slot_start(engine, &mut reader, &header, i)?;
        let t = header.frame_time_s(i);
        let positions = reader.read_frame(i, engine.motion()).map_err(cache_error)?;
        engine.set_guide_state(t, positions);
        Ok(t)
    })
}

/// With light paths built once per slot of motion (`ShadingConfig::paths_interval_s`): when
/// cache frame `i`'s slot began at an earlier frame and its paths are not built (a shard or
/// `--first-frame` that starts inside a slot), the slot's first frame is set first, so that
/// the paths are built from its hair as a run from the start builds them.
fn light_paths_from_slot_start(
    engine: &mut Engine,
    reader: &mut CacheReader,
    header: &CacheHeader,
    i: u32,
) -> Result<(), AppError> {
    let Some(slot) = engine.light_paths_slot(header.frame_time_s(i)) else {
        return Ok(());
    };
    if engine.light_paths_built_in(slot) {
        return Ok(());
    }
    let mut first = i;
    while first > 0 && engine.light_paths_slot(header.frame_time_s(first - 1)) == Some(slot) {
        first -= 1;
    }
    if first < i {
        let positions = reader
            .read_frame(first, engine.motion())
            .map_err(cache_error)?;
        engine.set_guide_state(header.frame_time_s(first), positions);
    }
    Ok(())
}

/// The cache frames this run renders: `--frames` from `--first-frame` (all from it by
/// default), checked against what the cache at `path` holds, and of those the `--shard`'s
/// block. `None` (with a message) when the shard has no frames.
fn frames_of_cache(
    args: &RenderArgs,
    path: &Path,
    header: &CacheHeader,
) -> Result<Option<Range<u32>>, AppError> {
    let first = args.first_frame.unwrap_or(0);
    if first >= header.frames {
        return Err(AppError::input(anyhow::anyhow!(
            "--first-frame {first}: {} holds frames 0 to {}",
            path.display(),
            header.frames - 1
        )));
    }
    let available = header.frames - first;
    let count = args.frames.unwrap_or(available);
    if count > available {
        return Err(AppError::input(anyhow::anyhow!(
            "--frames {count}: {} holds {available} frames from frame {first} (0 to {})",
            path.display(),
            header.frames - 1
        )));
    }
    let range = first..first + count;
    let part = match args.shard {
        Some(s) => s.block(range.clone()),
        None => range.clone(),
    };
    if part.is_empty() {
        if !args.quiet {
            let s = args.shard.unwrap_or(Shard { index: 1, count: 1 });
            eprintln!(
                "wisp: shard {}/{} has no frames ({} shards for {} frames); nothing to do",
                s.index,
                s.count,
                s.count,
                range.len()
            );
        }
        return Ok(None);
    }
    Ok(Some(part))
}

/// What a render of the cache frames `part` may tidy in its output directory. Shards share the
/// folder: each removes only its own frames' temporary files, and frames beyond the cache when
/// it renders a block of the whole cache.
fn tidy_for_cache(args: &RenderArgs, header: &CacheHeader, part: &Range<u32>) -> Tidy {
    let whole = args.first_frame.is_none() && args.frames.is_none();
    match (args.shard, whole) {
        (None, true) => Tidy::whole_run(header.frames),
        (Some(_), true) => Tidy {
            own: part.clone(),
            all_temporaries: false,
            stale_from: Some(header.frames),
        },
        (_, false) => Tidy {
            own: part.clone(),
            all_temporaries: false,
            stale_from: None,
        },
    }
}
