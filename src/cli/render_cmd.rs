//! `wisp render`: the dance (or a still pose) rendered frame by frame to image files.
//!
//! A single run simulates the hair up to the first frame and then frame by frame, rendering
//! each ([`run`]); `render --cache` reads the hair of each frame from a simulation cache
//! instead (`cache_cmd::render_from_cache`). Both end in [`export_frames`]: each frame
//! rendered on the calling thread and written by a writer thread ([`export`]).
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
//! cache are independent, and kept ones cost nothing.

mod curves;
mod export;
mod out_dir;

use super::{AppError, SceneArgs};
use std::path::PathBuf;
use std::time::Instant;
use wisp::budget::RunPlan;
use wisp::engine::Engine;
use wisp::motion::Motion;
use wisp::output::FrameFormat;
use wisp::scene::Scene;

pub use super::shard::MAX_FRAMES;
pub use curves::CurvesOutput;
pub use export::export_frames;
pub use out_dir::{FramePlan, Tidy, plan_frames, prepare_output_dir};

/// `--format`: the file format of the frames (frame_NNNNN.png or .exr).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FormatArg {
    // 8-bit sRGB RGB PNG, the picture over the background.
    Png,
    // 16-bit RGBA PNG: sRGB colour with straight (not premultiplied) alpha = the hair's and
    // solids' coverage; transparent black where nothing was drawn.
    Png16,
    // OpenEXR, linear RGBA 32-bit float, colour premultiplied by alpha = coverage.
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
    /// Frames, at most 100000 [default: one loop of the clip; 1 with --still]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=MAX_FRAMES as i64))]
    pub frames: Option<u32>,
    /// Frames per second of the motion, in (0, 1000]
    #[arg(long, default_value_t = 30.0, value_parser = super::parse_fps, allow_hyphen_values = true, conflicts_with = "cache")]
    pub fps: f32,
    /// First frame's time, seconds, wrapped into the clip's loop
    #[arg(long, value_name = "SECONDS", default_value_t = 0.0, value_parser = super::parse_finite_f64, allow_hyphen_values = true, conflicts_with = "cache")]
    pub start_s: f64,
    /// Output directory for frame_NNNNN.png/.exr (created)
    #[arg(long, value_name = "DIR", default_value = "frames")]
    pub out: PathBuf,
    /// Frame file format
    #[arg(long, value_enum, default_value_t = FormatArg::Png)]
    pub format: FormatArg,
    /// Keep the frames already complete in --out and render only the others
    #[arg(long)]
    pub resume: bool,
    /// Also write each frame's hair strands to FILE.usda (USD curves, for Blender/Houdini)
    #[arg(long, value_name = "FILE", value_parser = curves::parse_curves_path, conflicts_with_all = ["resume", "shard"])]
    pub curves: Option<PathBuf>,
    /// Print only errors (no progress bar)
    #[arg(long)]
    pub quiet: bool,
    /// Print the effective scene (scene file and flags merged) as JSON, and exit
    #[arg(long)]
    pub print_scene: bool,
    /// Render from a simulation cache (`wisp simulate`) instead of simulating
    #[arg(long, value_name = "FILE", help_heading = "Cache", conflicts_with_all = ["no_sim", "no_self_collision"])]
    pub cache: Option<PathBuf>,
    /// First cache frame to render, 0-based, named as in a whole run [default: 0]
    #[arg(long, value_name = "N", help_heading = "Cache", requires = "cache", value_parser = clap::value_parser!(u32).range(0..MAX_FRAMES as i64))]
    pub first_frame: Option<u32>,
    /// Render the I-th of N contiguous blocks of the frames (1-based, e.g. 2/8)
    #[arg(long, value_name = "I/N", help_heading = "Cache", requires = "cache", value_parser = super::shard::parse_shard)]
    pub shard: Option<super::shard::Shard>,
    #[command(flatten)]
    pub scene: SceneArgs,
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
    /// Where the render strands of every rendered frame go, if anywhere (`--curves`).
    pub curves: Option<CurvesOutput>,
}

