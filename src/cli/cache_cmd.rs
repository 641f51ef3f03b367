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
    FrameOutput, MAX_FRAMES, RenderArgs, Tidy, export_frames, plan_frames, prepare_output_dir,
};
use super::shard::Shard;
use super::{AppError, SceneArgs, printable};
use std::path::PathBuf;
use std::time::Instant;
use wisp::budget::{CacheUse, RunPlan};
use wisp::cache::{CacheError, CacheHeader, CacheReader, CacheWriter, Expected};
use wisp::engine::Engine;
use wisp::motion::Motion;

#[derive(clap::Args, Debug)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Cache file to write (written as `FILE.tmp`, renamed when complete).
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Number of frames (default: one loop of the clip at --fps; 1 with --still), at most
    /// 100,000.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_FRAMES as i64))]
    pub frames: Option<u32>,
    /// Frame rate in frames per second, in (0, 1000].
    #[arg(long, default_value_t = 30.0, value_parser = super::parse_fps, allow_hyphen_values = true)]
    pub fps: f32,
    /// Time of the first frame in seconds of the motion (wrapped into one loop of the clip,
    /// as for `render`).
    #[arg(long, default_value_t = 0.0, value_parser = super::parse_finite_f64, allow_hyphen_values = true)]
    pub start_s: f64,
    /// Print only errors.
    #[arg(long)]
    pub quiet: bool,
}

/// A cache error with its exit code (2 for a bad or mismatched file, 1 for a failed write).
fn cache_error(e: CacheError) -> AppError {
    if e.is_bad_input() {
        AppError::input(e)
    } else {
        AppError::other(e)
    }
}

/// What the motion flags chose, for the cache's header and messages.
fn motion_label(scene: &SceneArgs, motion: &Motion) -> String {
    if scene.still {
        return "--still (no motion)".to_string();
    }
    let file = scene.animation.as_ref().map_or_else(
        || "the embedded dance".to_string(),
        |p| p.display().to_string(),
    );
    format!(
        "clip \"{}\" of {file}, head joint \"{}\", speed {}",
        motion.clip_name(),
        motion.head_joint().1,
        motion.speed()
    )
}

/// The simulation cache is keyed by a generated hairstyle (its guides are regenerated when the
/// cache is read); an imported groom's guides come from its files, so it is not cached yet.
fn refuse_imported(hair: &super::ImportedHair) -> Result<(), AppError> {
    match hair {
        Some(_) => Err(AppError::input(anyhow::anyhow!(
            "--hairstyle: the simulation cache (simulate, render --cache) works with generated hairstyles only; render an imported groom (.tfx, .hair) without --cache"
        ))),
        None => Ok(()),
    }
}

pub fn simulate(args: SimulateArgs) -> Result<(), AppError> {
    let (style, hair, motion, mut config) = args.scene.resolve()?;
    refuse_imported(&hair)?;
    let frames = args.frames.unwrap_or_else(|| {
        if args.scene.still {
            1
        } else {
            let n = (motion.duration_s() as f64 * args.fps as f64).round();
            n.clamp(1.0, MAX_FRAMES as f64) as u32
        }
    });
    let (start_s, wrapped) =
        super::render_cmd::wrapped_start_s(args.start_s, motion.duration_s(), motion.speed());
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
        .check_budget(&style, &motion, &mut config, &plan)?;
    let label = motion_label(&args.scene, &motion);
    let expected = Expected::new(&style, &motion, &label);
    let header = CacheHeader {
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
        map_res: wisp::engine::map_geometry(&style, &config.hair_map).n,
        simulated: config.simulation.simulate,
        self_collision: config.simulation.self_collision,
        draw_solids: config.scene.draw_solids,
        hairstyle_name: style.name.clone(),
        motion_label: label,
    };
    // Created before the work starts, so a bad --out is refused at once.
    let mut writer = CacheWriter::create(&args.out, header.clone()).map_err(cache_error)?;
    let started = Instant::now();
    let name = style.name.clone();
    let mut engine = Engine::new(style, motion, config);
    let write_err = cache_error;
    if engine.simulation.state.positions.len() != header.particles as usize {
        return Err(AppError::other(anyhow::anyhow!(
            "the engine has {} guide particles, the hairstyle implies {}",
            engine.simulation.state.positions.len(),
            header.particles
        )));
    }
    writer
        .write_sim_state(0.0, &engine.simulation.state)
        .map_err(write_err)?;
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
    let mut sim_s = 0.0;
    let mut write_s = 0.0;
    for i in 0..frames {
        let t = header.frame_time_s(i);
        let t0 = Instant::now();
        engine.advance(t);
        let t1 = Instant::now();
        writer
            .write_sim_state(t, &engine.simulation.state)
            .map_err(write_err)?;
        write_s += t1.elapsed().as_secs_f64();
        sim_s += (t1 - t0).as_secs_f64();
        if !args.quiet && (i + 1) % 30 == 0 {
            eprintln!("wisp: frame {}/{frames} (t = {t:.2} s)", i + 1);
        }
    }
    let t0 = Instant::now();
    writer.finish().map_err(write_err)?;
    write_s += t0.elapsed().as_secs_f64();
    if !args.quiet {
        let bytes = header.file_bytes();
        eprintln!(
            "wisp: per frame: simulation {:.1} ms, writing {:.2} ms ({:.1} KB a frame); wall {:.1} s",
            sim_s * 1e3 / frames as f64,
            write_s * 1e3 / frames as f64,
            header.record_bytes() as f64 / 1e3,
            started.elapsed().as_secs_f64()
        );
        eprintln!(
            "wisp: wrote {} ({}, {frames} frames and the settled state)",
            args.out.display(),
            wisp::input::human_bytes(bytes)
        );
    }
    Ok(())
}

/// `wisp render --cache FILE [--first-frame F] [--frames N] [--shard I/N]`.
pub fn render_from_cache(args: RenderArgs) -> Result<(), AppError> {
    let Some(path) = args.cache.clone() else {
        return Err(AppError::other(anyhow::anyhow!("no --cache given")));
    };
    let (style, hair, motion, mut config) = args.scene.resolve()?;
    refuse_imported(&hair)?;
    let label = motion_label(&args.scene, &motion);
    let expected = Expected::new(&style, &motion, &label);
    let mut reader = CacheReader::open(&path, &expected).map_err(cache_error)?;
    let header = reader.header().clone();
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
        return Ok(());
    }
    let plan = RunPlan {
        frame_interval_s: 1.0 / header.fps as f64,
        warm_up_s: 0.0,
        export_png: true,
        cache: CacheUse::Read,
    };
    args.scene
        .check_budget(&style, &motion, &mut config, &plan)?;
    // Shards share the folder: each removes only its own frames' temporary files, and frames
    // beyond the cache when it renders a block of the whole cache.
    let whole = args.first_frame.is_none() && args.frames.is_none();
    let tidy = match (args.shard, whole) {
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
    };
    let output = FrameOutput::of(&args);
    prepare_output_dir(&args.out, &tidy, output.format, args.quiet)?;
    let todo = plan_frames(
        &output,
        part.clone(),
        config.scene.width,
        config.scene.height,
    );
    if todo.nothing_to_render() {
        return Ok(());
    }
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
        let t = header.frame_time_s(i);
        let positions = reader.read_frame(i, engine.motion()).map_err(cache_error)?;
        engine.set_guide_state(t, positions);
        Ok(t)
    })
}
