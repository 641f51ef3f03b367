//! Command-line edge: argument parsing, degrees and file formats live here, nowhere deeper.
//!
//! Exit codes: 0 success, 2 bad input (flags, files, output paths, or a run over its memory or
//! work budget), 1 any other failure, 141 when standard output was closed early (`wisp … |
//! head`: the reader had what it wanted; wisp stops quietly, as a program killed by SIGPIPE).

/// `print!` / `println!` for the commands (they shadow the standard macros in this module and
/// the ones declared below it): the standard ones panic when standard output is a pipe its
/// reader has closed; these stop the process quietly with exit code 141 instead.
macro_rules! print {
    ($($arg:tt)*) => {
        $crate::cli::write_stdout(format_args!($($arg)*))
    };
}
macro_rules! println {
    () => {
        print!("\n")
    };
    ($($arg:tt)*) => {
        $crate::cli::write_stdout(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// Writes to standard output; a closed pipe ends the process with code 141, any other write
/// error with code 1 and a message.
pub fn write_stdout(args: std::fmt::Arguments) {
    use std::io::Write;
    if let Err(e) = std::io::stdout().lock().write_fmt(args) {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(141);
        }
        eprintln!("wisp: error: cannot write to standard output: {e}");
        std::process::exit(1);
    }
}

pub mod accuracy_cmd;
pub mod bench_cmd;
pub mod cache_cmd;
pub mod export_cmd;
pub mod fiber_cmd;
pub mod light_path_args;
pub mod play_cmd;
pub mod render_cmd;
pub mod shard;
pub mod view_args;

mod parse;
pub use parse::*;

use clap::{Parser, Subcommand, ValueEnum};
use glam::Vec3;
use std::path::PathBuf;
use std::process::ExitCode;
use wisp::budget::{Budget, RunPlan};
use wisp::engine::{Engine, EngineConfig};
use wisp::fiber::ShadingMode;
use wisp::hairstyle::{Hairstyle, HairstyleError};
use wisp::motion::{Fit, JointRef, Motion, MotionError, MotionOptions};
use wisp::scene::file::LightJson;
use wisp::scene::{Scene, SceneFile};

/// Most worker threads per core. More only slows wisp down, and faster than linearly: on 2
/// cores, 2 frames at 160×120 took 0.25 s with 2 threads, 1.0 s with 256, 4.8 s with 512 and
/// 36 s with 1,000.
pub const THREADS_PER_CORE: usize = 4;

/// The most worker threads accepted on this machine.
pub fn max_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get()) * THREADS_PER_CORE
}

/// Embedded hairstyle presets, by `--hairstyle` name.
pub const PRESETS: [&str; 3] = ["smooth", "curly", "dense"];

#[derive(Parser, Debug)]
#[command(
    name = "wisp",
    version,
    about = "Animate and render human hair on the CPU"
)]
pub struct Cli {
    /// Worker threads for the parallel stages (default: all cores; at most 4 per core, more
    /// are reduced to that with a warning). Output does not depend on it.
    #[arg(long, global = true, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub threads: Option<u32>,
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render the dance (default: the embedded dance and the `smooth` hairstyle) to image
    /// frames: 8-bit PNG, 16-bit RGBA PNG or linear RGBA OpenEXR.
    #[command(allow_negative_numbers = true)]
    Render(render_cmd::RenderArgs),
    /// Simulate the hair once and write every frame's guide state to a cache file, for
    /// `render --cache` (any light, camera, shader or size; frame ranges; shards).
    #[command(allow_negative_numbers = true)]
    Simulate(cache_cmd::SimulateArgs),
    /// Play the dance live in a window (needs a display; see `render` otherwise).
    #[command(allow_negative_numbers = true)]
    Play(play_cmd::PlayArgs),
    /// Benchmark: per-stage timings over thread counts, and speed against error over map
    /// resolutions.
    #[command(allow_negative_numbers = true)]
    Bench(bench_cmd::BenchArgs),
    /// Inspect the fibre scattering model: evaluate, tabulate, plot.
    #[command(allow_negative_numbers = true)]
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
    /// Dual scattering (Zinke 2008): the fibre's BCSDF plus multiple scattering.
    Dual,
    /// Single scattering with hard shadows: the BCSDF times the light that reaches the point
    /// through no fibre.
    Single,
    /// Kajiya-Kay scaled by transmittance (Bertails 2005).
    KajiyaKay,
    /// The shadows alone: grey = the irradiance reaching the hair through no fibre (no fibre
    /// model, no ambient on the hair).
    Visibility,
    /// Single scattering plus multiply scattered light from paths traced through the hair
    /// volume (seconds per frame; `--volume-cell-mm`, `--volume-paths`).
    Volume,
}

