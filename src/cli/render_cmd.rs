//! `wisp render`: the dance (or a still pose) rendered frame by frame to image files.
//!
//! Frames are rendered on the calling thread (each stage parallel inside), converted there to
//! the output format (8-bit sRGB, 16-bit sRGB RGBA, or linear premultiplied RGBA: see
//! [`FormatArg`]), and handed through a bounded crossbeam channel to a writer thread that
//! encodes and writes them (temporary name, then rename: an interrupted export leaves complete
//! frames only). Pixel buffers travel back on a second channel, so the export allocates nothing
//! per frame once running.
//!
//! Before anything large is allocated, the run is checked against the memory and work budget
//! (`wisp::budget`), and the output directory is prepared ([`out_dir`]): it must be a writable
//! directory, and what an earlier export left there (temporary files of a killed run, frames
//! beyond this run's count) is removed, so the folder holds exactly this run's frames.
//!
//! `--resume` keeps the frames already complete on disk (decoded whole, at the run's size and
//! format) and renders the rest. The hair of frame n depends on every frame before it, so
//! without a cache the simulation still runs through the kept frames (up to the last frame to
//! render, not beyond); only their map, shading, raster and encoding are saved. Frames of a
//! cache are independent, and kept ones cost nothing. A progress bar (indicatif) shows frames
//! done, frames per second and the time left on a terminal; it is hidden with `--quiet` and
//! when stderr is not a terminal, where a line every 30 frames stands in for it.

mod out_dir;

use super::{AppError, SceneArgs};
use std::path::PathBuf;
use std::time::Instant;
use wisp::budget::RunPlan;
use wisp::engine::{Engine, StageTimings};
use wisp::output::{FrameFormat, FrameWriter};

pub use super::shard::MAX_FRAMES;
pub use out_dir::{FramePlan, Tidy, plan_frames, prepare_output_dir};

/// `--format`: the file format of the frames.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FormatArg {
    /// 8-bit sRGB RGB PNG, the picture over the background (frame_NNNNN.png).
    Png,
    /// 16-bit RGBA PNG: sRGB colour with straight (not premultiplied) alpha = the hair's and
    /// solids' coverage; transparent black where nothing was drawn (frame_NNNNN.png).
    Png16,
    /// OpenEXR, linear RGBA 32-bit float, colour premultiplied by alpha = coverage
    /// (frame_NNNNN.exr).
    Exr,
}

impl From<FormatArg> for FrameFormat {
    fn from(f: FormatArg) -> Self {
        match f {
            FormatArg::Png => FrameFormat::Png8,
            FormatArg::Png16 => FrameFormat::Png16,
            FormatArg::Exr => FrameFormat::Exr,
        }
    }
}

#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Number of frames to render (default: one loop of the clip at --fps; 1 with --still), at
    /// most 100,000.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_FRAMES as i64))]
    pub frames: Option<u32>,
    /// Output frame rate in frames per second, in (0, 1000] (the simulation step is independent
    /// of it; a cache keeps the rate it was simulated at).
    #[arg(long, default_value_t = 30.0, value_parser = super::parse_fps, allow_hyphen_values = true, conflicts_with = "cache")]
    pub fps: f32,
    /// Time of the first frame in seconds of the motion. The clip loops, so a start beyond one
    /// loop is wrapped into it (the hair's history is simulated from the start of that loop).
    #[arg(long, default_value_t = 0.0, value_parser = super::parse_finite_f64, allow_hyphen_values = true, conflicts_with = "cache")]
    pub start_s: f64,
    /// Output directory (created if missing); frames are frame_00000.png, frame_00001.png, ...
    /// (.exr with --format exr).
    #[arg(long, default_value = "frames")]
    pub out: PathBuf,
    /// Frame file format.
    #[arg(long, value_enum, default_value_t = FormatArg::Png)]
    pub format: FormatArg,
    /// Keep the frames already complete in --out (each decoded whole, at this size and
    /// format) and render only the others. Without --cache the simulation still runs through
    /// the kept frames, which saves their map, shading, raster and encoding.
    #[arg(long)]
    pub resume: bool,
    /// Render the guide states of a simulation cache (`wisp simulate`) instead of simulating:
    /// any scene, shader or size, with the hairstyle and motion the cache was made for. With
    /// --frames, that many frames from --first-frame (default: all of them).
    #[arg(long, value_name = "FILE", conflicts_with_all = ["no_sim", "no_self_collision"])]
    pub cache: Option<PathBuf>,
    /// First cache frame to render (0-based; frames keep their number in file names).
    #[arg(long, requires = "cache", value_parser = clap::value_parser!(u32).range(0..MAX_FRAMES as i64))]
    pub first_frame: Option<u32>,
    /// Render the I-th of N contiguous blocks of the frames (1-based, e.g. 2/8), writing the
    /// file names a whole run writes: one job of a Slurm array or a Kubernetes Indexed Job.
    #[arg(long, value_name = "I/N", requires = "cache", value_parser = super::shard::parse_shard)]
    pub shard: Option<super::shard::Shard>,
    /// Print only errors (no progress bar).
    #[arg(long)]
    pub quiet: bool,
    /// Write the effective scene (scene file and scene flags merged) as JSON to stdout and
    /// exit: a scene file to start from (`--scene` reads it back to the same frames).
    #[arg(long)]
    pub print_scene: bool,
}

