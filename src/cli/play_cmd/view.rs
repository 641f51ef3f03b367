//! The window's mouse camera applied to the engine: drags and the wheel read from the window
//! each frame become gestures of an [`Orbit`] (`orbit.rs`), whose camera the engine then
//! takes as a fixed camera. Left drag orbits, right or middle drag (or Shift + left) pans, the
//! wheel zooms; V returns to the engine's own camera.

use super::orbit::{Drag, Orbit};
use glam::Vec3;
use minifb::{Key, MouseButton, MouseMode, Window};
use wisp::engine::Engine;
use wisp::scene::CameraSetup;

/// What minifb's X11 backend adds to the vertical scroll per wheel notch: 1 for the button
/// press and 1 for its release (positive for the wheel turned away from the user: zoom in).
const SCROLL_PER_NOTCH: f32 = 2.0;

/// The mouse camera: off until the first drag or scroll, then an [`Orbit`] applied to the
/// engine as a fixed camera each frame (offset by the head's position when the engine's own
/// camera followed the head).
pub(super) struct ViewControl {
    /// The camera setup the engine started with (V returns to it).
    initial: CameraSetup,
    /// Whether the engine's own camera followed the head (its `head` framing).
    initial_follows_head: bool,
    orbit: Option<Orbit>,
    /// The last mouse position, pixels, while a button is held.
    last_mouse: Option<(f32, f32)>,
}

impl ViewControl {
    pub fn new(engine: &Engine) -> Self {
        ViewControl {
            initial: engine.scene.camera,
            initial_follows_head: engine.camera.follows_head(),
            orbit: None,
            last_mouse: None,
        }
    }

    /// Where the orbit is anchored: the head's position for a head-following camera.
    fn offset_m(&self, engine: &Engine) -> Vec3 {
        if self.initial_follows_head {
            Vec3::from(engine.pose().head.translation)
        } else {
            Vec3::ZERO
        }
    }

    pub fn handle_mouse(&mut self, window: &Window, engine: &Engine) {
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
    pub fn apply(&self, engine: &mut Engine) {
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
    pub fn reset(&mut self, engine: &mut Engine) {
        self.orbit = None;
        engine.set_camera(self.initial);
    }
}

#[cfg(test)]
mod tests;