impl From<ShadingArg> for ShadingMode {
    fn from(s: ShadingArg) -> Self {
        match s {
            ShadingArg::Dual => ShadingMode::DualScattering,
            ShadingArg::Single => ShadingMode::SingleScattering,
            ShadingArg::KajiyaKay => ShadingMode::KajiyaKay,
            ShadingArg::Visibility => ShadingMode::Visibility,
            ShadingArg::Volume => ShadingMode::Volume,
        }
    }
}

/// What is rendered: hairstyle, motion, light, image and map settings.
#[derive(clap::Args, Debug, Clone)]
pub struct SceneArgs {
    /// Hairstyle: a JSON file, or the name of an embedded preset (`smooth`, `curly`, `dense`); or a
    /// captured groom: one or more TressFX `.tfx` / cyHair `.hair` files forming one groom
    /// (comma-separated or the flag repeated), optionally with one preset or JSON file whose
    /// head, fibre and dynamics it takes (default `smooth`).
    #[arg(long, default_value = "smooth", value_delimiter = ',')]
    pub hairstyle: Vec<String>,
    /// Wisps of an imported groom (default: one per 25 strands, at most 400).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub groom_wisps: Option<u32>,
    /// Turn of an imported groom about the vertical axis, degrees (default: 0 or 180, whichever
    /// puts most of the hair behind the head).
    #[arg(long, value_parser = parse_finite_f32, allow_hyphen_values = true)]
    pub groom_turn_deg: Option<f32>,
    /// Dance motion: a glTF 2.0 file (.glb or .gltf). Default: the embedded dance.
    #[arg(long)]
    pub animation: Option<PathBuf>,
    /// Animation clip name (default "Dance" if present, else the first clip).
    #[arg(long)]
    pub clip: Option<String>,
    /// Head joint: a node name or index (default: the joint whose name contains "head").
    #[arg(long)]
    pub head_joint: Option<String>,
    /// Head fit: model head size over the hairstyle's 0.09 m head, > 0 (default: from the head
    /// mesh's box, else the skeleton). Needs --head-offset.
    #[arg(long, value_parser = parse_positive_f32, requires = "head_offset")]
    pub head_scale: Option<f32>,
    /// Head fit: the hairstyle head's centre X,Y,Z in the head joint's frame, model metres
    /// (rest-pose world axes). Needs --head-scale.
    #[arg(long, value_parser = parse_point, allow_hyphen_values = true, requires = "head_scale")]
    pub head_offset: Option<Vec3>,
    /// Playback speed of the motion (1 = real time), in (0, 1000].
    #[arg(long, default_value_t = 1.0, value_parser = parse_speed, allow_hyphen_values = true)]
    pub speed: f32,
    /// Hold the head still in its rest pose (no motion).
    #[arg(long)]
    pub still: bool,
    /// Do not simulate: hair stays in its rest pose riding on the head.
    #[arg(long)]
    pub no_sim: bool,
    /// Scene file (JSON: camera, lights, ambient, background, exposure, image size; see
    /// README "Scene files"). The scene flags below override its fields.
    #[arg(long, value_name = "FILE.json")]
    pub scene: Option<PathBuf>,
    /// Direction the first light travels, X,Y,Z (world, Y up; need not be normalised; scene
    /// `lights[0].direction`, a directional light).
    #[arg(long, value_parser = parse_direction, allow_hyphen_values = true)]
    pub light_dir: Option<Vec3>,
    /// Image width in pixels, 16..=8192 (default 800; scene `image.width`).
    #[arg(long, value_parser = clap::value_parser!(u32).range(16..=8192))]
    pub width: Option<u32>,
    /// Image height in pixels, 16..=8192 (default 800; scene `image.height`).
    #[arg(long, value_parser = clap::value_parser!(u32).range(16..=8192))]
    pub height: Option<u32>,
    /// Map cells per axis (default: sized from the hairstyle's strand spacing).
    #[arg(long, value_parser = clap::value_parser!(u32).range(4..=1024))]
    pub map_res: Option<u32>,
    /// Contact shadows for one-fibre-per-strand hair: the fibres within this many millimetres
    /// in front of each vertex (toward the light) are taken exactly, the map gives the rest
    /// (120 is what ACCURACY.md recommends; 0 or absent: off, except `wisp accuracy`, which
    /// uses 120 unless given 0). Bundles of fibres never use them.
    #[arg(long, value_name = "MM", value_parser = parse_contact_mm, allow_hyphen_values = true)]
    pub contact_mm: Option<f32>,
    /// Cut each segment of the render strands into this many straight pieces (1..=16): the
    /// same drawn hair, its light read this many times per segment (the raster interpolates
    /// light between points), at about as many times the map, contact and shading cost.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=16))]
    pub segment_pieces: Option<u32>,
    /// Fibre shader.
    #[arg(long, value_enum, default_value = "dual")]
    pub shading: ShadingArg,
    #[command(flatten)]
    pub volume: light_path_args::LightPathArgs,
    /// Turn off density-based self-collision.
    #[arg(long)]
    pub no_self_collision: bool,
    #[command(flatten)]
    pub view: view_args::ViewArgs,
    /// Memory budget in GB (10⁹ bytes): a run whose estimated memory is larger is refused
    /// before it allocates anything large (see README, "Limits").
    #[arg(long, default_value_t = 4.0, value_parser = parse_budget, allow_hyphen_values = true)]
    pub max_memory_gb: f64,
    /// Work budget in CPU-minutes: a run whose set-up (settle, warm-up and first frame) is
    /// estimated to take longer is refused (20 CPU-minutes: 10 minutes on 2 cores).
    #[arg(long, default_value_t = 20.0, value_parser = parse_budget, allow_hyphen_values = true)]
    pub max_work_cpu_min: f64,
}

