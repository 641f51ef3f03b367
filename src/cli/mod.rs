//! Command-line edge: argument parsing, degrees and file formats live here, nowhere deeper.
//!
//! Exit codes: 0 success, 2 bad input (flags or files), 1 any other failure.

pub mod accuracy_cmd;
pub mod bench_cmd;
pub mod export_cmd;
pub mod fiber_cmd;
pub mod play_cmd;
pub mod render_cmd;
pub mod view_args;

use clap::{Parser, Subcommand, ValueEnum};
use glam::Vec3;
use std::path::PathBuf;
use std::process::ExitCode;
use wisp::fiber::ShadingMode;
use wisp::frame::EngineConfig;
use wisp::hairstyle::Hairstyle;
use wisp::motion::{JointRef, Motion, MotionOptions};

#[derive(Parser, Debug)]
#[command(
    name = "wisp",
    version,
    about = "Animate and render human hair on the CPU"
)]
pub struct Cli {
    /// Worker threads for the parallel stages (default: all cores). Output does not depend on it.
    #[arg(long, global = true, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub threads: Option<u32>,
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render the dance (default: the embedded dance and the `smooth` hairstyle) to PNG frames.
    #[command(allow_negative_numbers = true)]
    Render(render_cmd::RenderArgs),
    /// Play the dance live in a window (needs a display; see `render` otherwise).
    #[command(allow_negative_numbers = true)]
    Play(play_cmd::PlayArgs),
    /// Benchmark: per-stage timings over thread counts, and speed against error over map
    /// resolutions.
    #[command(allow_negative_numbers = true)]
    Bench(bench_cmd::BenchArgs),
    /// Inspect the fibre scattering model: evaluate, tabulate, plot.
    Fiber(fiber_cmd::FiberArgs),
    /// The light map against the exact reference (ray shooting through explicit fibres) over
    /// map resolutions: the tables of ACCURACY.md.
    #[command(allow_negative_numbers = true)]
    Accuracy(accuracy_cmd::AccuracyArgs),
    /// Write one frame as a reference scene for a path tracer (hair.hair, scene.json) with
    /// wisp's own linear EXR of it (see tools/reference/).
    #[command(allow_negative_numbers = true)]
    Export(export_cmd::ExportArgs),
}

/// Fibre shader choice on the command line.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum ShadingArg {
    /// Dual scattering (Zinke 2008): Marschner BCSDF plus multiple scattering.
    Dual,
    /// Marschner BCSDF attenuated by the forward transmittance only.
    Single,
    /// Kajiya-Kay scaled by transmittance (Bertails 2005).
    KajiyaKay,
}

impl From<ShadingArg> for ShadingMode {
    fn from(s: ShadingArg) -> Self {
        match s {
            ShadingArg::Dual => ShadingMode::DualScattering,
            ShadingArg::Single => ShadingMode::SingleScattering,
            ShadingArg::KajiyaKay => ShadingMode::KajiyaKay,
        }
    }
}

/// What is rendered: hairstyle, motion, light, image and map settings.
#[derive(clap::Args, Debug, Clone)]
pub struct SceneArgs {
    /// Hairstyle: a JSON file, or the name of an embedded preset (`smooth`, `curly`).
    #[arg(long, default_value = "smooth")]
    pub hairstyle: String,
    /// Dance motion: a glTF 2.0 file (.glb or .gltf). Default: the embedded dance.
    #[arg(long)]
    pub animation: Option<PathBuf>,
    /// Animation clip name (default "Dance" if present, else the first clip).
    #[arg(long)]
    pub clip: Option<String>,
    /// Head joint: a node name or index (default: the joint whose name contains "head").
    #[arg(long)]
    pub head_joint: Option<String>,
    /// Playback speed of the motion (1 = real time).
    #[arg(long, default_value_t = 1.0, value_parser = parse_positive_f32)]
    pub speed: f32,
    /// Hold the head still in its rest pose (no motion).
    #[arg(long)]
    pub still: bool,
    /// Do not simulate: hair stays in its rest pose riding on the head.
    #[arg(long)]
    pub no_sim: bool,
    /// Direction the light travels, X,Y,Z (world, Y up; need not be normalised).
    #[arg(long, value_parser = parse_direction, allow_hyphen_values = true)]
    pub light_dir: Option<Vec3>,
    /// Image width in pixels.
    #[arg(long, default_value_t = 800, value_parser = clap::value_parser!(u32).range(16..=8192))]
    pub width: u32,
    /// Image height in pixels.
    #[arg(long, default_value_t = 800, value_parser = clap::value_parser!(u32).range(16..=8192))]
    pub height: u32,
    /// Map cells per axis (default: sized from the hairstyle's strand spacing).
    #[arg(long, value_parser = clap::value_parser!(u32).range(4..=1024))]
    pub map_res: Option<u32>,
    /// Fibre shader.
    #[arg(long, value_enum, default_value = "dual")]
    pub shading: ShadingArg,
    /// Turn off density-based self-collision.
    #[arg(long)]
    pub no_self_collision: bool,
    #[command(flatten)]
    pub view: view_args::ViewArgs,
}