/// Where and how an export writes its frames.
#[derive(Clone, Debug)]
pub struct FrameOutput {
    /// The output directory.
    pub dir: PathBuf,
    pub format: FrameFormat,
    /// Keep the frames already complete in `dir`.
    pub resume: bool,
    /// Each frame is rendered from its own stored state (a cache), so a kept frame needs no
    /// work at all; otherwise the simulation must run through it.
    pub independent_frames: bool,
    /// Print only errors.
    pub quiet: bool,
}

impl FrameOutput {
    pub fn of(args: &RenderArgs) -> Self {
        Self {
            dir: args.out.clone(),
            format: args.format.into(),
            resume: args.resume,
            independent_frames: args.cache.is_some(),
            quiet: args.quiet,
        }
    }
}

/// The first frame's time in seconds, wrapped into one loop of the motion (`duration_s /
/// speed` seconds long; a still motion starts at 0), and whether it was wrapped.
pub fn wrapped_start_s(start_s: f64, duration_s: f32, speed: f32) -> (f64, bool) {
    let period = duration_s as f64 / speed as f64;
    if !(period.is_finite() && period > 0.0) {
        return (0.0, start_s != 0.0);
    }
    let wrapped = start_s.rem_euclid(period);
    // rem_euclid can round up to exactly `period` for a tiny negative start.
    let wrapped = if wrapped >= period { 0.0 } else { wrapped };
    (wrapped, wrapped != start_s)
}