impl SceneArgs {
    /// Loads the hairstyle (and an imported groom's hair) and motion and builds the engine
    /// configuration.
    pub fn resolve(&self) -> Result<(Hairstyle, ImportedHair, Motion, EngineConfig), AppError> {
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
                fit: self
                    .head_scale
                    .zip(self.head_offset)
                    .map(|(scale, offset_m)| Fit { scale, offset_m }),
                ..MotionOptions::default()
            };
            match &self.animation {
                Some(path) => Motion::load(path, &opts).map_err(|e| self.motion_error(e))?,
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
        let (style, hair) = self.load_hair(&motion)?;
        let (file, scene) = self.scene_file()?;
        let head = Vec3::from(motion.sample(0.0).head.translation);
        let reach = style.max_length_m() + style.head.radii_m.iter().copied().fold(0.0, f32::max);
        wisp::scene::file::check_point_lights_outside(&scene.lights, head, reach)
            .map_err(|(field, rule)| AppError::input(anyhow::anyhow!("{file}: {field}: {rule}")))?;
        let mut config = {
            let mut config = EngineConfig::default();
            config.hair_map.map_res = self.map_res;
            config
        }
        .with_scene(&scene);
        config.shading.mode = self.shading.into();
        if let Some(mm) = self.contact_mm {
            config.hair_map.contact = wisp::engine::ContactShadowing::from_mm(mm);
        }
        if let Some(n) = self.segment_pieces {
            config.interpolation.segment_pieces = n;
        }
        self.volume.apply(&mut config);
        config.simulation.self_collision = !self.no_self_collision;
        config.simulation.simulate = !self.no_sim;
        self.view.apply(&mut config);
        self.check_roots_on_head(&style, &hair, &motion)?;
        Ok((style, hair, motion, config))
    }

