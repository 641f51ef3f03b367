//! `wisp play`: the dance with simulated, self-shadowed hair, live in a window (minifb).
//!
//! The motion runs on the wall clock (times `--speed`); the simulation catches up in fixed steps,
//! so a slow frame makes the hair jump ahead rather than slow down.
//!
//! Mouse: left drag orbits the camera about its target, right or middle drag (or Shift + left
//! drag) pans it across the view, the wheel zooms toward the target ([`orbit`]). The camera
//! starts as the engine framed it; a head-following camera keeps following the head after it
//! was moved, a fixed one (scene flags or file) stays fixed in the world. Keys: Space pause,
//! S cycle the fibre shader, C toggle self-collision, Left/Right turn the lights about the
//! vertical through the head, Up/Down tilt them about the view's horizontal axis (Up lifts a
//! light on the camera's side of the head), V reset the view, H hide the readout, P write a
//! screenshot (`wisp-shot-NNNN.png` in the current directory, without the readout), R restart,
//! Esc or Q quit. The readout ([`overlay`]) shows the frame rate, the mean time of each stage
//! and of the window's own work, the shader and whether self-collision and pause are on.

mod orbit;
mod overlay;

use super::{AppError, SceneArgs};
use glam::{Quat, Vec3};
use minifb::{InputCallback, Key, MouseButton, MouseMode, Window, WindowOptions};
use orbit::{Drag, Orbit};
use overlay::Readout;
use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::time::{Duration, Instant};
use wisp::engine::{Engine, StageTimings};
use wisp::fiber::ShadingMode;
use wisp::output::write_png_rgb8;
use wisp::scene::CameraSetup;

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

/// Light turn rate while an arrow key is held, radians per second (about 70°/s).
const LIGHT_TURN_RAD_PER_S: f32 = 1.2;
/// Shortest time between two frames, seconds (at most 60 frames a second).
const MIN_FRAME_INTERVAL_S: f64 = 1.0 / 60.0;
/// What minifb's X11 backend adds to the vertical scroll per wheel notch: 1 for the button
/// press and 1 for its release (positive for the wheel turned away from the user: zoom in).
const SCROLL_PER_NOTCH: f32 = 2.0;
/// How often the readout's figures are renewed (means over the frames since), seconds.
const READOUT_INTERVAL_S: f64 = 0.5;

