//! wisp fibre parameters mapped to Mitsuba 3's `hair` BSDF (Chiang et al. 2016), following
//! `../shared/reference/MAPPING.md` (checked there against the 3.9.1 source and by evaluating
//! the BSDF):
//!
//! | wisp | Mitsuba | mapping |
//! |---|---|---|
//! | `eta` | `int_ior`, `ext_ior` = 1 | 1:1 (Mitsuba's default `ext_ior` is 1.000277) |
//! | `sigma_a` per unit radius | `sigma_a` | 1:1: both use the Beer-Lambert chord 2 cos γt / cos θt |
//! | `beta_r_deg` (std of the R lobe in θh) | `longitudinal_roughness` b | the R lobe's std in θo is 2β_R; b solves 0.726b + 0.812b² + 3.7b²⁰ = 2β_R (radians) |
//! | `alpha_r_deg` | `scale_tilt` (degrees) | same value and sign |
//! | `azimuthal_roughness` ("chiang") | `azimuthal_roughness` | 1:1; Marschner 2003 has none, see [`MARSCHNER_AZIMUTHAL_ROUGHNESS`] |
//!
//! The scene's one light ([`reference_light`]) keeps its units: a directional light's
//! irradiance is the `directional` emitter's `irradiance`, and a point light's radiant
//! intensity I is the `point` emitter's `intensity`, which Mitsuba also turns into I / d² on a
//! surface facing it at distance d (its `point` emitter's direction sampling), as wisp does
//! ([`crate::light::Light::Point`]).
//!
//! The fibre is read as JSON (the hairstyle's `fiber` object) so that fields added by other
//! fibre models (`model`, `azimuthal_roughness`) are mapped when present.

// `!(a > b)` on purpose: unlike `a <= b` it is also true for NaN, so one test rejects both.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use serde::{Deserialize, Serialize};

use super::LightJson;
use crate::light::Light;

/// Azimuthal roughness given to Mitsuba for a Marschner 2003 fibre, which has none: 0.1 gives a
/// trimmed-logistic scale of 0.024 rad (1.4°), close to a smooth fibre; smaller values are
/// closer still but make the glints' fireflies much noisier (MAPPING.md).
pub const MARSCHNER_AZIMUTHAL_ROUGHNESS: f64 = 0.1;

/// The parameters of Mitsuba 3's `hair` BSDF.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MitsubaHair {
    /// Always `"hair"`.
    #[serde(rename = "type")]
    pub kind: String,
    pub int_ior: f64,
    pub ext_ior: f64,
    /// Absorption per unit fibre radius, linear RGB.
    pub sigma_a: [f64; 3],
    pub longitudinal_roughness: f64,
    pub azimuthal_roughness: f64,
    /// Cuticle tilt in degrees.
    pub scale_tilt: f64,
}

/// Chiang's longitudinal roughness b whose R lobe has standard deviation `std_theta_o_rad` in
/// θo (MAPPING.md, verified there against Mitsuba's lobes); inputs ≤ 0 or NaN give 0.
pub fn longitudinal_roughness_for_std(std_theta_o_rad: f64) -> f64 {
    crate::fiber::roughness_for_std(std_theta_o_rad)
}

/// The fibre model named in the fibre JSON (`"model"`), `"marschner"` when absent.
pub fn fiber_model(fiber: &serde_json::Value) -> String {
    fiber
        .get("model")
        .and_then(|m| m.as_str())
        .unwrap_or("marschner")
        .to_string()
}

/// Maps a fibre (the hairstyle's `fiber` JSON object, already validated by the hairstyle
/// loader) to Mitsuba's `hair` BSDF. Missing fields take wisp's defaults' meaning: a fibre
/// without `azimuthal_roughness` gets [`MARSCHNER_AZIMUTHAL_ROUGHNESS`], and so does any fibre
/// whose model is Marschner's.
pub fn mitsuba_hair(fiber: &serde_json::Value) -> MitsubaHair {
    let num = |k: &str, default: f64| fiber.get(k).and_then(|v| v.as_f64()).unwrap_or(default);
    let sigma = |c: usize| {
        fiber
            .get("sigma_a")
            .and_then(|s| s.get(c))
            .and_then(|v| v.as_f64())
            .unwrap_or(0.0)
    };
    let azimuthal = if fiber_model(fiber) == "marschner" {
        MARSCHNER_AZIMUTHAL_ROUGHNESS
    } else {
        num("azimuthal_roughness", MARSCHNER_AZIMUTHAL_ROUGHNESS)
    };
    MitsubaHair {
        kind: "hair".into(),
        int_ior: num("eta", 1.55),
        ext_ior: 1.0,
        sigma_a: [sigma(0), sigma(1), sigma(2)],
        longitudinal_roughness: longitudinal_roughness_for_std(
            2.0 * num("beta_r_deg", 7.5).to_radians(),
        ),
        azimuthal_roughness: azimuthal,
        scale_tilt: num("alpha_r_deg", 0.0),
    }
}

/// The one light a reference scene describes (tools/reference renders exactly that): a
/// directional or a point light, in wisp's units, or why `lights` is not such a scene.
pub fn reference_light(lights: &[Light]) -> Result<LightJson, String> {
    match lights {
        [Light::Directional { travel, irradiance }] => Ok(LightJson::Directional {
            direction: travel.get().to_array(),
            irradiance: irradiance.to_array(),
        }),
        [
            Light::Point {
                position_m,
                intensity,
            },
        ] => Ok(LightJson::Point {
            position_m: position_m.to_array(),
            intensity: intensity.to_array(),
        }),
        _ => Err(format!(
            "a reference scene has exactly one light (directional or point); this scene has {}",
            lights.len()
        )),
    }
}

#[cfg(test)]
mod tests;