    /// The effective scene: the scene file (or the default scene) with the scene flags
    /// written over it (`--print-scene` prints it). Errors name the file, the field and the rule.
    pub fn effective_scene(&self) -> Result<(String, SceneFile), AppError> {
        let (name, mut file) = match &self.scene {
            Some(path) => {
                let name = path.display().to_string();
                let (file, _) = SceneFile::load(path).map_err(AppError::input)?;
                (name, file)
            }
            None => ("scene flags".to_string(), SceneFile::default()),
        };
        if let Some(w) = self.width {
            file.image.width = w;
        }
        if let Some(h) = self.height {
            file.image.height = h;
        }
        if let Some(l) = self.light_dir {
            match file.lights.first_mut() {
                Some(LightJson::Directional { direction, .. }) => *direction = l.to_array(),
                _ => {
                    return Err(AppError::input(anyhow::anyhow!(
                        "--light-dir sets the first light's direction, and the first light of {name} is not a directional light"
                    )));
                }
            }
        }
        self.view.apply_to_scene(&mut file)?;
        Ok((name, file))
    }

    /// [`Self::effective_scene`], validated.
    fn scene_file(&self) -> Result<(String, Scene), AppError> {
        let (name, file) = self.effective_scene()?;
        let scene = file.validate(&name).map_err(AppError::input)?;
        Ok((name, scene))
    }

    /// The hairstyle, and the hair of an imported groom when `--hairstyle` names strand files
    /// (the import's figures go to stderr).
    /// An imported groom is placed on the hairstyle's own head ellipsoid, not on one fitted to a
    /// character's head mesh: a mesh's bounding box is a poor scalp for a human groom (the
    /// TressFX ponytail on RobotExpressive's boxy head: 19% of roots over 30 mm off). The roots
    /// are then checked on the drawn head mesh (`check_roots_on_head`).
    fn load_hair(&self, _motion: &Motion) -> Result<(Hairstyle, ImportedHair), AppError> {
        let (files, styles): (Vec<&String>, Vec<&String>) = self
            .hairstyle
            .iter()
            .partition(|a| wisp::input::strand_file::is_strand_file_name(a));
        if styles.len() > 1 || (styles.is_empty() && files.is_empty()) {
            return Err(AppError::input(anyhow::anyhow!(
                "--hairstyle {}: give one preset or JSON hairstyle, plus any number of .tfx/.hair strand files",
                self.hairstyle.join(",")
            )));
        }
        let source = styles.first().map_or("smooth", |s| s.as_str());
        let base = load_hairstyle(source)?;
        if files.is_empty() {
            warn_advisories(source, &base);
            return Ok((base, None));
        }
        let opts = wisp::groom::GroomOptions {
            wisps: self.groom_wisps.map(|w| w as usize),
            yaw_rad: self.groom_turn_deg.map(f32::to_radians),
        };
        let paths: Vec<&std::path::Path> = files
            .iter()
            .map(|f| std::path::Path::new(f.as_str()))
            .collect();
        let started = std::time::Instant::now();
        let groom = wisp::groom::load_groom(&paths, &base, &opts).map_err(AppError::input)?;
        let r = &groom.report;
        let p = r.placement.unwrap_or(wisp::groom::Placement {
            scale: 1.0,
            yaw_rad: 0.0,
            offset_m: Vec3::ZERO,
        });
        eprintln!(
            "wisp: groom {}: {} strands ({} dropped: zero length) in {} wisps, imported in {:.2} s; \
             placed on the head at scale {:.5}, turn {:.0}°, roots {:.1} mm from the scalp (mean, max {:.1}); \
             rest pose vs file: mean {:.3} mm, max {:.3} mm",
            printable(&groom.style.name),
            r.strands_read - r.strands_dropped,
            r.strands_dropped,
            r.wisps,
            started.elapsed().as_secs_f64(),
            p.scale,
            p.yaw_rad.to_degrees(),
            r.root_distance_mean_m * 1e3,
            r.root_distance_max_m * 1e3,
            r.rest_distance_mean_m * 1e3,
            r.rest_distance_max_m * 1e3,
        );
        // What the groom keeps of the hairstyle (not its curls: an imported groom has its own
        // shape) is checked as it will be drawn.
        warn_advisories(source, &groom.style);
        Ok((groom.style, Some((groom.guides, groom.layout))))
    }

