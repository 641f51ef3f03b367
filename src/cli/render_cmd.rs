//! `wisp render`: the dance (or a still pose) rendered frame by frame to PNG files.
//!
//! Frames are rendered on the calling thread (each stage parallel inside) and handed through a
//! bounded crossbeam channel to a writer thread that encodes and writes them (temporary name,
//! then rename: an interrupted export leaves complete frames only). Pixel buffers travel back
//! on a second channel, so the export allocates nothing per frame once running.
//!
//! Before anything large is allocated, the run is checked against the memory and work budget
//! (`wisp::budget`), and the output directory is prepared: it must be a writable directory,
//! and what an earlier export left there (temporary files of a killed run, frames beyond this
//! run's count) is removed, so the folder holds exactly this run's frames.

use super::{AppError, SceneArgs};
use anyhow::Context;
use std::path::{Path, PathBuf};
use wisp::budget::RunPlan;
use wisp::frame::{Engine, StageTimings};
use wisp::output::write_png_rgb8;

pub use super::shard::MAX_FRAMES;

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
    #[arg(long, default_value = "frames")]
    pub out: PathBuf,
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
    /// Print only errors.
    #[arg(long)]
    pub quiet: bool,
    /// Write the effective scene (scene file and scene flags merged) as JSON to stdout and
    /// exit: a scene file to start from (`--scene` reads it back to the same frames).
    #[arg(long)]
    pub print_scene: bool,
}

/// A rendered frame on its way to the writer thread.
struct Job {
    index: u32,
    width: u32,
    height: u32,
    rgb: Vec<u8>,
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
    prepare_output_dir(&args.out, &Tidy::whole_run(frames), args.quiet)?;
    let name = style.name.clone();
    let started = std::time::Instant::now();
    let mut engine = super::engine(style, hair, motion, config);
    engine.run_up_to(start_s);
    let setup_s = started.elapsed().as_secs_f64();
    if !args.quiet {
        let g = engine.map_geometry();
        eprintln!(
            "wisp: {} ({} wisps, {} strands, {} segments), clip \"{}\" {:.2} s, map {}^3 cells of {:.1} mm, {}x{} px, set-up {:.2} s",
            super::printable(&name),
            engine.layout.wisp_guides.len(),
            engine.layout.count(),
            engine.layout.segments(),
            super::printable(engine.motion.clip_name()),
            engine.motion.duration_s(),
            g.n,
            g.ds_m * 1e3,
            engine.config.width,
            engine.config.height,
            setup_s
        );
    }
    let fps = args.fps as f64;
    export_frames(
        &mut engine,
        0..frames,
        &args.out,
        args.quiet,
        started,
        |engine, i| {
            let t = start_s + i as f64 / fps;
            engine.advance(t);
            Ok(t)
        },
    )
}

