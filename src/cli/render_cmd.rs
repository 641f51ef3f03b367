//! `wisp render`: the dance (or a still pose) rendered frame by frame to PNG files.
//!
//! Frames are rendered on the calling thread (each stage parallel inside) and handed through a
//! bounded crossbeam channel to a writer thread that encodes and writes them (temporary name,
//! then rename: an interrupted export leaves complete frames only). Pixel buffers travel back
//! on a second channel, so the export allocates nothing per frame once running.

use super::{AppError, SceneArgs};
use anyhow::Context;
use std::path::{Path, PathBuf};
use wisp::frame::{Engine, StageTimings};
use wisp::output::write_png_rgb8;

#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Number of frames to render (default: one loop of the clip at --fps; 1 with --still).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub frames: Option<u32>,
    /// Output frame rate in frames per second (the simulation step is independent of it).
    #[arg(long, default_value_t = 30.0, value_parser = super::parse_positive_f32)]
    pub fps: f32,
    /// Time of the first frame in seconds of the motion.
    #[arg(long, default_value_t = 0.0, value_parser = super::parse_finite_f32)]
    pub start_s: f32,
    /// Output directory (created if missing); frames are frame_00000.png, frame_00001.png, ...
    #[arg(long, default_value = "frames")]
    pub out: PathBuf,
    /// Print only errors.
    #[arg(long)]
    pub quiet: bool,
}

/// A rendered frame on its way to the writer thread.
struct Job {
    index: u32,
    width: u32,
    height: u32,
    rgb: Vec<u8>,
}

pub fn run(args: RenderArgs) -> Result<(), AppError> {
    let (style, motion, config) = args.scene.resolve()?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("{}: cannot create the output directory", args.out.display()))
        .map_err(AppError::input)?;
    let name = style.name.clone();
    let started = std::time::Instant::now();
    let still = args.scene.still;
    let mut engine = Engine::new(style, motion, config);
    let frames = args.frames.unwrap_or_else(|| {
        if still {
            1
        } else {
            ((engine.motion.duration_s() * args.fps).round() as u32).clamp(1, 100_000)
        }
    });
    engine.run_up_to(args.start_s as f64);
    let setup_s = started.elapsed().as_secs_f64();
    if !args.quiet {
        let g = engine.map_geometry();
        eprintln!(
            "wisp: {} ({} wisps, {} strands, {} segments), clip \"{}\" {:.2} s, map {}^3 cells of {:.1} mm, {}x{} px, set-up {:.2} s",
            name,
            engine.layout.wisp_guides.len(),
            engine.layout.count(),
            engine.layout.segments(),
            engine.motion.clip_name(),
            engine.motion.duration_s(),
            g.n,
            g.ds_m * 1e3,
            engine.config.width,
            engine.config.height,
            setup_s
        );
    }
    let (to_writer, jobs) = crossbeam_channel::bounded::<Job>(2);
    let (to_renderer, spare) = crossbeam_channel::bounded::<Vec<u8>>(3);
    for _ in 0..3 {
        let _ = to_renderer.send(Vec::new());
    }
    let out_dir = args.out.clone();
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
    let mut failed = None;
    for i in 0..frames {
        let t = args.start_s as f64 + i as f64 / args.fps as f64;
        let fb = engine.frame(t);
        let mut rgb = spare.recv().unwrap_or_default();
        fb.to_srgb8_into(&mut rgb);
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
        if !args.quiet && (i + 1) % 30 == 0 {
            eprintln!("wisp: frame {}/{} (t = {:.2} s)", i + 1, frames, t);
        }
    }
    drop(to_writer);
    let written = writer
        .join()
        .map_err(|_| AppError::other(anyhow::anyhow!("the PNG writer thread panicked")))?;
    written.map_err(AppError::other)?;
    if let Some(i) = failed {
        return Err(AppError::other(anyhow::anyhow!(
            "frame {i}: the PNG writer stopped"
        )));
    }
    if !args.quiet {
        print_timings(&total, frames, started.elapsed().as_secs_f64());
        eprintln!("wisp: wrote {} frames to {}", frames, args.out.display());
    }
    Ok(())
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