    /// Refuses (exit code 2) a groom whose roots do not lie on the character's head mesh
    /// (`wisp::motion::scalp`), naming the fit and the flags that change it.
    fn check_roots_on_head(
        &self,
        style: &Hairstyle,
        hair: &ImportedHair,
        motion: &Motion,
    ) -> Result<(), AppError> {
        let roots = match hair {
            Some((guides, _)) => wisp::engine::roots_of_guides_on_head(guides, style, motion),
            None => wisp::engine::roots_on_head(style, motion),
        };
        let Some(r) = roots else {
            return Ok(());
        };
        if r.on_head() {
            return Ok(());
        }
        let fit = motion.fit();
        let animation = self
            .animation
            .as_ref()
            .map_or("the embedded dance".to_string(), |p| {
                p.display().to_string()
            });
        Err(AppError::input(anyhow::anyhow!(
            "{}: the hairstyle's roots do not lie on the head mesh of {}: the median root is \
             {:.3} m from it, the farthest {:.3} m ({} of {} roots within the tolerance of \
             {:.3} m); the head was fitted by {:?} (scale {}, offset \
             {},{},{} m); give the fit with --head-scale S --head-offset X,Y,Z",
            printable(&self.hairstyle.join(",")),
            animation,
            r.median_m,
            r.worst_m,
            r.near,
            r.roots,
            r.tolerance_m,
            motion.fit_method(),
            fit.scale,
            fit.offset_m.x,
            fit.offset_m.y,
            fit.offset_m.z,
        )))
    }

    /// A motion error, with the flag that fixes it when there is one.
    fn motion_error(&self, e: MotionError) -> AppError {
        let hint = match &e {
            MotionError::UnknownJoint { role, .. } if role == "head joint" => {
                if self.head_joint.is_none() {
                    "; choose the head with --head-joint NAME|INDEX"
                } else {
                    "; give one of these to --head-joint"
                }
            }
            MotionError::UnknownClip { .. } => "; give one of these to --clip",
            _ => "",
        };
        AppError::input(anyhow::anyhow!("{e}{hint}"))
    }

    /// The budget the flags set.
    pub fn budget(&self) -> Budget {
        Budget {
            memory_bytes: (self.max_memory_gb * 1e9) as u64,
            work_cpu_s: self.max_work_cpu_min * 60.0,
        }
    }

    /// Refuses a run over the budget (exit code 2), before the engine allocates. An automatic
    /// map resolution is lowered first, with a warning, when that brings the run within the
    /// memory budget.
    pub fn check_budget(
        &self,
        style: &Hairstyle,
        motion: &Motion,
        config: &mut EngineConfig,
        plan: &RunPlan,
    ) -> Result<(), AppError> {
        if let Some((auto, n)) =
            wisp::engine::fit_map_resolution(style, motion, config, plan, &self.budget())
        {
            eprintln!(
                "wisp: warning: the automatic map resolution {auto} (cells of 1.5 strand spacings at the scalp) could need more memory than --max-memory-gb {}; using {n}",
                self.max_memory_gb
            );
            config.hair_map.map_res = Some(n);
        }
        wisp::engine::estimate(style, motion, config, plan)
            .check(&self.budget())
            .map_err(|e| {
                let flag = match e {
                    wisp::budget::BudgetError::Memory { .. } => "--max-memory-gb",
                    wisp::budget::BudgetError::Work { .. } => "--max-work-cpu-min",
                };
                AppError::input(anyhow::anyhow!(
                    "{e}. Lower it, or raise the budget with {flag}"
                ))
            })
    }
}

