//! Lights, validated once: every later stage (map, shading, skin) takes a [`Light`] and never
//! normalises or checks a direction again.
//!
//! - [`Light::Directional`]: parallel light travelling along a unit direction, with the
//!   irradiance E (linear RGB, W/m² in the engine's relative units: 1 = white) it gives a
//!   surface facing it.
//! - [`Light::Point`]: light from a point, with radiant intensity I (linear RGB, per
//!   steradian): a surface facing it at distance d receives E = I / d² (the inverse-square
//!   law). Its shadows come from a map in the light's own angular frame (`map`, Bertails 2005
//!   §6).

use glam::{Quat, Vec3};
use thiserror::Error;

/// Why a light is not valid.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum LightError {
    #[error("direction {0} is not a finite, non-zero vector")]
    Direction(Vec3),
    #[error("{what} {value} must be three finite numbers >= 0")]
    Color { what: &'static str, value: Vec3 },
    #[error("position {0} is not finite")]
    Position(Vec3),
}

/// A unit vector, normalised once (from any finite, non-zero vector).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitDir(Vec3);

impl UnitDir {
    /// `v` normalised; an error for a zero, non-finite or overflowing vector. The vector is
    /// scaled by its largest component first, so 1e30-long vectors normalise too.
    pub fn new(v: Vec3) -> Result<Self, LightError> {
        let big = v.abs().max_element();
        if !(v.is_finite() && big > 0.0) {
            return Err(LightError::Direction(v));
        }
        let u = (v / big).normalize_or_zero();
        if u == Vec3::ZERO || !u.is_finite() {
            return Err(LightError::Direction(v));
        }
        Ok(Self(u))
    }

    /// The unit vector.
    #[inline]
    pub fn get(self) -> Vec3 {
        self.0
    }
}

/// One light of a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// Parallel light travelling along `travel`; `irradiance` on a surface facing it.
    Directional { travel: UnitDir, irradiance: Vec3 },
    /// Light from `position_m` (world metres) with radiant intensity `intensity` (E = I/d²).
    Point { position_m: Vec3, intensity: Vec3 },
}

/// Closest distance at which a point light's inverse-square law is evaluated, metres: keeps
/// the irradiance finite at the light itself (a scene with a light inside the hair is refused
/// before it gets here; this only guards the arithmetic).
pub const POINT_LIGHT_MIN_DISTANCE_M: f32 = 1e-3;

fn color(what: &'static str, value: Vec3) -> Result<Vec3, LightError> {
    if value.is_finite() && value.min_element() >= 0.0 {
        Ok(value)
    } else {
        Err(LightError::Color { what, value })
    }
}

impl Light {
    /// A directional light travelling along `travel` (any finite non-zero vector).
    pub fn directional(travel: Vec3, irradiance: Vec3) -> Result<Self, LightError> {
        Ok(Self::Directional {
            travel: UnitDir::new(travel)?,
            irradiance: color("irradiance", irradiance)?,
        })
    }

    /// A point light at `position_m` with radiant intensity `intensity`.
    pub fn point(position_m: Vec3, intensity: Vec3) -> Result<Self, LightError> {
        if !position_m.is_finite() {
            return Err(LightError::Position(position_m));
        }
        Ok(Self::Point {
            position_m,
            intensity: color("intensity", intensity)?,
        })
    }

    /// At world point `p`: the unit direction toward the light (ωi) and the irradiance on a
    /// surface facing it (a point light's within [`crate::color::RADIANCE_MAX`]).
    #[inline]
    pub fn toward_and_irradiance(&self, p: Vec3) -> (Vec3, Vec3) {
        match *self {
            Light::Directional { travel, irradiance } => (-travel.get(), irradiance),
            Light::Point {
                position_m,
                intensity,
            } => {
                let d = position_m - p;
                let d2 = d
                    .length_squared()
                    .max(POINT_LIGHT_MIN_DISTANCE_M * POINT_LIGHT_MIN_DISTANCE_M);
                // I/d² overflows for a bright light near a point: saturate, not infinity
                // (which a fibre's zero scattering would turn into NaN).
                (
                    d * d2.sqrt().recip(),
                    crate::color::saturate_radiance(intensity / d2),
                )
            }
        }
    }

    /// The light turned by `rotation` about `pivot` (a directional light turns its direction,
    /// a point light moves around the pivot). Keys in the window use it.
    pub fn turned(&self, rotation: Quat, pivot: Vec3) -> Self {
        match *self {
            Light::Directional { travel, irradiance } => Light::Directional {
                travel: UnitDir::new(rotation * travel.get()).unwrap_or(travel),
                irradiance,
            },
            Light::Point {
                position_m,
                intensity,
            } => Light::Point {
                position_m: pivot + rotation * (position_m - pivot),
                intensity,
            },
        }
    }

    /// The direction a directional light travels, or `None` for a point light.
    pub fn travel(&self) -> Option<Vec3> {
        match self {
            Light::Directional { travel, .. } => Some(travel.get()),
            Light::Point { .. } => None,
        }
    }
}

/// The direction the engine's default light travels, as written in a scene file: from above,
/// front-left of the face.
pub const DEFAULT_LIGHT_TRAVEL: [f32; 3] = [-0.75, -0.55, -0.35];

/// The engine's default light: travelling along [`DEFAULT_LIGHT_TRAVEL`], irradiance 6 (made
/// as a scene file's light is, so both give the same bits).
pub fn default_light() -> Light {
    let v = Vec3::from(DEFAULT_LIGHT_TRAVEL);
    Light::Directional {
        travel: UnitDir::new(v).unwrap_or(UnitDir(Vec3::NEG_Y)),
        irradiance: Vec3::splat(6.0),
    }
}

#[cfg(test)]
mod tests;