impl SceneArgs {
    /// Loads the hairstyle and motion and builds the engine configuration.
    pub fn resolve(&self) -> Result<(Hairstyle, Motion, EngineConfig), AppError> {
        let style = match self.hairstyle.as_str() {
            "smooth" => Hairstyle::default_smooth(),
            "curly" => Hairstyle::default_curly(),
            path => Hairstyle::load(std::path::Path::new(path)).map_err(AppError::input)?,
        };
        let motion = if self.still {
            Motion::still(glam::Affine3A::IDENTITY)
        } else {
            let opts = MotionOptions {
                clip: self.clip.clone(),
                head_joint: self
                    .head_joint
                    .as_deref()
                    .map(|s| match s.parse::<usize>() {
                        Ok(i) => JointRef::Index(i),
                        Err(_) => JointRef::Name(s.to_string()),
                    }),
                speed: self.speed,
                ..MotionOptions::default()
            };
            match &self.animation {
                Some(path) => Motion::load(path, &opts).map_err(AppError::input)?,
                None => {
                    if self.clip.is_some() || self.head_joint.is_some() {
                        return Err(AppError::input(anyhow::anyhow!(
                            "--clip and --head-joint need --animation FILE (the embedded dance has one clip)"
                        )));
                    }
                    wisp::motion::dance::try_dance(&opts).map_err(AppError::other)?
                }
            }
        };
        let mut config = EngineConfig {
            width: self.width,
            height: self.height,
            map_res: self.map_res,
            ..Default::default()
        };
        if let Some(l) = self.light_dir {
            config.lighting.light_dir = l;
        }
        config.lighting.mode = self.shading.into();
        config.self_collision = !self.no_self_collision;
        config.simulate = !self.no_sim;
        self.view.apply(&mut config)?;
        Ok((style, motion, config))
    }
}

/// A finite number > 0.
pub fn parse_positive_f32(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        Ok(v) => Err(format!("must be a finite number > 0 (got {v})")),
        Err(_) => Err(format!("`{s}` is not a number")),
    }
}

/// A finite number.
pub fn parse_finite_f32(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(v) => Err(format!("must be finite (got {v})")),
        Err(_) => Err(format!("`{s}` is not a number")),
    }
}

/// `X,Y,Z`: three finite numbers, not all zero.
pub fn parse_direction(s: &str) -> Result<Vec3, String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(format!("expected three numbers X,Y,Z (got `{s}`)"));
    }
    let mut v = [0.0f32; 3];
    for (o, p) in v.iter_mut().zip(&parts) {
        *o = parse_finite_f32(p)?;
    }
    let v = Vec3::from(v);
    if v.length_squared() < 1e-12 {
        return Err("the direction must not be zero".into());
    }
    Ok(v.normalize())
}

/// An error with its exit code: 2 for bad input, 1 otherwise.
#[derive(Debug)]
pub struct AppError {
    pub code: u8,
    pub error: anyhow::Error,
}

impl AppError {
    pub fn input(error: impl Into<anyhow::Error>) -> Self {
        Self {
            code: 2,
            error: error.into(),
        }
    }
    pub fn other(error: impl Into<anyhow::Error>) -> Self {
        Self {
            code: 1,
            error: error.into(),
        }
    }
}

/// Parses the command line and runs it; errors go to stderr with their exit code.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    if let Some(n) = cli.threads
        && let Err(e) = rayon::ThreadPoolBuilder::new()
            .num_threads(n as usize)
            .build_global()
    {
        eprintln!("wisp: error: cannot start {n} threads: {e}");
        return ExitCode::from(1);
    }
    let result = match cli.command {
        Command::Render(args) => render_cmd::run(args),
        Command::Play(args) => play_cmd::run(args),
        Command::Bench(args) => bench_cmd::run(args),
        Command::Fiber(args) => fiber_cmd::run(args),
        Command::Accuracy(args) => accuracy_cmd::run(args),
        Command::Export(args) => export_cmd::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("wisp: error: {:#}", e.error);
            ExitCode::from(e.code)
        }
    }
}
