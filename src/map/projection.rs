//! How world points become map coordinates: the light frame (X along the light, Y and Z across
//! it) and, for a point light, the central projection that makes its rays parallel
//! (Bertails 2005 §6), so the fill, the sweep and the lookups work unchanged for both lights.
//!
//! Parallel light: m = (L·p, Y·p, Z·p). Point light at o with axis X: q = frame(p − o), then
//! m = (q.x, q.y·s, q.z·s) with s = ref / q.x, the central projection onto the plane at the
//! reference depth. Every ray of the light is then a line of constant (m.y, m.z).
//! [`MapLight`] is what the map knows of a light, and chooses the reference depth.

use glam::Vec3;
use rayon::prelude::*;

/// Orthonormal light frame: `x` is the direction the light travels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightFrame {
    pub x: Vec3,
    pub y: Vec3,
    pub z: Vec3,
}

impl LightFrame {
    /// The frame for light travelling along `l` (normalised here; a zero vector falls back to
    /// light travelling down, −Y).
    pub fn new(l: Vec3) -> Self {
        let x = l.normalize_or(Vec3::NEG_Y);
        let (y, z) = x.any_orthonormal_pair();
        Self { x, y, z }
    }

    /// World point -> map coordinates in metres.
    #[inline]
    pub fn to_map(&self, p: Vec3) -> Vec3 {
        Vec3::new(self.x.dot(p), self.y.dot(p), self.z.dot(p))
    }

    /// Map coordinates in metres -> world point.
    #[inline]
    pub fn to_world(&self, m: Vec3) -> Vec3 {
        self.x * m.x + self.y * m.y + self.z * m.z
    }
}

/// Closest depth along a point light's axis at which the map places anything, metres: nearer
/// points (and those behind the light) are not in the map (skipped when filling, unshadowed
/// when read).
pub const CENTRAL_MIN_DEPTH_M: f32 = 1e-4;

/// How world points become map coordinates (metres): X along the light's rays, Y and Z across
/// them, so that every ray of the light is a line of constant (Y, Z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// A directional light: parallel rays along `frame.x`; map coordinates are the frame's.
    Parallel { frame: LightFrame },
    /// A point light at `origin` (Bertails 2005 §6: a light-oriented map for a point source
    /// is angular). Depth is the distance along the axis `frame.x` (from the light toward the
    /// hair); across the axis a point's offset is scaled by `ref_depth_m / depth`, its
    /// central projection onto the plane at `ref_depth_m`. Rays from the light are then lines
    /// of constant (Y, Z), and the whole map (fill, sweep, lookup) works unchanged. A strand
    /// piece keeps its crossing count: its length across the rays and its fibres' width both
    /// shrink by that scale while a column stands for a cone whose cross-section grows with
    /// depth² (`build/fill.rs`).
    Central {
        frame: LightFrame,
        origin: Vec3,
        ref_depth_m: f32,
    },
}

impl Projection {
    /// The light frame (its X is the light's direction, or a point light's axis).
    #[inline]
    pub fn frame(&self) -> LightFrame {
        match *self {
            Projection::Parallel { frame } | Projection::Central { frame, .. } => frame,
        }
    }

    /// Map coordinates of world point `p`, metres (non-finite for a point not in front of a
    /// point light).
    #[inline]
    pub fn point(&self, p: Vec3) -> Vec3 {
        match *self {
            Projection::Parallel { frame } => frame.to_map(p),
            Projection::Central { .. } => match self.central(p) {
                Some((q, s)) => Vec3::new(q.x, q.y * s, q.z * s),
                None => Vec3::NAN,
            },
        }
    }

    /// For a point light: `p` in the light's frame relative to the light, and the lateral
    /// scale ref/depth there; `None` for parallel light or a point not in front of the light.
    #[inline]
    fn central(&self, p: Vec3) -> Option<(Vec3, f32)> {
        match *self {
            Projection::Parallel { .. } => None,
            Projection::Central {
                frame,
                origin,
                ref_depth_m,
            } => {
                let q = frame.to_map(p - origin);
                (q.x > CENTRAL_MIN_DEPTH_M).then(|| (q, ref_depth_m / q.x))
            }
        }
    }

    /// World point of map coordinates `m` (the inverse of [`Projection::point`]).
    pub fn to_world(&self, m: Vec3) -> Vec3 {
        match *self {
            Projection::Parallel { frame } => frame.to_world(m),
            Projection::Central {
                frame,
                origin,
                ref_depth_m,
            } => {
                let s = m.x / ref_depth_m;
                origin + frame.to_world(Vec3::new(m.x, m.y * s, m.z * s))
            }
        }
    }

    /// Unit direction from world point `p` toward the light.
    #[inline]
    pub fn toward_light(&self, p: Vec3) -> Vec3 {
        match *self {
            Projection::Parallel { frame } => -frame.x,
            Projection::Central { frame, origin, .. } => (origin - p).normalize_or(-frame.x),
        }
    }

    /// A point light's reference depth (lateral lengths at depth x are scaled by ref/x), or
    /// `None` for parallel light.
    #[inline]
    pub fn central_ref_depth_m(&self) -> Option<f32> {
        match *self {
            Projection::Parallel { .. } => None,
            Projection::Central { ref_depth_m, .. } => Some(ref_depth_m),
        }
    }

