//! The window's mouse camera: orbit about a target, pan across the view, zoom toward the target.
//!
//! What: [`Orbit`] holds a camera as a target, a distance and two angles (azimuth about an up
//! axis, elevation above the plane across it), so that each mouse gesture is one change of one
//! quantity: orbiting changes the angles and nothing else (the distance to the target is kept
//! exactly), zooming changes the distance and nothing else (scaled, and clamped, so the eye never
//! reaches the target), panning moves the target and the eye together (the view direction and
//! distance stay). The eye is derived, never stored, so no sequence of gestures can drift.
//!
//! How: the up axis is the camera's up hint as it was when the orbit started (world Y for the
//! engine's own framing). The elevation is clamped to ±[`MAX_ELEVATION_RAD`] (85°), so the view
//! direction keeps at least 5° from the up axis: the camera's basis never degenerates at the
//! poles and the camera always passes [`CameraSpec::new`]. Gestures follow the "grab" feel: a
//! drag to the right turns the scene to the right (the eye goes left about the target), a drag
//! down tilts its top toward the viewer (the eye goes up), and a pan keeps the point under the
//! mouse, at the target's depth, under the mouse.
//!
//! Pure: no window and no engine, so the invariants are unit-tested here; `view.rs` turns mouse
//! deltas into these calls and the result into the engine's fixed camera.

use glam::Vec3;
use wisp::raster::Camera;
use wisp::scene::{CameraError, CameraSpec};

/// Largest elevation above (or below) the plane across the up axis, radians (85°).
pub const MAX_ELEVATION_RAD: f32 = 85.0 * std::f32::consts::PI / 180.0;
/// Orbit angle per pixel of mouse drag, radians (a drag across 400 px turns about 180°).
pub const ORBIT_RAD_PER_PX: f32 = 0.008;
/// Zoom per scroll step (one notch of a wheel): the distance is scaled by exp(∓0.15).
pub const ZOOM_PER_STEP: f32 = 0.15;
/// Nearest the eye may come to the target, metres (5 near planes of the default camera), unless
/// the orbit started nearer.
pub const MIN_DISTANCE_M: f32 = 0.05;
/// Farthest the eye may go from the target, metres, unless the orbit started farther.
pub const MAX_DISTANCE_M: f32 = 50.0;
/// Farthest a pan may carry the target from the origin along each axis, metres, unless the
/// orbit started farther: beyond it f32 positions would be too coarse for a 5 cm view
/// (the spacing of f32 values at 1 km is 0.06 mm).
pub const MAX_PAN_M: f32 = 1000.0;

/// A camera as target, distance and angles about an up axis. See the module doc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    /// The point looked at, metres (in whatever frame the caller keeps: world, or head-relative).
    target: Vec3,
    /// Eye to target, metres, in `[min_distance_m, max_distance_m]`.
    distance_m: f32,
    /// Angle about `pole` from `axis_a` toward `axis_b`, radians (any value).
    azimuth_rad: f32,
    /// Angle above the plane across `pole`, radians, in ±[`MAX_ELEVATION_RAD`].
    elevation_rad: f32,
    /// Unit up axis; `axis_a`, `axis_b` complete it to a right-handed basis (b × pole = a).
    pole: Vec3,
    axis_a: Vec3,
    axis_b: Vec3,
    /// Vertical field of view, radians.
    fov_y_rad: f32,
    min_distance_m: f32,
    max_distance_m: f32,
    /// Bound of each coordinate of `target`, metres.
    max_target_m: f32,
}

/// What a mouse drag does, from the buttons held and Shift.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Drag {
    None,
    Orbit,
    Pan,
}

impl Drag {
    /// Left drag orbits; Shift + left, right or middle drag pans.
    pub fn from_buttons(left: bool, right: bool, middle: bool, shift: bool) -> Drag {
        if right || middle || (left && shift) {
            Drag::Pan
        } else if left {
            Drag::Orbit
        } else {
            Drag::None
        }
    }
}

