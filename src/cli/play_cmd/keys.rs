//! The window's keys: each press seen once however short ([`Presses`]), what the keys switch
//! ([`Controls`]: pause, shader, self-collision, readout, restart, view, screenshot, quality
//! level, quit),
//! and the arrow keys turning the lights while held ([`turn_lights`]).

use super::view::ViewControl;
use glam::{Quat, Vec3};
use minifb::{InputCallback, Key, Window};
use std::cell::RefCell;
use std::rc::Rc;
use wisp::engine::Engine;
use wisp::fiber::ShadingMode;
use wisp::quality::Quality;

/// Light turn rate while an arrow key is held, radians per second (about 70°/s).
const LIGHT_TURN_RAD_PER_S: f32 = 1.2;

/// Whether the window goes on after the keys of a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Flow {
    Go,
    Quit,
}

/// The motion's clock and the switches the keys flip.
pub(super) struct Controls {
    /// Seconds of the motion shown: moved by the motion clock (`clock`) except while paused;
    /// R sets it to 0.
    pub t_s: f64,
    pub paused: bool,
    pub show_readout: bool,
    /// P was pressed: a screenshot is written after this frame's render.
    pub screenshot_wanted: bool,
    /// L was pressed: the engine is rebuilt at [`next_level`] before this frame.
    pub level_wanted: bool,
}

impl Default for Controls {
    fn default() -> Self {
        Self {
            t_s: 0.0,
            paused: false,
            show_readout: true,
            screenshot_wanted: false,
            level_wanted: false,
        }
    }
}

impl Controls {
    /// Acts on the keys pressed since the last frame, in order, up to Esc or Q (quit).
    pub fn apply_keys(
        &mut self,
        pressed: Vec<Key>,
        engine: &mut Engine,
        view: &mut ViewControl,
    ) -> Flow {
        for key in pressed {
            match key {
                Key::Escape | Key::Q => return Flow::Quit,
                Key::Space => self.paused = !self.paused,
                Key::S => engine.shading.config.mode = next_shader(engine.shading.config.mode),
                Key::C => {
                    engine.simulation.config.self_collision =
                        !engine.simulation.config.self_collision
                }
                Key::H => self.show_readout = !self.show_readout,
                Key::R => self.t_s = 0.0,
                Key::V => view.reset(engine),
                Key::P => self.screenshot_wanted = true,
                Key::L => self.level_wanted = true,
                _ => {}
            }
        }
        Flow::Go
    }
}

/// The level after `level` in the cycle of the L key: preview and final, the two that draw in
/// a fraction of a second (`reference` traces light paths, seconds a frame: for exports).
pub(super) fn next_level(level: Quality) -> Quality {
    match level {
        Quality::Preview => Quality::Final,
        Quality::Final | Quality::Reference => Quality::Preview,
    }
}

/// The shader after `mode` in the cycle of the S key: dual, single, Kajiya-Kay, visibility,
/// and back to dual (the volume shader, seconds per frame, is not in the cycle).
fn next_shader(mode: ShadingMode) -> ShadingMode {
    match mode {
        ShadingMode::DualScattering => ShadingMode::SingleScattering,
        ShadingMode::SingleScattering => ShadingMode::KajiyaKay,
        ShadingMode::KajiyaKay => ShadingMode::Visibility,
        ShadingMode::Visibility | ShadingMode::Volume => ShadingMode::DualScattering,
    }
}

/// The keys pressed since the last frame, in order, each press once. A frame can take a
/// second: minifb's own `is_key_pressed` compares key levels from one frame to the next, so
/// a tap pressed and released within one frame would be lost; its input callback sees every
/// event.
#[derive(Default)]
pub(super) struct Presses {
    /// Keys held now (a held key's repeats are not new presses).
    down: Vec<Key>,
    pub pressed: Vec<Key>,
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
pub(super) struct PressRecorder(pub Rc<RefCell<Presses>>);

impl InputCallback for PressRecorder {
    fn add_char(&mut self, _uni_char: u32) {}
    fn set_key_state(&mut self, key: Key, is_down: bool) {
        self.0.borrow_mut().set(key, is_down);
    }
}

/// Left/Right turn every light about the vertical through the head centre, Up/Down about the
/// view's horizontal axis through it, at [`LIGHT_TURN_RAD_PER_S`] for `dt_s` seconds.
pub(super) fn turn_lights(window: &Window, engine: &mut Engine, dt_s: f32) {
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

#[cfg(test)]
mod tests;
