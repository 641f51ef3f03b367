//! `wisp play`: the dance with simulated, self-shadowed hair, live in a window (minifb).
//!
//! The motion moves the same whole number of simulation steps each frame, the steps of the frame
//! interval the window sustains ([`clock`]), times `--speed`: real time on average, and one
//! slow frame does not make the next one slower.
//!
//! Mouse ([`view`], on the gestures of [`orbit`]): left drag orbits the camera about its
//! target, right or middle drag (or Shift + left drag) pans it across the view, the wheel
//! zooms toward the target. The camera starts as the engine framed it; a head-following
//! camera keeps following the head after it was moved, a fixed one (scene flags or file)
//! stays fixed in the world.
//!
//! Keys ([`keys`]): Space pause, S cycle the fibre shader, C toggle self-collision, Left/Right
//! turn the lights about the vertical through the head, Up/Down tilt them about the view's
//! horizontal axis (Up lifts a light on the camera's side of the head), V reset the view, H
//! hide the readout, P write a screenshot (`wisp-shot-NNNN.png` in the current directory,
//! without the readout), L switch between the preview and final quality levels (the hair
//! settles again), R restart, Esc or Q quit. The readout ([`overlay`]) shows the frame
//! rate, the mean time of each stage and of the window's own work, the simulation steps per
//! frame, the shader, whether
//! self-collision and pause are on, and the quality level (`preview` unless `--quality` or the
//! scene file says otherwise).

mod clock;
mod keys;
mod orbit;
mod overlay;
mod view;

use super::{AppError, SceneArgs};
use clock::MotionClock;
use keys::{Controls, Flow, PressRecorder, Presses, turn_lights};
use minifb::{Window, WindowOptions};
use overlay::ReadoutMeter;
use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::time::{Duration, Instant};
use view::ViewControl;
use wisp::engine::Engine;
use wisp::output::write_png_rgb8;
use wisp::quality::Quality;

#[derive(clap::Args, Debug)]
pub struct PlayArgs {
    /// Quit after this many frames [default: run until the window is closed]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: Option<u32>,
    /// Write the last frame shown to this PNG file on exit
    #[arg(long, value_name = "FILE.png")]
    pub screenshot: Option<PathBuf>,
    #[command(flatten)]
    pub scene: SceneArgs,
}

/// Shortest time between two frames, seconds (at most 60 frames a second).
const MIN_FRAME_INTERVAL_S: f64 = 1.0 / 60.0;

pub fn run(mut args: PlayArgs) -> Result<(), AppError> {
    args.scene.default_quality = Quality::Preview;
    let (style, hair, motion, mut config) = args.scene.resolve()?;
    if let Some(path) = &args.screenshot {
        super::check_output_file("--screenshot", path)?;
    }
    let plan = wisp::budget::RunPlan {
        frame_interval_s: MIN_FRAME_INTERVAL_S,
        warm_up_s: 0.0,
        export_png: args.screenshot.is_some(),
        cache: wisp::budget::CacheUse::None,
    };
    args.scene
        .budget
        .check(&style, &motion, &mut config, &plan)?;
    let (w, h) = (config.scene.width as usize, config.scene.height as usize);
    let (mut window, presses) = open_window(w, h)?;
    let mut engine = super::engine(style, hair, motion, config);
    let mut view = ViewControl::new(&engine);
    let mut controls = Controls::default();
    let mut meter = ReadoutMeter::new();
    let mut argb = Vec::new();
    let mut clock = Instant::now();
    let mut motion_clock = MotionClock::new(MIN_FRAME_INTERVAL_S, step_s(&engine));
    let mut shown = 0u32;
    while window.is_open() {
        let now = Instant::now();
        let dt_s = (now - clock).as_secs_f64();
        let moved_s = motion_clock.tick(dt_s);
        if !controls.paused {
            controls.t_s += moved_s;
        }
        clock = now;
        let pressed = std::mem::take(&mut presses.borrow_mut().pressed);
        if controls.apply_keys(pressed, &mut engine, &mut view) == Flow::Quit {
            break;
        }
        if std::mem::take(&mut controls.level_wanted) {
            engine = rebuilt_at(&args.scene, &engine, keys::next_level(engine.level))?;
            view = ViewControl::new(&engine);
            motion_clock = MotionClock::new(MIN_FRAME_INTERVAL_S, step_s(&engine));
        }
        // A slow frame turns the lights no further than a tenth of a second would.
        turn_lights(&window, &mut engine, dt_s.min(0.1) as f32);
        view.handle_mouse(&window, &engine);
        engine.advance(controls.t_s);
        view.apply(&mut engine);
        engine.render();
        if std::mem::take(&mut controls.screenshot_wanted) {
            save_screenshot(&engine);
        }
        let t_window = Instant::now();
        engine.framebuffer().to_argb_u32_into(&mut argb);
        if controls.show_readout {
            meter.draw(&mut argb, w, h);
        }
        window
            .update_with_buffer(&argb, w, h)
            .map_err(|e| AppError::other(anyhow::anyhow!("window update failed: {e}")))?;
        shown += 1;
        let steps = motion_clock.steps_per_frame();
        meter.record(
            &engine,
            t_window.elapsed().as_secs_f64(),
            controls.paused,
            steps,
        );
        if args.frames.is_some_and(|n| shown >= n) {
            break;
        }
        let spare_s = MIN_FRAME_INTERVAL_S - now.elapsed().as_secs_f64();
        if spare_s > 0.0 {
            std::thread::sleep(Duration::from_secs_f64(spare_s));
        }
    }
    if let Some(path) = &args.screenshot {
        let fb = engine.framebuffer();
        write_png_rgb8(path, fb.width, fb.height, &fb.to_srgb8()).map_err(AppError::input)?;
    }
    Ok(())
}