impl Orbit {
    /// The orbit that reproduces `cam` (eye, target, up, field of view), with `offset_m`
    /// subtracted from its eye and target (the head's position, for a camera that follows the
    /// head; zero for one fixed in the world). A non-finite or degenerate camera (eye at the
    /// target, zero up) falls back to a unit distance and world Y up; an elevation beyond
    /// ±85° is clamped (the camera then moves once, to the clamp).
    pub fn from_camera(cam: &Camera, offset_m: Vec3) -> Orbit {
        let pole = cam
            .up
            .try_normalize()
            .filter(|u| u.is_finite())
            .unwrap_or(Vec3::Y);
        // Any unit b across the pole; a = b × pole makes the basis right-handed by construction
        // (for the pole Y and b = X, a = Z: azimuth 0 looks from +Z).
        let axis_b = pole.any_orthonormal_vector();
        let axis_a = axis_b.cross(pole);
        let target = if cam.target.is_finite() && offset_m.is_finite() {
            cam.target - offset_m
        } else {
            Vec3::ZERO
        };
        let back = cam.eye - cam.target;
        let distance = back.length();
        let (distance_m, dir) = if distance.is_finite() && distance > 1e-6 {
            (distance, back / distance)
        } else {
            (1.0, axis_a)
        };
        let elevation_rad = dir
            .dot(pole)
            .clamp(-1.0, 1.0)
            .asin()
            .clamp(-MAX_ELEVATION_RAD, MAX_ELEVATION_RAD);
        let azimuth_rad = dir.dot(axis_b).atan2(dir.dot(axis_a));
        let fov_y_rad = if cam.fov_y_rad > 0.0 && cam.fov_y_rad < std::f32::consts::PI {
            cam.fov_y_rad
        } else {
            wisp::scene::HEAD_FOLLOWING_FOV_Y_RAD
        };
        Orbit {
            target,
            distance_m,
            azimuth_rad: if azimuth_rad.is_finite() {
                azimuth_rad
            } else {
                0.0
            },
            elevation_rad,
            pole,
            axis_a,
            axis_b,
            fov_y_rad,
            min_distance_m: MIN_DISTANCE_M.min(distance_m),
            max_distance_m: MAX_DISTANCE_M.max(distance_m),
            max_target_m: MAX_PAN_M.max(target.abs().max_element()),
        }
    }

    /// Unit direction from the target toward the eye.
    fn back(&self) -> Vec3 {
        let (sa, ca) = self.azimuth_rad.sin_cos();
        let (se, ce) = self.elevation_rad.sin_cos();
        ce * (ca * self.axis_a + sa * self.axis_b) + se * self.pole
    }

    /// The eye, metres (the orbit's frame).
    pub fn eye(&self) -> Vec3 {
        self.target + self.distance_m * self.back()
    }

    /// Unit image-right and image-up axes of the current view.
    fn image_axes(&self) -> (Vec3, Vec3) {
        let forward = -self.back();
        // Never degenerate: the elevation keeps the view at least 5° from the pole.
        let right = forward.cross(self.pole).normalize();
        (right, right.cross(forward))
    }

    /// Turns the eye about the target by a mouse drag of (`dx_px` right, `dy_px` down): the
    /// azimuth by −dx · [`ORBIT_RAD_PER_PX`], the elevation by +dy · [`ORBIT_RAD_PER_PX`],
    /// clamped. The distance to the target does not change. Non-finite deltas are ignored.
    pub fn orbit(&mut self, dx_px: f32, dy_px: f32) {
        if !(dx_px.is_finite() && dy_px.is_finite()) {
            return;
        }
        // Keep the azimuth small so its sine and cosine stay exact after long sessions.
        self.azimuth_rad =
            (self.azimuth_rad - dx_px * ORBIT_RAD_PER_PX).rem_euclid(std::f32::consts::TAU);
        self.elevation_rad = (self.elevation_rad + dy_px * ORBIT_RAD_PER_PX)
            .clamp(-MAX_ELEVATION_RAD, MAX_ELEVATION_RAD);
    }

    /// Moves the eye and the target together across the view by a mouse drag of (`dx_px`
    /// right, `dy_px` down) in an image `height_px` tall, so that a point at the target's depth
    /// follows the mouse, up to [`MAX_PAN_M`] from the origin. Non-finite deltas and a zero
    /// height are ignored.
    pub fn pan(&mut self, dx_px: f32, dy_px: f32, height_px: u32) {
        if !(dx_px.is_finite() && dy_px.is_finite()) || height_px == 0 {
            return;
        }
        // Metres per pixel at the target's depth: the image height spans 2 d tan(fov/2).
        let m_per_px = 2.0 * self.distance_m * (0.5 * self.fov_y_rad).tan() / height_px as f32;
        let (right, up) = self.image_axes();
        let bound = Vec3::splat(self.max_target_m);
        self.target = (self.target + m_per_px * (-dx_px * right + dy_px * up)).clamp(-bound, bound);
    }

    /// Moves the eye toward the target by `steps` wheel notches (negative: away): the distance
    /// is scaled by exp(−[`ZOOM_PER_STEP`] · steps) and clamped to its range, so it stays
    /// positive and the eye never reaches or crosses the target. Non-finite steps are ignored.
    pub fn zoom(&mut self, steps: f32) {
        if !steps.is_finite() {
            return;
        }
        // Clamp the exponent too: a huge scroll must not overflow to inf or 0 · inf.
        let scale = (-ZOOM_PER_STEP * steps).clamp(-20.0, 20.0).exp();
        self.distance_m = (self.distance_m * scale).clamp(self.min_distance_m, self.max_distance_m);
    }

    /// The fixed camera of this orbit with `offset_m` added to the eye and target (the head's
    /// position for a camera that follows the head).
    pub fn spec(&self, offset_m: Vec3) -> Result<CameraSpec, CameraError> {
        CameraSpec::new(
            self.eye() + offset_m,
            self.target + offset_m,
            self.pole,
            self.fov_y_rad,
        )
    }
}

#[cfg(test)]
mod tests;