/// A single run: simulate and render (`render --cache` goes to `cache_cmd::render_from_cache`).
pub fn run(args: RenderArgs) -> Result<(), AppError> {
    if args.print_scene {
        let (name, file) = args.scene.effective_scene()?;
        file.validate(&name).map_err(AppError::input)?;
        println!("{}", file.to_json());
        return Ok(());
    }
    let (style, hair, motion, mut config) = args.scene.resolve()?;
    let still = args.scene.still;
    let frames = args.frames.unwrap_or_else(|| {
        if still {
            1
        } else {
            let n = (motion.duration_s() as f64 * args.fps as f64).round();
            n.clamp(1.0, MAX_FRAMES as f64) as u32
        }
    });
    let (start_s, wrapped) = wrapped_start_s(args.start_s, motion.duration_s(), motion.speed());
    if wrapped && !args.quiet && motion.duration_s() == 0.0 {
        eprintln!("wisp: the motion is still, so --start-s is ignored");
    } else if wrapped && !args.quiet {
        eprintln!(
            "wisp: --start-s {} is {:.3} s into one {:.3} s loop of the clip; the hair is simulated from the start of that loop",
            args.start_s,
            start_s,
            motion.duration_s() / motion.speed()
        );
    }
    let plan = RunPlan {
        frame_interval_s: 1.0 / args.fps as f64,
        warm_up_s: start_s,
        export_png: true,
        cache: wisp::budget::CacheUse::None,
    };
    args.scene
        .check_budget(&style, &motion, &mut config, &plan)?;
    let output = FrameOutput::of(&args);
    prepare_output_dir(
        &args.out,
        &Tidy::whole_run(frames),
        output.format,
        args.quiet,
    )?;
    let todo = plan_frames(&output, 0..frames, config.scene.width, config.scene.height);
    if todo.nothing_to_render() {
        return Ok(());
    }
    let name = style.name.clone();
    let started = Instant::now();
    let mut engine = super::engine(style, hair, motion, config);
    engine.run_up_to(start_s);
    let setup_s = started.elapsed().as_secs_f64();
    if !args.quiet {
        let g = engine.map_geometry();
        let pieces = match engine.interpolation.config.segment_pieces {
            0 | 1 => String::new(),
            k => format!(" cut into {k} pieces"),
        };
        eprintln!(
            "wisp: {} ({} wisps, {} strands, {} segments{pieces}), clip \"{}\" {:.2} s, map {}^3 cells of {:.1} mm, {}x{} px, set-up {:.2} s",
            super::printable(&name),
            engine.layout.wisp_guides.len(),
            engine.layout.count(),
            engine.layout.segments(),
            super::printable(engine.motion().clip_name()),
            engine.motion().duration_s(),
            g.n,
            g.ds_m * 1e3,
            engine.scene.width,
            engine.scene.height,
            setup_s
        );
    }
    let fps = args.fps as f64;
    export_frames(&mut engine, &todo, &output, started, |engine, i| {
        let t = start_s + i as f64 / fps;
        engine.advance(t);
        Ok(t)
    })
}

/// The progress bar of an export of `len` frames, on stderr: hidden when quiet, and by
/// indicatif when stderr is not a terminal.
fn progress_bar(len: usize, quiet: bool) -> indicatif::ProgressBar {
    if quiet {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len as u64);
    let style = indicatif::ProgressStyle::with_template(
        "wisp: {pos}/{len} frames, {fps} frames/s, ETA {eta}, {msg} [{wide_bar}]",
    )
    .map(|s| {
        s.progress_chars("=> ").with_key(
            "fps",
            |state: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
                let _ = write!(w, "{:.2}", state.per_sec());
            },
        )
    });
    if let Ok(style) = style {
        bar.set_style(style);
    }
    bar
}

