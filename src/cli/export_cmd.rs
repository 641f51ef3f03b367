//! `wisp export`: one frame as a reference scene for a path tracer (`tools/reference/`):
//! the render strands as cyHair `.hair`, `scene.json` (camera, light, fibre and its Mitsuba
//! mapping), and wisp's own linear RGBA EXR of the same frame with the same camera
//! (`wisp::export`). The frame is drawn over a black background, so the EXR's colour is
//! premultiplied by its coverage.

use super::{AppError, SceneArgs};
use anyhow::Context;
use glam::Vec3;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct ExportArgs {
    /// Output directory (created if missing): hair.hair, scene.json, wisp.exr/png
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Time of the frame in the motion, seconds
    #[arg(long, value_name = "SECONDS", default_value_t = 0.0, value_parser = super::parse_finite_f32)]
    pub time_s: f32,
    /// Print only errors
    #[arg(long)]
    pub quiet: bool,
    #[command(flatten)]
    pub scene: SceneArgs,
}

pub fn run(args: ExportArgs) -> Result<(), AppError> {
    let (style, hair, motion, mut config) = args.scene.resolve()?;
    // A path tracer's reference scene has one light (directional or point): refused before
    // any work.
    wisp::export::reference_light(&config.scene.lights)
        .map_err(|e| AppError::input(anyhow::anyhow!("export: {e}")))?;
    config.scene.background = Vec3::ZERO;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("{}: cannot create the output directory", args.out.display()))
        .map_err(AppError::input)?;
    let started = std::time::Instant::now();
    let mut engine = super::engine(style, hair, motion, config);
    let t = f64::from(args.time_s.max(0.0));
    engine.run_up_to(t);
    // Twice: the second frame is identical (same time, same state) and its timings are those
    // of a warmed-up engine (the first one allocates its buffers).
    engine.frame(t);
    engine.frame(t);
    let frame_ms = engine.timings.total_s() * 1e3;
    // A frame shades only the points the raster can draw; `vertex_rgb.f32` holds every
    // point's colour (the same colours where the frame has them, so the image is unchanged).
    engine.shade();
    let scene =
        wisp::export::write_reference_scene(&engine, &args.out, t).map_err(AppError::other)?;
    if !args.quiet {
        eprintln!(
            "wisp: exported {} ({} strands x {} points, {} fibres each) at t = {:.2} s, \
             {}x{} px, frame {:.1} ms (warm; map {:.1}, shading {:.1}, raster {:.1}), total {:.2} s, to {}",
            scene.hairstyle,
            scene.strands,
            scene.points_per_strand,
            scene.fibers_per_strand,
            t,
            scene.image.width,
            scene.image.height,
            frame_ms,
            engine.timings.map_s * 1e3,
            engine.timings.shading_s * 1e3,
            engine.timings.raster_s * 1e3,
            started.elapsed().as_secs_f64(),
            args.out.display()
        );
    }
    Ok(())
}