/// Renders frames `indices` and writes them to `out` as `frame_NNNNN.png` (numbered by
/// index) through a writer thread. `hair_at(engine, i)` puts the hair of frame `i` in place
/// (simulated, or read from a cache) and returns its time; the engine renders it.
pub fn export_frames(
    engine: &mut Engine,
    indices: std::ops::Range<u32>,
    out: &Path,
    quiet: bool,
    started: std::time::Instant,
    mut hair_at: impl FnMut(&mut Engine, u32) -> Result<f64, AppError>,
) -> Result<(), AppError> {
    let (to_writer, jobs) = crossbeam_channel::bounded::<Job>(2);
    let (to_renderer, spare) = crossbeam_channel::bounded::<Vec<u8>>(3);
    for _ in 0..3 {
        let _ = to_renderer.send(Vec::new());
    }
    let out_dir = out.to_path_buf();
    let writer = std::thread::spawn(move || -> Result<(), wisp::output::OutputError> {
        for job in jobs {
            let path = frame_path(&out_dir, job.index);
            write_png_rgb8(&path, job.width, job.height, &job.rgb)?;
            let _ = to_renderer.send(job.rgb);
        }
        Ok(())
    });
    let mut total = StageTimings::default();
    let (width, height) = (engine.config.width, engine.config.height);
    let frames = indices.len() as u32;
    let mut failed = None;
    let mut hair_error = None;
    for (n, i) in indices.clone().enumerate() {
        let t = match hair_at(engine, i) {
            Ok(t) => t,
            Err(e) => {
                hair_error = Some(e);
                break;
            }
        };
        engine.render();
        if n == 0 {
            warn_about_first_frame(engine);
        }
        let mut rgb = spare.recv().unwrap_or_default();
        engine.framebuffer().to_srgb8_into(&mut rgb);
        total.add(&engine.timings);
        if to_writer
            .send(Job {
                index: i,
                rgb,
                width,
                height,
            })
            .is_err()
        {
            failed = Some(i);
            break;
        }
        if !quiet && (n + 1) % 30 == 0 {
            eprintln!("wisp: frame {}/{} (t = {:.2} s)", n + 1, frames, t);
        }
    }
    drop(to_writer);
    let written = writer
        .join()
        .map_err(|_| AppError::other(anyhow::anyhow!("the PNG writer thread panicked")))?;
    written.map_err(AppError::other)?;
    if let Some(e) = hair_error {
        return Err(e);
    }
    if let Some(i) = failed {
        return Err(AppError::other(anyhow::anyhow!(
            "frame {i}: the PNG writer stopped"
        )));
    }
    if !quiet {
        print_timings(&total, frames, started.elapsed().as_secs_f64());
        let shown = out.display();
        if indices.start == 0 {
            eprintln!("wisp: wrote {frames} frames to {shown}");
        } else {
            eprintln!(
                "wisp: wrote {frames} frames ({} to {}) to {shown}",
                indices.start,
                indices.end - 1
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
    let background = engine.config.background;
    if fb.color.iter().all(|c| *c == background) {
        eprintln!(
            "wisp: warning: the first frame shows only the background: the head and the hair are out of view"
        );
    }
}

/// What an export may remove from its output directory before it starts.
#[derive(Clone, Debug, PartialEq)]
pub struct Tidy {
    /// The frames this run writes: their temporary files (of an interrupted run) are removed,
    /// and a non-file in the way of one is an error.
    pub own: std::ops::Range<u32>,
    /// Temporary files of any frame are removed (false when other processes may be writing
    /// frames into the same directory: shards).
    pub all_temporaries: bool,
    /// Frames numbered this or more are removed (no run of this sequence writes them).
    pub stale_from: Option<u32>,
}

impl Tidy {
    /// A run that writes frames 0 to `frames − 1` alone: the folder ends up holding exactly
    /// its frames.
    pub fn whole_run(frames: u32) -> Self {
        Self {
            own: 0..frames,
            all_temporaries: true,
            stale_from: Some(frames),
        }
    }
}

/// Makes `dir` ready for a run's frames: creates it, checks that files can be written there,
/// and removes what an earlier export left, as `tidy` allows: `frame_NNNNN.png.tmp` files of
/// an interrupted run and `frame_NNNNN.png` files beyond the sequence (which this run would not
/// overwrite). Only files named exactly like wisp's frames are touched, and a file another
/// process removed first is not an error (shards tidy the same folder at once).
pub fn prepare_output_dir(dir: &Path, tidy: &Tidy, quiet: bool) -> Result<(), AppError> {
    let shown = dir.display();
    if dir.exists() && !dir.is_dir() {
        return Err(AppError::input(anyhow::anyhow!(
            "--out {shown}: exists and is not a directory"
        )));
    }
    std::fs::create_dir_all(dir)
        .with_context(|| format!("--out {shown}: cannot create the output directory"))
        .map_err(AppError::input)?;
    let probe = dir.join(format!(
        ".wisp-write-test-{}-{}",
        std::process::id(),
        tidy.own.start
    ));
    std::fs::write(&probe, b"")
        .with_context(|| format!("--out {shown}: cannot write files into the directory"))
        .map_err(AppError::input)?;
    let _ = std::fs::remove_file(&probe);
    let entries = std::fs::read_dir(dir)
        .with_context(|| format!("--out {shown}: cannot list the directory"))
        .map_err(AppError::input)?;
    let (mut temporaries, mut stale) = (0usize, 0usize);
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        let Some((index, temporary)) = frame_index(name) else {
            continue;
        };
        let is_file = entry.file_type().is_ok_and(|t| t.is_file());
        let own = tidy.own.contains(&index);
        if !temporary && own {
            if !is_file && !entry.path().is_file() {
                return Err(AppError::input(anyhow::anyhow!(
                    "--out {shown}: {name} is in the way (not a file, so this run cannot replace it)"
                )));
            }
            continue;
        }
        let remove = if temporary {
            own || tidy.all_temporaries
        } else {
            tidy.stale_from.is_some_and(|from| index >= from)
        };
        if !is_file || !remove {
            continue;
        }
        match std::fs::remove_file(entry.path()) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => continue,
            Err(e) => {
                return Err(AppError::input(anyhow::anyhow!(
                    "{}: cannot remove it: {e}",
                    entry.path().display()
                )));
            }
        }
        if temporary {
            temporaries += 1;
        } else {
            stale += 1;
        }
    }
    if !quiet && temporaries + stale > 0 {
        let beyond = tidy
            .stale_from
            .map_or(String::new(), |f| format!(" numbered {f} or more"));
        eprintln!(
            "wisp: removed from {shown} what an earlier export left: {stale} frames{beyond}, {temporaries} temporary files"
        );
    }
    Ok(())
}

/// `frame_00012.png` -> (12, false); `frame_00012.png.tmp` -> (12, true); anything else -> None.
fn frame_index(name: &str) -> Option<(u32, bool)> {
    let rest = name.strip_prefix("frame_")?;
    let (digits, temporary) = match rest.strip_suffix(".png.tmp") {
        Some(d) => (d, true),
        None => (rest.strip_suffix(".png")?, false),
    };
    if digits.len() < 5 || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok().map(|i| (i, temporary))
}

/// `DIR/frame_00012.png`.
pub fn frame_path(dir: &Path, index: u32) -> PathBuf {
    dir.join(format!("frame_{index:05}.png"))
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
mod tests {
    use super::*;

    #[test]
    fn frame_names_are_recognised_exactly() {
        assert_eq!(frame_index("frame_00012.png"), Some((12, false)));
        assert_eq!(frame_index("frame_00012.png.tmp"), Some((12, true)));
        assert_eq!(frame_index("frame_123456.png"), Some((123_456, false)));
        assert_eq!(frame_index("frame_0012.png"), None);
        assert_eq!(frame_index("frame_00012.PNG"), None);
        assert_eq!(frame_index("my_frame_00012.png"), None);
        assert_eq!(frame_index("frame_000a2.png"), None);
    }

    #[test]
    fn start_wraps_into_one_loop() {
        assert_eq!(wrapped_start_s(4.0, 8.0, 1.0), (4.0, false));
        assert_eq!(wrapped_start_s(1e12, 8.0, 1.0), (0.0, true));
        assert_eq!(wrapped_start_s(-1.0, 8.0, 1.0), (7.0, true));
        // At speed 2 one loop of an 8 s clip lasts 4 s.
        assert_eq!(wrapped_start_s(5.0, 8.0, 2.0), (1.0, true));
        // A still motion has no loop: it starts at 0.
        assert_eq!(wrapped_start_s(3.0, 0.0, 1.0), (0.0, true));
        let (t, _) = wrapped_start_s(-1e-300, 8.0, 1.0);
        assert!((0.0..8.0).contains(&t));
    }
}
