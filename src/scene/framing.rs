//! How much of the figure the engine's own camera shows ([`Framing`]), and the camera that
//! shows a set of boxes ([`frame_boxes`]).
//!
//! - `head`: the head and its hair, close up, the camera following the head's translation
//!   ([`super::HeadFollowing`]).
//! - `upper`: the head and the upper body, head to hips; `full`: the whole figure, feet
//!   included. Both frame the character's extent over the whole clip
//!   ([`crate::motion::Motion::figure_extent`]) with the settled hair, once, and then stand
//!   still: the dance moves inside the picture, and the camera does not bob with the hips.
//!
//! The default ([`Framing::default_for`]) is `upper` when a character with a body is drawn:
//! the dance is in the body (the hips' groove, the arms, the turn), and the close-up shows it
//! only as a head that bobs; `upper` keeps the hair large enough to see strands (the head is
//! about a fifth of the picture's height) while the body moves. Without a body (a head alone,
//! or solids not drawn) there is nothing more to show, so `head`.

use crate::raster::Camera;
use crate::raster::camera::DEFAULT_NEAR_M;
use glam::Vec3;
use serde::{Deserialize, Serialize};

/// How much of the figure the engine's camera shows (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Framing {
    /// The head and its hair, following the head.
    Head,
    /// Head to hips, over the clip's whole motion.
    Upper,
    /// The whole figure, over the clip's whole motion.
    Full,
}

impl Framing {
    /// Every framing, in the order of the names.
    pub const ALL: [Framing; 3] = [Framing::Head, Framing::Upper, Framing::Full];

    /// The name in flags and scene files.
    pub fn name(self) -> &'static str {
        match self {
            Framing::Head => "head",
            Framing::Upper => "upper",
            Framing::Full => "full",
        }
    }

    /// The framing called `name` (`head`, `upper`, `full`).
    pub fn from_name(name: &str) -> Option<Framing> {
        Self::ALL.into_iter().find(|f| f.name() == name)
    }

    /// The framing when none is asked for: `upper` when a character's body is drawn
    /// (`body_drawn`), else `head` (see the module doc).
    pub fn default_for(body_drawn: bool) -> Framing {
        if body_drawn {
            Framing::Upper
        } else {
            Framing::Head
        }
    }
}

/// Fraction of the tangent of each half field of view the box may fill (the rest is margin).
const FILL: f32 = 0.9;

/// A camera's axes, world unit vectors: `right` and `up` across the image, `forward` from the
/// eye into the scene. A box "in these axes" has the coordinates `(p·right, p·up,
/// p·forward)` of world points `p`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewAxes {
    pub right: Vec3,
    pub up: Vec3,
    pub forward: Vec3,
}

impl ViewAxes {
    /// The axes of a camera looking along `-back` (`back`: from the target toward the eye),
    /// world +Y up (+Z when `back` is nearly vertical), as [`Camera::look_at`] makes them.
    pub fn looking_back_along(back: Vec3) -> ViewAxes {
        let back = back.try_normalize().unwrap_or(Vec3::Z);
        let up_hint = Self::up_hint(back);
        let forward = -back;
        let right = forward.cross(up_hint).normalize();
        ViewAxes {
            right,
            up: right.cross(forward),
            forward,
        }
    }

    /// `p`'s coordinates along the axes.
    pub fn coords(&self, p: Vec3) -> Vec3 {
        Vec3::new(p.dot(self.right), p.dot(self.up), p.dot(self.forward))
    }

    fn up_hint(back: Vec3) -> Vec3 {
        if back.y.abs() > 0.99 {
            Vec3::Z
        } else {
            Vec3::Y
        }
    }
}