impl FrameOutput {
    /// The output `args` ask for; `--curves` with the frames' rate `fps` and the time of
    /// frame 0, `start_s`.
    pub fn of(args: &RenderArgs, fps: f64, start_s: f64) -> Self {
        Self {
            dir: args.out.clone(),
            format: args.format.into(),
            resume: args.resume,
            independent_frames: args.cache.is_some(),
            quiet: args.quiet,
            curves: args
                .curves
                .clone()
                .map(|path| CurvesOutput { path, fps, start_s }),
        }
    }

    /// Makes the output directory ready (tidied as `tidy` allows; the `--curves` file's
    /// directory checked) and plans the frames of `indices` at the scene's image size;
    /// `None` when every one of them is already complete (`--resume`) and there is nothing
    /// to render.
    pub fn prepare(
        &self,
        tidy: &Tidy,
        indices: std::ops::Range<u32>,
        scene: &Scene,
    ) -> Result<Option<FramePlan>, AppError> {
        if let Some(curves) = &self.curves {
            curves.check_dir()?;
        }
        prepare_output_dir(&self.dir, tidy, self.format, self.quiet)?;
        let todo = plan_frames(self, indices, scene.width, scene.height);
        Ok((!todo.nothing_to_render()).then_some(todo))
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

/// The frames of a run not given `--frames`: one loop of the clip at `fps` (at least 1, at
/// most [`MAX_FRAMES`]), or 1 for a still head.
pub fn default_frame_count(still: bool, motion: &Motion, fps: f32) -> u32 {
    if still {
        return 1;
    }
    let n = (motion.duration_s() as f64 * fps as f64).round();
    n.clamp(1.0, MAX_FRAMES as f64) as u32
}

/// A single run: simulate and render (`render --cache` goes to `cache_cmd::render_from_cache`).
pub fn run(args: RenderArgs) -> Result<(), AppError> {
    if args.print_scene {
        let (name, file) = args.scene.scene_file.effective()?;
        file.validate(&name).map_err(AppError::input)?;
        println!("{}", file.to_json());
        return Ok(());
    }
    let (style, hair, motion, mut config) = args.scene.resolve()?;
    let frames = args
        .frames
        .unwrap_or_else(|| default_frame_count(args.scene.motion.still, &motion, args.fps));
    let start_s = start_time_s(&args, &motion);
    let plan = RunPlan {
        frame_interval_s: 1.0 / args.fps as f64,
        warm_up_s: start_s,
        export_png: true,
        cache: wisp::budget::CacheUse::None,
    };
    args.scene
        .budget
        .check(&style, &motion, &mut config, &plan)?;
    let output = FrameOutput::of(&args, f64::from(args.fps), start_s);
    let Some(todo) = output.prepare(&Tidy::whole_run(frames), 0..frames, &config.scene)? else {
        return Ok(());
    };
    let name = style.name.clone();
    let started = Instant::now();
    let mut engine = super::engine(style, hair, motion, config);
    engine.run_up_to(start_s);
    let setup_s = started.elapsed().as_secs_f64();
    if !args.quiet {
        print_setup(&engine, &name, setup_s);
    }
    let fps = args.fps as f64;
    export_frames(&mut engine, &todo, &output, started, |engine, i| {
        let t = start_s + i as f64 / fps;
        engine.advance(t);
        Ok(t)
    })
}

/// `--start-s` wrapped into one loop of the clip, saying so on stderr when it was.
fn start_time_s(args: &RenderArgs, motion: &Motion) -> f64 {
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
    start_s
}

/// What is rendered, on stderr: the hairstyle `name`, its hair, the clip, the map, the image
/// size and the set-up time.
fn print_setup(engine: &Engine, name: &str, setup_s: f64) {
    let g = engine.map_geometry();
    let pieces = match engine.interpolation.config.segment_pieces {
        0 | 1 => String::new(),
        k => format!(" cut into {k} pieces"),
    };
    eprintln!(
        "wisp: {} ({} wisps, {} strands, {} segments{pieces}), clip \"{}\" {:.2} s, map {}^3 cells of {:.1} mm, {}x{} px, set-up {:.2} s",
        super::printable(name),
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

#[cfg(test)]
mod tests;