pub fn run(args: PlayArgs) -> Result<(), AppError> {
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
        .check_budget(&style, &motion, &mut config, &plan)?;
    let (w, h) = (config.scene.width as usize, config.scene.height as usize);
    let mut window = Window::new("wisp", w, h, WindowOptions::default()).map_err(|e| {
        AppError::other(anyhow::anyhow!(
            "cannot open a window ({e}); without a display, use `wisp render` to write PNG frames"
        ))
    })?;
    // The loop limits the frame rate itself, outside the timed window work.
    window.set_target_fps(0);
    let presses = Rc::new(RefCell::new(Presses::default()));
    window.set_input_callback(Box::new(PressRecorder(Rc::clone(&presses))));
    let mut engine = super::engine(style, hair, motion, config);
    let mut view = ViewControl::new(&engine);
    let mut argb = Vec::new();
    let mut clock = Instant::now();
    let mut t_s = 0.0f64;
    let mut paused = false;
    let mut show_readout = true;
    let mut shown = 0u32;
    let mut sums = (StageTimings::default(), 0.0f64, 0u32);
    let mut readout: Option<Readout> = None;
    let mut readout_text = String::new();
    let mut readout_clock = Instant::now();
    let mut screenshot_wanted = false;
    'frames: while window.is_open() {
        let now = Instant::now();
        let dt_s = (now - clock).as_secs_f64();
        if !paused {
            t_s += dt_s;
        }
        clock = now;
        let pressed = std::mem::take(&mut presses.borrow_mut().pressed);
        for key in pressed {
            match key {
                Key::Escape | Key::Q => break 'frames,
                Key::Space => paused = !paused,
                Key::S => {
                    engine.shading.config.mode = match engine.shading.config.mode {
                        ShadingMode::DualScattering => ShadingMode::SingleScattering,
                        ShadingMode::SingleScattering => ShadingMode::KajiyaKay,
                        ShadingMode::KajiyaKay => ShadingMode::Visibility,
                        ShadingMode::Visibility | ShadingMode::Volume => {
                            ShadingMode::DualScattering
                        }
                    }
                }
                Key::C => {
                    engine.simulation.config.self_collision =
                        !engine.simulation.config.self_collision
                }
                Key::H => show_readout = !show_readout,
                Key::R => t_s = 0.0,
                Key::V => view.reset(&mut engine),
                Key::P => screenshot_wanted = true,
                _ => {}
            }
        }
        // A slow frame turns the lights no further than a tenth of a second would.
        turn_lights(&window, &mut engine, dt_s.min(0.1) as f32);
        view.handle_mouse(&window, &engine);
        engine.advance(t_s);
        view.apply(&mut engine);
        engine.render();
        if std::mem::take(&mut screenshot_wanted) {
            save_screenshot(&engine);
        }
        let t_window = Instant::now();
        engine.framebuffer().to_argb_u32_into(&mut argb);
        if show_readout && let Some(r) = &readout {
            r.write_into(&mut readout_text);
            overlay::draw_panel(&mut argb, w, h, &readout_text, overlay::scale_for(w));
        }
        window
            .update_with_buffer(&argb, w, h)
            .map_err(|e| AppError::other(anyhow::anyhow!("window update failed: {e}")))?;
        shown += 1;
        sums.0.add(&engine.timings);
        sums.1 += t_window.elapsed().as_secs_f64();
        sums.2 += 1;
        let since_s = readout_clock.elapsed().as_secs_f64();
        if readout.is_none() || since_s >= READOUT_INTERVAL_S {
            let n = sums.2 as f64;
            readout = Some(Readout {
                fps: n / since_s.max(1e-9),
                stages: sums.0.scaled(1.0 / n),
                window_s: sums.1 / n,
                ..Readout::default()
            });
            sums = (StageTimings::default(), 0.0, 0);
            readout_clock = Instant::now();
        }
        if let Some(r) = &mut readout {
            r.mode = engine.shading.config.mode;
            r.self_collision = engine.simulation.config.self_collision;
            r.paused = paused;
        }
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

/// The keys pressed since the last frame, in order, each press once. A frame can take a
/// second: minifb's own `is_key_pressed` compares key levels from one frame to the next, so
/// a tap pressed and released within one frame would be lost; its input callback sees every
/// event.
#[derive(Default)]
struct Presses {
    /// Keys held now (a held key's repeats are not new presses).
    down: Vec<Key>,
    pressed: Vec<Key>,
}

impl Presses {
    fn set(&mut self, key: Key, is_down: bool) {
        let was_down = self.down.contains(&key);
        if is_down && !was_down {
            self.down.push(key);
            self.pressed.push(key);
        } else if !is_down {
            self.down.retain(|k| *k != key);
        }
    }
}

/// Hands minifb's key events to [`Presses`].
struct PressRecorder(Rc<RefCell<Presses>>);

impl InputCallback for PressRecorder {
    fn add_char(&mut self, _uni_char: u32) {}
    fn set_key_state(&mut self, key: Key, is_down: bool) {
        self.0.borrow_mut().set(key, is_down);
    }
}

/// Left/Right turn every light about the vertical through the head centre, Up/Down about the
/// view's horizontal axis through it, at [`LIGHT_TURN_RAD_PER_S`] for `dt_s` seconds.
fn turn_lights(window: &Window, engine: &mut Engine, dt_s: f32) {
    let angle = LIGHT_TURN_RAD_PER_S * dt_s;
    let right = engine.camera().view().right;
    let turns = [
        (Key::Left, Vec3::Y, angle),
        (Key::Right, Vec3::Y, -angle),
        // About the image's right axis a negative angle carries the camera's side upward.
        (Key::Up, right, -angle),
        (Key::Down, right, angle),
    ];
    for (key, axis, angle) in turns {
        if window.is_key_down(key) {
            let pivot = Vec3::from(engine.pose().head.translation);
            engine
                .scene
                .turn_lights(Quat::from_axis_angle(axis, angle), pivot);
        }
    }
}

/// The mouse camera: off until the first drag or scroll, then an [`Orbit`] applied to the
/// engine as a fixed camera each frame (offset by the head's position when the engine's own
/// camera followed the head).
struct ViewControl {
    /// The camera setup the engine started with (V returns to it).
    initial: CameraSetup,
    orbit: Option<Orbit>,
    /// The last mouse position, pixels, while a button is held.
    last_mouse: Option<(f32, f32)>,
}

impl ViewControl {
    fn new(engine: &Engine) -> Self {
        ViewControl {
            initial: engine.scene.camera,
            orbit: None,
            last_mouse: None,
        }
    }

    /// Where the orbit is anchored: the head's position for a head-following camera.
    fn offset_m(&self, engine: &Engine) -> Vec3 {
        match self.initial {
            CameraSetup::HeadFollowing => Vec3::from(engine.pose().head.translation),
            CameraSetup::Fixed(_) => Vec3::ZERO,
        }
    }

    fn handle_mouse(&mut self, window: &Window, engine: &Engine) {
        let shift = window.is_key_down(Key::LeftShift) || window.is_key_down(Key::RightShift);
        let drag = Drag::from_buttons(
            window.get_mouse_down(MouseButton::Left),
            window.get_mouse_down(MouseButton::Right),
            window.get_mouse_down(MouseButton::Middle),
            shift,
        );
        let scroll = window
            .get_scroll_wheel()
            .map_or(0.0, |(_, y)| y / SCROLL_PER_NOTCH);
        let pos = window.get_mouse_pos(MouseMode::Pass);
        let delta = match (drag, self.last_mouse, pos) {
            (Drag::None, ..) => None,
            (_, Some((x0, y0)), Some((x1, y1))) => Some((x1 - x0, y1 - y0)),
            _ => None,
        };
        self.last_mouse = if drag == Drag::None { None } else { pos };
        let moved = delta.is_some_and(|(dx, dy)| dx != 0.0 || dy != 0.0);
        if !moved && scroll == 0.0 {
            return;
        }
        let offset = self.offset_m(engine);
        let orbit = self
            .orbit
            .get_or_insert_with(|| Orbit::from_camera(engine.camera(), offset));
        if let Some((dx, dy)) = delta {
            match drag {
                Drag::Orbit => orbit.orbit(dx, dy),
                Drag::Pan => orbit.pan(dx, dy, engine.scene.height),
                Drag::None => {}
            }
        }
        orbit.zoom(scroll);
    }

    /// Sets the engine's camera from the orbit (after the frame's pose is known).
    fn apply(&self, engine: &mut Engine) {
        if let Some(orbit) = &self.orbit {
            // An orbit always makes a valid camera (orbit.rs); were it refused, the last
            // camera stays.
            if let Ok(spec) = orbit.spec(self.offset_m(engine)) {
                engine.set_camera(CameraSetup::Fixed(spec));
            }
        }
    }

    /// Back to the engine's own camera: the fixed one as given, or the head-following framing
    /// made anew on the current hair.
    fn reset(&mut self, engine: &mut Engine) {
        self.orbit = None;
        engine.set_camera(self.initial);
    }
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
