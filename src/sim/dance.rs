//! An analytic dance: a head transform and body spheres as closed-form functions of time.
//!
//! What: a stand-in motion source for tests, benchmarks and demos that needs no file, so the
//! simulator can be exercised independently of the glTF motion loader. Anything
//! that can fill a [`Colliders`] at time t plugs into [`super::Simulator::advance`] the same way.
//!
//! How (τ = `speed` · t, seconds): the head centre bobs 0.1 m at 2 Hz and sways
//! (`translation`), and the head turns with
//! - yaw   = 0.9 sin(2π·0.5τ) + 0.32 sin(2π·2.6τ)   (peak rate 0.9·π + 0.32·5.2π ≈ 8.1 rad/s),
//! - pitch = 0.3 sin(2π·1.0τ + 0.7)                 (nod, peak 1.9 rad/s),
//! - roll  = 0.12 sin(2π·0.7τ + 1.3),
//!
//! composed as `R = R_y(yaw) R_x(pitch) R_z(roll)` about the head centre. The torso does not turn
//! with the head: a neck sphere and a shoulder/upper-back sphere follow the head centre's
//! translation only. They are placed so that no rotation of the head can make the ellipsoid
//! touch them (the nearest sphere point is 0.1057 m from the head centre, beyond the largest
//! semi-axis 0.098 m of the presets plus the collision margin), so hair is never squeezed
//! between two solids; hanging hair drapes over the shoulder sphere.
//!
//! Peak speeds at `speed` = 1: scalp points (≈ 0.1 m from the centre) ≈ 0.8 m/s from the yaw,
//! head centre 1.26 m/s from the bob; at `speed` = 3 these triple, still well under the
//! tunnelling limit discussed in `collide.rs`.

use super::collide::{Colliders, SphereCollider};
use glam::{Affine3A, Quat, Vec3};
use std::f64::consts::TAU;

/// Neck sphere: centre relative to the head centre (world axes, metres) and radius.
pub const NECK_OFFSET_M: Vec3 = Vec3::new(0.0, -0.15, -0.015);
/// Neck sphere radius, metres.
pub const NECK_RADIUS_M: f32 = 0.045;
/// Shoulder / upper-back sphere centre relative to the head centre, metres.
pub const SHOULDERS_OFFSET_M: Vec3 = Vec3::new(0.0, -0.27, -0.03);
/// Shoulder / upper-back sphere radius, metres.
pub const SHOULDERS_RADIUS_M: f32 = 0.13;
/// Head centre at rest, world metres (a standing adult).
pub const HEAD_HOME_M: Vec3 = Vec3::new(0.0, 1.6, 0.0);

/// The analytic dance motion (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnalyticDance {
    /// Semi-axes of the head ellipsoid, metres.
    pub head_radii_m: Vec3,
    /// Playback speed factor (1: as designed; 3: the stress test).
    pub speed: f64,
    /// Body spheres on (true) or head only (false).
    pub with_body: bool,
}

impl AnalyticDance {
    /// The dance at normal speed with body spheres.
    pub fn new(head_radii_m: Vec3) -> Self {
        Self {
            head_radii_m,
            speed: 1.0,
            with_body: true,
        }
    }

    /// Head frame → world at time `t_s`.
    pub fn head_at(&self, t_s: f64) -> Affine3A {
        let tau = self.speed * t_s;
        let s = |amp: f64, hz: f64, phase: f64| (amp * (TAU * hz * tau + phase).sin()) as f32;
        let yaw = s(0.9, 0.5, 0.0) + s(0.32, 2.6, 0.0);
        let pitch = s(0.3, 1.0, 0.7);
        let roll = s(0.12, 0.7, 1.3);
        let rot =
            Quat::from_rotation_y(yaw) * Quat::from_rotation_x(pitch) * Quat::from_rotation_z(roll);
        Affine3A::from_rotation_translation(rot, HEAD_HOME_M + self.translation_m(t_s))
    }

    /// Head-centre displacement from [`HEAD_HOME_M`] at `t_s`, metres: the 2 Hz bob and sway.
    pub fn translation_m(&self, t_s: f64) -> Vec3 {
        let tau = self.speed * t_s;
        let s = |amp: f64, hz: f64, phase: f64| (amp * (TAU * hz * tau + phase).sin()) as f32;
        Vec3::new(s(0.05, 0.5, 0.0), s(0.1, 2.0, 0.0), s(0.03, 0.8, 0.4))
    }

    /// Fills `c` with the colliders at `t_s` (reusing its sphere vector: no allocation once it
    /// has held two spheres). This is the closure to give [`super::Simulator::advance`].
    pub fn colliders_at(&self, t_s: f64, c: &mut Colliders) {
        c.head = self.head_at(t_s);
        c.head_radii_m = self.head_radii_m;
        c.spheres.clear();
        if self.with_body {
            let centre = HEAD_HOME_M + self.translation_m(t_s);
            c.spheres.push(SphereCollider {
                center: centre + NECK_OFFSET_M,
                radius_m: NECK_RADIUS_M,
            });
            c.spheres.push(SphereCollider {
                center: centre + SHOULDERS_OFFSET_M,
                radius_m: SHOULDERS_RADIUS_M,
            });
        }
    }

    /// The colliders at `t_s`, freshly allocated.
    pub fn colliders(&self, t_s: f64) -> Colliders {
        let mut c = Colliders::head_only(Affine3A::IDENTITY, self.head_radii_m);
        self.colliders_at(t_s, &mut c);
        c
    }
}

#[cfg(test)]
mod tests;