    /// The point of a fibre's surface nearest the light, in map coordinates: map point `m`
    /// on the fibre's axis moved by the fibre's radius `radius_m` along the part of the
    /// direction toward the light that is across the fibre, whose tangent is the chord from
    /// map point `prev_m` to `next_m`. The path tracer lights a fibre's surface, not its
    /// axis: a ray from the axis also meets the fibres touching the lit side, which the lit
    /// side sees past (ACCURACY.md §2, "Converged strands"). For a point light taken in world
    /// space, so its direction and lateral scale are exact; for parallel light in the
    /// (orthonormal) map frame. Light along the fibre has no lit side, and a point the
    /// projection cannot take stays at `m`.
    pub fn lit_side(&self, m: Vec3, prev_m: Vec3, next_m: Vec3, radius_m: f32) -> Vec3 {
        if let Projection::Parallel { .. } = self {
            // The frame is orthonormal: the same geometry in map coordinates, the light
            // toward −X, without the trip through world space.
            let t = (next_m - prev_m).normalize_or_zero();
            let across = (Vec3::NEG_X + t * t.x).normalize_or_zero();
            let q = m + across * radius_m;
            return if q.is_finite() { q } else { m };
        }
        let p = self.to_world(m);
        let t = (self.to_world(next_m) - self.to_world(prev_m)).normalize_or_zero();
        let l = self.toward_light(p);
        let across = (l - t * t.dot(l)).normalize_or_zero();
        if across == Vec3::ZERO {
            return m;
        }
        let q = self.point(p + across * radius_m);
        if q.is_finite() { q } else { m }
    }

    /// A strand of unit tangent `u` at world point `p`, in map coordinates: the image of `u`
    /// (the map displacement per metre along the strand), the share of a metre of strand that
    /// crosses the light's rays (sin ψ for parallel light; the lateral length of the image
    /// times the width scale for a point light: its fibres' width shrinks with the lateral
    /// scale too), and the factor of its fibre volume per map volume (1, or the lateral
    /// scale²).
    #[inline]
    pub fn strand(&self, p: Vec3, u: Vec3) -> (Vec3, f32, f32) {
        match *self {
            Projection::Parallel { frame } => {
                let cos_psi = u.dot(frame.x).clamp(-1.0, 1.0);
                let sin_psi = (1.0 - cos_psi * cos_psi).max(0.0).sqrt();
                (frame.to_map(u), sin_psi, 1.0)
            }
            Projection::Central { frame, .. } => {
                let Some((q, s)) = self.central(p) else {
                    return (Vec3::NAN, 0.0, 0.0);
                };
                let v = frame.to_map(u);
                // d(s·y)/dt = s·(v.y − (y/x)·v.x): the derivative of the central projection.
                let img = Vec3::new(
                    v.x,
                    s * (v.y - q.y / q.x * v.x),
                    s * (v.z - q.z / q.x * v.x),
                );
                let lateral = (img.y * img.y + img.z * img.z).sqrt();
                (img, lateral * s, s * s)
            }
        }
    }
}

/// What the map needs to know of a light: where its rays go.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MapLight {
    /// Parallel rays travelling along this direction (need not be normalised).
    Directional(Vec3),
    /// Rays from `position_m`; the map's axis points from it toward `aim_m` (the middle of
    /// the hair: the head's centre).
    Point { position_m: Vec3, aim_m: Vec3 },
}

impl From<Vec3> for MapLight {
    fn from(travel: Vec3) -> Self {
        MapLight::Directional(travel)
    }
}

impl MapLight {
    /// The map geometry of `light`, a point light aimed at `aim_m`.
    pub fn of(light: &crate::light::Light, aim_m: Vec3) -> Self {
        match *light {
            crate::light::Light::Directional { travel, .. } => MapLight::Directional(travel.get()),
            crate::light::Light::Point { position_m, .. } => MapLight::Point { position_m, aim_m },
        }
    }

    /// The projection for hair at `positions`: for a point light, the reference plane is at
    /// the nearest hair along the axis, so no hair is magnified across the light (the modulo
    /// map cannot overflow for it) and the nearest hair keeps the map's full resolution. The
    /// plane is at least a tenth of the way to the aim point (a light inside the hair, which
    /// scene files refuse, would otherwise put it at the light). The minimum is exact, so the
    /// projection does not depend on the thread count.
    pub fn projection(&self, positions: &[Vec3]) -> Projection {
        match *self {
            MapLight::Directional(travel) => Projection::Parallel {
                frame: LightFrame::new(travel),
            },
            MapLight::Point { position_m, aim_m } => {
                let axis = aim_m - position_m;
                let dist = axis.length();
                let frame = LightFrame::new(if dist > 0.0 { axis } else { Vec3::NEG_Y });
                let nearest = positions
                    .par_iter()
                    .with_min_len(4096)
                    .map(|p| frame.x.dot(*p - position_m))
                    .filter(|d| d.is_finite())
                    .reduce(|| f32::INFINITY, f32::min);
                let ref_depth_m = nearest.min(dist).max(0.1 * dist).max(CENTRAL_MIN_DEPTH_M);
                Projection::Central {
                    frame,
                    origin: position_m,
                    ref_depth_m,
                }
            }
        }
    }
}
