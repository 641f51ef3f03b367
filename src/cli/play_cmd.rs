//! `wisp play`: the dance with simulated, self-shadowed hair, live in a window (minifb).
//!
//! The motion runs on the wall clock (times `--speed`); the simulation catches up in fixed steps,
//! so a slow frame makes the hair jump ahead rather than slow down. Keys:
//! Space pause, S cycle the fibre shader, C toggle self-collision, Left/Right turn the light,
//! R restart, Esc or Q quit. The title bar shows the frame rate and per-stage times.

use super::{AppError, SceneArgs};
use glam::{Quat, Vec3};
use minifb::{Key, KeyRepeat, Window, WindowOptions};
use std::path::PathBuf;
use std::time::Instant;
use wisp::fiber::ShadingMode;
use wisp::frame::StageTimings;
use wisp::output::write_png_rgb8;

#[derive(clap::Args, Debug)]
pub struct PlayArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Quit after this many frames (default: run until the window is closed).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: Option<u32>,
    /// Write the last frame shown to this PNG file on exit.
    #[arg(long)]
    pub screenshot: Option<PathBuf>,
}

pub fn run(args: PlayArgs) -> Result<(), AppError> {
    let (style, hair, motion, mut config) = args.scene.resolve()?;
    if let Some(path) = &args.screenshot {
        super::check_output_file("--screenshot", path)?;
    }
    let plan = wisp::budget::RunPlan {
        frame_interval_s: 1.0 / 60.0,
        warm_up_s: 0.0,
        export_png: args.screenshot.is_some(),
        cache: wisp::budget::CacheUse::None,
    };
    args.scene
        .check_budget(&style, &motion, &mut config, &plan)?;
    let (w, h) = (config.width as usize, config.height as usize);
    let mut window = Window::new("wisp", w, h, WindowOptions::default()).map_err(|e| {
        AppError::other(anyhow::anyhow!(
            "cannot open a window ({e}); without a display, use `wisp render` to write PNG frames"
        ))
    })?;
    window.set_target_fps(60);
    let mut engine = super::engine(style, hair, motion, config);
    let mut argb = Vec::new();
    let mut clock = Instant::now();
    let mut t_s = 0.0f64;
    let mut paused = false;
    let mut shown = 0u32;
    let mut recent = StageTimings::default();
    let mut recent_frames = 0u32;
    let mut fps_clock = Instant::now();
    while window.is_open() && !window.is_key_down(Key::Escape) && !window.is_key_down(Key::Q) {
        let now = Instant::now();
        if !paused {
            t_s += (now - clock).as_secs_f64();
        }
        clock = now;
        if window.is_key_pressed(Key::Space, KeyRepeat::No) {
            paused = !paused;
        }
        if window.is_key_pressed(Key::S, KeyRepeat::No) {
            engine.config.lighting.mode = match engine.config.lighting.mode {
                ShadingMode::DualScattering => ShadingMode::SingleScattering,
                ShadingMode::SingleScattering => ShadingMode::KajiyaKay,
                ShadingMode::KajiyaKay => ShadingMode::DualScattering,
            };
        }
        if window.is_key_pressed(Key::C, KeyRepeat::No) {
            engine.config.self_collision = !engine.config.self_collision;
        }
        for (key, angle) in [(Key::Left, 0.05f32), (Key::Right, -0.05)] {
            if window.is_key_down(key) {
                let pivot = Vec3::from(engine.pose().head.translation);
                engine
                    .config
                    .lighting
                    .turn(Quat::from_axis_angle(Vec3::Y, angle), pivot);
            }
        }
        if window.is_key_pressed(Key::R, KeyRepeat::No) {
            t_s = 0.0;
        }
        engine.advance(t_s);
        engine.render().to_argb_u32_into(&mut argb);
        window
            .update_with_buffer(&argb, w, h)
            .map_err(|e| AppError::other(anyhow::anyhow!("window update failed: {e}")))?;
        shown += 1;
        recent.add(&engine.timings);
        recent_frames += 1;
        if fps_clock.elapsed().as_secs_f64() >= 0.5 {
            let fps = recent_frames as f64 / fps_clock.elapsed().as_secs_f64();
            let m = recent.scaled(1e3 / recent_frames as f64);
            window.set_title(&format!(
                "wisp - {:.1} fps - {:?}{} - sim {:.1} ms, map {:.1}, shade {:.1}, raster {:.1}{}",
                fps,
                engine.config.lighting.mode,
                if engine.config.self_collision {
                    ""
                } else {
                    ", no self-collision"
                },
                m.simulation_s,
                m.map_s,
                m.shading_s,
                m.raster_s,
                if paused { " - paused" } else { "" }
            ));
            recent = StageTimings::default();
            recent_frames = 0;
            fps_clock = Instant::now();
        }
        if args.frames.is_some_and(|n| shown >= n) {
            break;
        }
    }
    if let Some(path) = &args.screenshot {
        let fb = engine.framebuffer();
        write_png_rgb8(path, fb.width, fb.height, &fb.to_srgb8()).map_err(AppError::input)?;
    }
    Ok(())
}