/// Renders the frames of `plan` not kept and writes them to `output` as `frame_NNNNN.EXT`
/// (numbered by index) through a writer thread. `hair_at(engine, i)` puts the hair of frame
/// `i` in place (simulated, or read from a cache) and returns its time; the engine renders
/// it. Kept frames go through `hair_at` too, up to the last frame to render, unless the
/// output's frames are independent.
pub fn export_frames(
    engine: &mut Engine,
    plan: &FramePlan,
    output: &FrameOutput,
    started: Instant,
    mut hair_at: impl FnMut(&mut Engine, u32) -> Result<f64, AppError>,
) -> Result<(), AppError> {
    let format = output.format;
    let quiet = output.quiet;
    let mut writer = FrameWriter::start(output.dir.clone(), format);
    let mut total = StageTimings::default();
    let background = engine.scene.background;
    let frames = plan.indices.len();
    let last = plan.last_to_render();
    // Kept frames that need no work: all of them when frames are independent, else those
    // after the last frame to render (the simulation stops there).
    let passed_freely = |i: u32, kept: bool| kept && (output.independent_frames || Some(i) > last);
    let free = plan
        .indices
        .clone()
        .zip(&plan.kept)
        .filter(|(i, k)| passed_freely(*i, **k))
        .count();
    let bar = progress_bar(frames, quiet);
    bar.set_position(free as u64);
    bar.reset_eta();
    let (mut rendered, mut simulated_only) = (0u32, 0u32);
    let mut simulated_only_s = 0.0;
    let mut failed = None;
    let mut hair_error = None;
    for (i, &kept) in plan.indices.clone().zip(&plan.kept) {
        if passed_freely(i, kept) {
            continue;
        }
        let t = match hair_at(engine, i) {
            Ok(t) => t,
            Err(e) => {
                hair_error = Some(e);
                break;
            }
        };
        bar.set_message(format!("t = {t:.2} s"));
        if kept {
            simulated_only += 1;
            simulated_only_s += engine.timings.animation_s
                + engine.timings.simulation_s
                + engine.timings.interpolation_s;
            bar.inc(1);
            continue;
        }
        engine.render();
        if rendered == 0 {
            bar.suspend(|| warn_about_first_frame(engine));
        }
        rendered += 1;
        total.add(&engine.timings);
        if writer.write(engine.framebuffer(), background, i).is_err() {
            failed = Some(i);
            break;
        }
        bar.inc(1);
        let done = bar.position();
        if !quiet && bar.is_hidden() && done.is_multiple_of(30) {
            eprintln!("wisp: frame {done}/{frames} (t = {t:.2} s)");
        }
    }
    bar.finish_and_clear();
    let output_s = writer.finish().map_err(AppError::other)?;
    if let Some(e) = hair_error {
        return Err(e);
    }
    if let Some(i) = failed {
        return Err(AppError::other(anyhow::anyhow!(
            "frame {i}: the frame writer stopped"
        )));
    }
    if !quiet {
        print_timings(&total, rendered, started.elapsed().as_secs_f64());
        let per_frame_ms = |s: f64| s * 1e3 / f64::from(rendered.max(1));
        eprintln!(
            "wisp: output ({}, ms per frame): conversion {:.1}, encoding and writing {:.1} (on the writer thread, beside the next frame)",
            format.describe(),
            per_frame_ms(output_s.convert_s),
            per_frame_ms(output_s.write_s)
        );
        let shown = output.dir.display();
        let range = if plan.indices.start == 0 {
            String::new()
        } else {
            format!(" ({} to {})", plan.indices.start, plan.indices.end - 1)
        };
        let kept = frames - rendered as usize;
        if kept == 0 {
            eprintln!("wisp: wrote {rendered} frames{range} to {shown}");
        } else {
            let through = if simulated_only > 0 {
                format!(
                    " ({simulated_only} of them simulated through, {:.1} ms each)",
                    simulated_only_s * 1e3 / f64::from(simulated_only)
                )
            } else {
                String::new()
            };
            eprintln!(
                "wisp: wrote {rendered} frames and kept {kept} complete ones{through} of {frames}{range} in {shown}"
            );
        }
    }
    Ok(())
}

/// Says on stderr what makes the first frame wrong or empty, instead of writing blank frames
/// silently: render points that are not finite, hair wider than the map, a picture with
/// nothing but background.
pub fn warn_about_first_frame(engine: &Engine) {
    let stats = engine.map_stats();
    if stats.skipped > 0 {
        eprintln!(
            "wisp: warning: {} of {} render points are not finite numbers and are not drawn",
            stats.skipped,
            stats.skipped + stats.samples
        );
    }
    if stats.overflow {
        let g = engine.map_geometry();
        eprintln!(
            "wisp: warning: the hair extends beyond the light map ({} cells of {:.1} mm per axis), so far-apart hair shadows itself; the map is sized for hair no longer than the hairstyle's guides",
            g.n,
            g.ds_m * 1e3
        );
    }
    let fb = engine.framebuffer();
    let background = engine.scene.background;
    if fb.color.iter().all(|c| *c == background) {
        eprintln!(
            "wisp: warning: the first frame shows only the background: the head and the hair are out of view"
        );
    }
}

/// Mean per-stage milliseconds per frame, on stderr.
pub fn print_timings(total: &StageTimings, frames: u32, wall_s: f64) {
    let mean = total.scaled(1.0 / frames.max(1) as f64);
    let parts: Vec<String> = StageTimings::NAMES
        .iter()
        .zip(mean.as_array())
        .map(|(n, v)| format!("{n} {:.1}", v * 1e3))
        .collect();
    eprintln!(
        "wisp: per frame (ms): {} | total {:.1} ms; wall {:.1} s for {} frames",
        parts.join(", "),
        mean.total_s() * 1e3,
        wall_s,
        frames
    );
}

#[cfg(test)]
mod tests;