/// Seconds of one simulation step of `engine`.
fn step_s(engine: &Engine) -> f64 {
    engine.simulation.config.step_s(&engine.style) as f64
}

/// The engine of `args` rebuilt at `level` (the flags given still override it) with
/// `engine`'s scene (its lights as turned), its hair settled again; refused (exit code 2) when
/// that level is over the budget.
fn rebuilt_at(args: &SceneArgs, engine: &Engine, level: Quality) -> Result<Engine, AppError> {
    eprintln!("wisp play: quality {level}: settling the hair again");
    let (style, hair, motion, _) = args.resolve()?;
    let mut config = args.config(engine.scene.clone(), level);
    let plan = wisp::budget::RunPlan {
        frame_interval_s: MIN_FRAME_INTERVAL_S,
        warm_up_s: 0.0,
        export_png: false,
        cache: wisp::budget::CacheUse::None,
    };
    args.budget.check(&style, &motion, &mut config, &plan)?;
    Ok(super::engine(style, hair, motion, config))
}

/// A `w` × `h` window that records every key press ([`Presses`]); the loop limits the frame
/// rate itself, outside the timed window work.
fn open_window(w: usize, h: usize) -> Result<(Window, Rc<RefCell<Presses>>), AppError> {
    let mut window = Window::new("wisp", w, h, WindowOptions::default()).map_err(|e| {
        AppError::other(anyhow::anyhow!(
            "cannot open a window ({e}); without a display, use `wisp render` to write PNG frames"
        ))
    })?;
    window.set_target_fps(0);
    let presses = Rc::new(RefCell::new(Presses::default()));
    window.set_input_callback(Box::new(PressRecorder(Rc::clone(&presses))));
    Ok((window, presses))
}

/// Writes the engine's last frame (without the readout) to the first free
/// `wisp-shot-NNNN.png` in the current directory and prints its path; a failure is printed
/// and the window goes on.
fn save_screenshot(engine: &Engine) {
    let Some(path) = free_shot_path(Path::new(""), |p| p.exists()) else {
        eprintln!("screenshot: wisp-shot-0001.png to wisp-shot-9999.png all exist; none written");
        return;
    };
    let fb = engine.framebuffer();
    match write_png_rgb8(&path, fb.width, fb.height, &fb.to_srgb8()) {
        Ok(()) => println!("screenshot: {}", path.display()),
        Err(e) => eprintln!("screenshot: {e}"),
    }
}

/// The first `dir/wisp-shot-NNNN.png` (0001 to 9999) that `exists` says is free.
fn free_shot_path(dir: &Path, exists: impl Fn(&Path) -> bool) -> Option<PathBuf> {
    (1..=9999)
        .map(|i| dir.join(format!("wisp-shot-{i:04}.png")))
        .find(|p| !exists(p))
}

#[cfg(test)]
mod tests;