/// A camera with `axes` looking at the centre of the union of `boxes` (each `(lo, hi)` in
/// those axes, metres; empty boxes ignored), as near as it can be with every corner of every
/// box inside [`FILL`] of both half fields of view of a `width` × `height` image. Its near
/// plane is a hundredth of the distance (at most [`DEFAULT_NEAR_M`]).
pub fn frame_boxes(
    boxes: &[(Vec3, Vec3)],
    axes: ViewAxes,
    fov_y_rad: f32,
    width: u32,
    height: u32,
) -> Camera {
    let boxes = || boxes.iter().filter(|(lo, hi)| lo.cmple(*hi).all());
    let (lo, hi) = boxes().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), b| (lo.min(b.0), hi.max(b.1)),
    );
    let centre = if lo.cmple(hi).all() {
        0.5 * (lo + hi)
    } else {
        Vec3::ZERO
    };
    let aspect = width as f32 / height.max(1) as f32;
    let tan_y = (0.5 * fov_y_rad).tan() * FILL;
    let tan_x = tan_y * aspect;
    // A corner at (x, y, z) from the centre is inside when |x| ≤ tan_x (d + z) and
    // |y| ≤ tan_y (d + z), d the eye's distance from the centre; the eye stays outside every
    // box (beyond its farthest-reaching corner toward the eye, by a tenth of the box).
    let mut dist: f32 = 0.05;
    for (blo, bhi) in boxes() {
        for k in 0..8 {
            let corner = Vec3::new(
                if k & 1 == 0 { blo.x } else { bhi.x },
                if k & 2 == 0 { blo.y } else { bhi.y },
                if k & 4 == 0 { blo.z } else { bhi.z },
            ) - centre;
            dist = dist
                .max(corner.x.abs() / tan_x - corner.z)
                .max(corner.y.abs() / tan_y - corner.z)
                .max(-corner.z + 0.1 * (*bhi - *blo).length());
        }
    }
    let dist = if dist.is_finite() { dist } else { 1.0 };
    let target = axes.right * centre.x + axes.up * centre.y + axes.forward * centre.z;
    let back = -axes.forward;
    let mut cam = Camera::look_at(
        target + back * dist,
        target,
        ViewAxes::up_hint(back),
        fov_y_rad,
        width,
        height,
    );
    cam.near_m = (0.01 * dist).clamp(1e-4, DEFAULT_NEAR_M);
    cam
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_unknown_names_are_refused() {
        for f in Framing::ALL {
            assert_eq!(Framing::from_name(f.name()), Some(f));
        }
        assert_eq!(Framing::from_name("legs"), None);
        assert_eq!(Framing::default_for(true), Framing::Upper);
        assert_eq!(Framing::default_for(false), Framing::Head);
    }

    /// A tall box in the view's axes (a 1.8 m figure, 0.6 m wide, 0.4 m deep), with an empty
    /// box that must be ignored: its eight corners project inside the image, and the tighter axis (the height, in a landscape
    /// image) binds: the farthest corner from the centre line lies at `FILL` (90%) ± 0.5% of
    /// the half height, by the distance's construction.
    #[test]
    fn a_box_fills_the_image_and_stays_inside_it() {
        let (lo, hi) = (Vec3::new(-0.3, 0.0, -0.2), Vec3::new(0.3, 1.8, 0.2));
        let (w, h) = (640, 360);
        let axes = ViewAxes::looking_back_along(Vec3::new(0.5, 0.1, 1.0));
        let empty = (Vec3::ONE, Vec3::ZERO);
        let fov = std::f32::consts::FRAC_PI_6;
        let cam = frame_boxes(&[(lo, hi), empty], axes, fov, w, h);
        let mut reach_y: f32 = 0.0;
        for k in 0..8 {
            let c = Vec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            );
            let world = axes.right * c.x + axes.up * c.y + axes.forward * c.z;
            assert!((axes.coords(world) - c).length() < 1e-5);
            let q = cam.project(world).expect("in front");
            assert!(
                q.x > 0.0 && q.x < w as f32 && q.y > 0.0 && q.y < h as f32,
                "{q}"
            );
            reach_y = reach_y.max((q.y - 0.5 * h as f32).abs() / (0.5 * h as f32));
        }
        assert!((reach_y - FILL).abs() < 0.005, "{reach_y}");
    }
}