/// Hair built elsewhere than from a hairstyle's parameters: an imported groom's guides and
/// layout (`None`: generate from the hairstyle).
pub type ImportedHair = Option<(wisp::hairstyle::GuideSet, wisp::hairstyle::StrandLayout)>;

/// The engine for a resolved scene: generated hair, or the imported groom's.
pub fn engine(
    style: Hairstyle,
    hair: ImportedHair,
    motion: Motion,
    config: EngineConfig,
) -> Engine {
    match hair {
        Some((guides, layout)) => Engine::with_hair(style, guides, layout, motion, config),
        None => Engine::new(style, motion, config),
    }
}

/// A preset by name, else a hairstyle file; a missing file that is no preset says which
/// presets exist.
pub fn load_hairstyle(arg: &str) -> Result<Hairstyle, AppError> {
    match arg {
        "smooth" => return Ok(Hairstyle::default_smooth()),
        "curly" => return Ok(Hairstyle::default_curly()),
        "dense" => return Ok(Hairstyle::dense()),
        _ => {}
    }
    let path = std::path::Path::new(arg);
    Hairstyle::load(path).map_err(|e| match e {
        HairstyleError::Io { .. } if !path.exists() => AppError::input(anyhow::anyhow!(
            "--hairstyle {arg}: not a preset ({}) and no such file",
            PRESETS.join(", ")
        )),
        e => AppError::input(e),
    })
}

/// Prints the hairstyle's advisories (`Hairstyle::advisories`: what it may ask for but is
/// measured to render wrongly) as warnings naming `source`, the file it came from.
fn warn_advisories(source: &str, style: &Hairstyle) {
    for a in style.advisories() {
        eprintln!(
            "wisp: warning: {source}: field `{}`: {}",
            a.field, a.message
        );
    }
}

/// Checks, before any work, that `path` can be an output file: not a directory, in a folder
/// that exists. `flag` names the option in the message.
pub fn check_output_file(flag: &str, path: &std::path::Path) -> Result<(), AppError> {
    let shown = path.display();
    if path.is_dir() {
        return Err(AppError::input(anyhow::anyhow!(
            "{flag} {shown}: is a directory, not a file name"
        )));
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => std::path::Path::new("."),
    };
    if !parent.is_dir() {
        return Err(AppError::input(anyhow::anyhow!(
            "{flag} {shown}: the folder {} does not exist",
            parent.display()
        )));
    }
    Ok(())
}

/// A name from an input file (hairstyle, clip, joint) safe to print on a terminal: control
/// characters (an escape sequence could clear the screen) become `?`.
pub fn printable(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect()
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
    if let Some(asked) = cli.threads {
        let n = (asked as usize).min(max_threads());
        if n < asked as usize {
            eprintln!(
                "wisp: warning: --threads {asked} is more than {THREADS_PER_CORE} per core ({} cores here), which only slows wisp down; using {n}",
                max_threads() / THREADS_PER_CORE
            );
        }
        if let Err(e) = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
        {
            eprintln!("wisp: error: cannot start {n} threads: {e}");
            return ExitCode::from(1);
        }
    }
    let result = match cli.command {
        Command::Render(args) if args.cache.is_some() => cache_cmd::render_from_cache(args),
        Command::Render(args) => render_cmd::run(args),
        Command::Simulate(args) => cache_cmd::simulate(args),
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

#[cfg(test)]
mod tests;
