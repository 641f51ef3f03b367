//! A point light so far from the hair that its rays are parallel within the light map's
//! precision is drawn as the directional light it is ([`far_point_lights_as_directional`]).
//!
//! Why: a point light's map is central (`map::projection`): it measures depth from the light.
//! At the Sun's 1.5e11 m, or 1e18 m, the hair's depth differences are below the 32-bit
//! resolution of that depth (1.5e11 m has a spacing of 16 km) and every sample falls outside
//! the map, so the hair lost all its shadows from that light; the inverse-square law overflows
//! past 1.8e19 m as well.
//!
//! The rule, [`FAR_LIGHT_REACH_RATIO`]: the hair lies within the reach R of the head's centre
//! (its longest strand plus the head's largest radius, `Hairstyle::reach_m`), so it is at most
//! 2R deep and 2R across. A ray from a point light at distance d reaching the hair at a lateral
//! offset y ≤ R from the axis leans by y/d from the parallel ray, and over the hair's depth it
//! drifts across by at most 2R·R/d. The map's cells are at least its span over its cells per
//! axis, 2R / 1024 at the finest map (`--map-res` 1024). The drift stays under half a cell,
//! R / 1024, when 2R²/d ≤ R/1024, that is d ≥ 2048 R. The irradiance then varies across the
//! hair by (1 ± R/d)⁻², within 0.1%, and the directional light takes I/d² at the head's centre.

use crate::light::Light;
use glam::Vec3;

/// A point light at least this many times the hair's reach from the head's centre is drawn as
/// a directional light (module doc: parallel within half a cell of the finest map).
pub const FAR_LIGHT_REACH_RATIO: f64 = 2048.0;

/// A point light replaced by a directional one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FarLight {
    /// Its index in the scene's lights.
    pub index: usize,
    /// Its distance from the head's centre, metres.
    pub distance_m: f64,
    /// The directional light now in its place.
    pub light: Light,
}

/// Replaces each point light of `lights` at least [`FAR_LIGHT_REACH_RATIO`] × `reach_m` from
/// `head_m` (world metres) by a directional light travelling from it to `head_m`, of
/// irradiance I/d² there (computed in f64: d² overflows f32 past 1.8e19 m); returns the lights
/// replaced, in order. A directional light, or a point light nearer, is left as it is, so a
/// second call changes nothing.
pub fn far_point_lights_as_directional(
    lights: &mut [Light],
    head_m: Vec3,
    reach_m: f32,
) -> Vec<FarLight> {
    let mut replaced = Vec::new();
    for (index, light) in lights.iter_mut().enumerate() {
        let Light::Point {
            position_m,
            intensity,
        } = *light
        else {
            continue;
        };
        let travel = head_m.as_dvec3() - position_m.as_dvec3();
        let distance_m = travel.length();
        if distance_m.is_nan() || distance_m < FAR_LIGHT_REACH_RATIO * f64::from(reach_m.max(0.0)) {
            continue;
        }
        let irradiance = (intensity.as_dvec3() / (distance_m * distance_m)).as_vec3();
        let direction = (travel / distance_m).as_vec3();
        // Both are finite: the direction is a unit vector and the irradiance at most I.
        let Ok(directional) = Light::directional(direction, irradiance) else {
            continue;
        };
        *light = directional;
        replaced.push(FarLight {
            index,
            distance_m,
            light: directional,
        });
    }
    replaced
}

/// What [`far_point_lights_as_directional`] did, for stderr: one sentence a light.
pub fn describe(far: &FarLight, reach_m: f32) -> String {
    let (travel, irradiance) = match far.light {
        Light::Directional { travel, irradiance } => (travel.get(), irradiance),
        Light::Point { .. } => (Vec3::ZERO, Vec3::ZERO),
    };
    format!(
        "lights[{}] is a point light {:.3e} m from the head, at least {} × the hair's reach \
         ({reach_m:.2} m): its rays are parallel within the light map's precision, so it is \
         drawn as a directional light travelling [{:.3}, {:.3}, {:.3}] with irradiance I/d² = \
         [{:.3e}, {:.3e}, {:.3e}]",
        far.index,
        far.distance_m,
        FAR_LIGHT_REACH_RATIO,
        travel.x,
        travel.y,
        travel.z,
        irradiance.x,
        irradiance.y,
        irradiance.z
    )
}

#[cfg(test)]
mod tests;
