//! The scene file (`--scene FILE.json`): what a frame is looked at with and lit by, as JSON.
//!
//! Every field has a default, so `{}` is the engine's default scene, and `wisp render
//! --print-scene` writes the effective scene (defaults, file and flags merged) for a user to
//! start from. Units are in the names (`_m` metres, `_deg` degrees, `_stops` powers of two);
//! colours are linear RGB.
//!
//! ```json
//! {
//!   "image": { "width": 800, "height": 800 },
//!   "camera": { "type": "follow_head" },
//!   "lights": [
//!     { "type": "directional", "direction": [-0.75, -0.55, -0.35], "irradiance": [6, 6, 6] },
//!     { "type": "point", "position_m": [0.6, 1.9, 0.8], "intensity": [2, 1.8, 1.5] }
//!   ],
//!   "ambient": [0.035, 0.04, 0.05],
//!   "background": [0.012, 0.014, 0.018],
//!   "exposure_stops": 0,
//!   "draw_solids": true
//! }
//! ```
//!
//! - `camera`: `{"type": "follow_head", "framing": "upper"}`: the engine's own camera, from
//!   three-quarters front; `framing` (optional) is `"head"` (the settled hair, following the
//!   head), `"upper"` (head to hips) or `"full"` (the whole figure), the last two framed on the
//!   character's whole clip and still ([`Framing`]; absent: `upper` when a character's body is
//!   drawn, else `head`). Or `{"type": "fixed", "position_m": [x, y, z], "target_m": [x, y, z],
//!   "up": [0, 1, 0], "fov_y_deg": 30}` (`up` and `fov_y_deg` optional).
//! - `lights`: one or more (at most [`MAX_LIGHTS`]); each gets its own map. `directional`:
//!   `direction` the light travels (any non-zero vector, world, Y up) and `irradiance` on a
//!   surface facing it. `point`: `position_m` and radiant `intensity` (irradiance I/d² at
//!   distance d); it must lie outside the hair (checked against the hairstyle,
//!   [`check_point_lights_outside`]).
//! - `exposure_stops`: the image's radiance is scaled by 2^stops (lights, ambient and
//!   background alike), in [−20, 20].
//! - `draw_solids`: draw the head and body (or the character's mesh); without them, hair alone.
//! - `quality` (optional): `"preview"`, `"final"` or `"reference"` ([`Quality`]); absent, the
//!   command's default (`play` previews, `render` and `simulate` make final frames). The
//!   `--quality` flag overrides it, and each pass's own flags override the level.
//!
//! Parsing is strict ([`crate::input::json::from_str`]) and [`SceneFile::validate`] checks every
//! rule, naming the field (`lights[1].intensity`) and the rule.

use super::camera::{CameraError, CameraSetup, CameraSpec};
use super::framing::Framing;
use super::shown;
use crate::light::{Light, LightError};
use crate::quality::Quality;
use glam::Vec3;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Most lights a scene may have (each one is a map built every frame).
pub const MAX_LIGHTS: usize = 16;
/// Image sides wisp renders, pixels.
pub const MIN_IMAGE_SIDE: u32 = 16;
pub const MAX_IMAGE_SIDE: u32 = 8192;

/// A scene file as written.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SceneFile {
    pub image: ImageSize,
    pub camera: CameraJson,
    pub lights: Vec<LightJson>,
    pub ambient: [f32; 3],
    pub background: [f32; 3],
    pub exposure_stops: f32,
    pub draw_solids: bool,
    /// The quality level the scene asks for (absent: the command's own default).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub quality: Option<Quality>,
}

/// Image size in pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImageSize {
    pub width: u32,
    pub height: u32,
}

/// The camera as written.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum CameraJson {
    /// The engine's own camera (the default): `framing` `head` (the settled hair, following
    /// the head), `upper` or `full` ([`Framing`]); absent, the motion's default
    /// ([`Framing::default_for`]).
    FollowHead {
        #[serde(default, skip_serializing_if = "Option::is_none")]
        framing: Option<Framing>,
    },
    /// Fixed in the world.
    Fixed {
        position_m: [f32; 3],
        target_m: [f32; 3],
        #[serde(default = "default_up")]
        up: [f32; 3],
        #[serde(default = "default_fov_deg")]
        fov_y_deg: f32,
    },
}

impl Default for CameraJson {
    fn default() -> Self {
        CameraJson::FollowHead { framing: None }
    }
}

fn default_up() -> [f32; 3] {
    [0.0, 1.0, 0.0]
}
fn default_fov_deg() -> f32 {
    30.0
}

/// A light as written.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum LightJson {
    Directional {
        direction: [f32; 3],
        irradiance: [f32; 3],
    },
    Point {
        position_m: [f32; 3],
        intensity: [f32; 3],
    },
}

impl Default for SceneFile {
    /// The engine's default scene (the same frame as `wisp render` with no scene flags).
    fn default() -> Self {
        Self {
            image: ImageSize {
                width: 800,
                height: 800,
            },
            camera: CameraJson::default(),
            lights: vec![LightJson::Directional {
                direction: crate::light::DEFAULT_LIGHT_TRAVEL,
                irradiance: [6.0; 3],
            }],
            ambient: [0.035, 0.04, 0.05],
            background: [0.012, 0.014, 0.018],
            exposure_stops: 0.0,
            draw_solids: true,
            quality: None,
        }
    }
}

impl Default for ImageSize {
    fn default() -> Self {
        SceneFile::default().image
    }
}

/// Why a scene file was refused.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SceneError {
    #[error("{file}: {message}")]
    Io { file: String, message: String },
    #[error("{file}: {field}: {message}")]
    Parse {
        file: String,
        field: String,
        message: String,
    },
    #[error("{file}: {field}: {rule}")]
    Invalid {
        file: String,
        field: String,
        rule: String,
    },
}

/// A validated scene: what the engine takes.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    pub width: u32,
    pub height: u32,
    pub camera: CameraSetup,
    /// Lights with the exposure applied.
    pub lights: Vec<Light>,
    /// Ambient radiance and background, exposure applied, linear RGB.
    pub ambient: Vec3,
    pub background: Vec3,
    pub draw_solids: bool,
}

impl Scene {
    /// Turns every light by `rotation` about `pivot` ([`Light::turned`]).
    pub fn turn_lights(&mut self, rotation: glam::Quat, pivot: Vec3) {
        for l in &mut self.lights {
            *l = l.turned(rotation, pivot);
        }
    }
}

impl Default for Scene {
    /// The engine's default scene: [`SceneFile::default`] validated (800 × 800, the camera
    /// following the head, one directional light of irradiance 6, the default ambient and
    /// background, the solids drawn).
    fn default() -> Self {
        Scene {
            width: 800,
            height: 800,
            camera: CameraSetup::default(),
            lights: vec![crate::light::default_light()],
            ambient: Vec3::new(0.035, 0.04, 0.05),
            background: Vec3::new(0.012, 0.014, 0.018),
            draw_solids: true,
        }
    }
}

fn color(field: String, c: [f32; 3]) -> Result<Vec3, (String, String)> {
    let v = Vec3::from(c);
    if v.is_finite() && v.min_element() >= 0.0 {
        Ok(v)
    } else {
        Err((
            field,
            format!("must be three finite numbers >= 0 (got {v})"),
        ))
    }
}

/// The scene's exposure, `exposure_stops` (checked to lie in [−20, 20]): what multiplies every
/// radiance of the scene by 2^stops.
#[derive(Clone, Copy)]
struct Exposure(f32);

impl Exposure {
    /// The colour `c` of `field` checked ([`color`]) and exposed, refused when the product
    /// overflows a 32-bit float: ambient 3e38 at 20 stops would reach the pixels as infinity
    /// (black after compositing). Finite products saturate in the shading instead
    /// ([`crate::color::RADIANCE_MAX`]).
    fn apply(self, field: String, c: [f32; 3]) -> Result<Vec3, (String, String)> {
        let v = color(field.clone(), c)?;
        let exposed = v * self.0.exp2();
        if exposed.is_finite() {
            return Ok(exposed);
        }
        Err((
            field.clone(),
            format!(
                "{} × 2^{} (exposure_stops) = {}: the exposed value must be finite (at most \
                 3.4e38, the largest 32-bit float); lower {field} or exposure_stops",
                shown(v),
                self.0,
                shown(exposed)
            ),
        ))
    }
}

/// Largest scene file read, bytes (a scene is a few hundred bytes; this only stops a wrong file
/// from being read whole).
pub const MAX_SCENE_FILE_BYTES: u64 = 1 << 20;

impl SceneFile {
    /// Reads, parses and validates a scene file.
    pub fn load(path: &std::path::Path) -> Result<(SceneFile, Scene), SceneError> {
        let file = path.display().to_string();
        let bytes =
            crate::input::read_capped(path, MAX_SCENE_FILE_BYTES, "a scene file").map_err(|e| {
                SceneError::Io {
                    file: file.clone(),
                    message: e.to_string(),
                }
            })?;
        let text = crate::input::json::decode_text(&bytes).map_err(|e| SceneError::Parse {
            file: file.clone(),
            field: e.field,
            message: e.message,
        })?;
        Self::from_json(text, &file)
    }

    /// Parses and validates JSON text; `file` names the source in errors.
    pub fn from_json(text: &str, file: &str) -> Result<(SceneFile, Scene), SceneError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let parsed: SceneFile =
            crate::input::json::from_str(text).map_err(|e| SceneError::Parse {
                file: file.to_string(),
                field: e.field,
                message: e.message,
            })?;
        let scene = parsed.validate(file)?;
        Ok((parsed, scene))
    }

    /// The file as pretty JSON (what `--print-scene` writes; reading it back gives this file).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
    }

    /// Checks every rule; the error names `file`, the field and the rule.
    pub fn validate(&self, file: &str) -> Result<Scene, SceneError> {
        self.check().map_err(|(field, rule)| SceneError::Invalid {
            file: file.to_string(),
            field,
            rule,
        })
    }

    /// Every rule, in the file's order (image, camera, exposure, lights, ambient, background);
    /// the error is (field, rule).
    fn check(&self) -> Result<Scene, (String, String)> {
        self.check_image()?;
        let camera = self.camera_setup()?;
        if !(self.exposure_stops.is_finite() && self.exposure_stops.abs() <= 20.0) {
            return Err((
                "exposure_stops".into(),
                format!("must be in [-20, 20] (got {})", self.exposure_stops),
            ));
        }
        let exposure = Exposure(self.exposure_stops);
        let lights = self.lights_exposed(exposure)?;
        let ambient = exposure.apply("ambient".into(), self.ambient)?;
        let background = exposure.apply("background".into(), self.background)?;
        Ok(Scene {
            width: self.image.width,
            height: self.image.height,
            camera,
            lights,
            ambient,
            background,
            draw_solids: self.draw_solids,
        })
    }

    /// Each image side in [`MIN_IMAGE_SIDE`]..=[`MAX_IMAGE_SIDE`] pixels.
    fn check_image(&self) -> Result<(), (String, String)> {
        for (field, side) in [
            ("image.width", self.image.width),
            ("image.height", self.image.height),
        ] {
            if !(MIN_IMAGE_SIDE..=MAX_IMAGE_SIDE).contains(&side) {
                return Err((
                    field.into(),
                    format!("must be in {MIN_IMAGE_SIDE}..={MAX_IMAGE_SIDE} pixels (got {side})"),
                ));
            }
        }
        Ok(())
    }

    /// The camera: head-following, or a fixed one checked by [`CameraSpec::new`] (its error
    /// is reported at the field it names).
    fn camera_setup(&self) -> Result<CameraSetup, (String, String)> {
        Ok(match self.camera {
            CameraJson::FollowHead { framing } => CameraSetup::Framed(framing),
            CameraJson::Fixed {
                position_m,
                target_m,
                up,
                fov_y_deg,
            } => {
                let spec = CameraSpec::new(
                    Vec3::from(position_m),
                    Vec3::from(target_m),
                    Vec3::from(up),
                    fov_y_deg.to_radians(),
                )
                .map_err(|e| {
                    let field = match e {
                        CameraError::NonFinite { field: "eye", .. }
                        | CameraError::TooFar { field: "eye", .. }
                        | CameraError::EyeAtTarget(_) => "camera.position_m",
                        CameraError::NonFinite {
                            field: "target", ..
                        }
                        | CameraError::TooFar { .. } => "camera.target_m",
                        CameraError::NonFinite { .. } | CameraError::UpAlongView { .. } => {
                            "camera.up"
                        }
                        CameraError::FieldOfView { .. } => "camera.fov_y_deg",
                    };
                    (field.to_string(), e.to_string())
                })?;
                CameraSetup::Fixed(spec)
            }
        })
    }

    /// The lights (one to [`MAX_LIGHTS`]), each checked and exposed.
    fn lights_exposed(&self, exposure: Exposure) -> Result<Vec<Light>, (String, String)> {
        if self.lights.is_empty() {
            return Err((
                "lights".into(),
                "needs at least one light (a directional or a point light)".into(),
            ));
        }
        if self.lights.len() > MAX_LIGHTS {
            return Err((
                "lights".into(),
                format!(
                    "at most {MAX_LIGHTS} lights (got {}): each light is a map built every frame",
                    self.lights.len()
                ),
            ));
        }
        self.lights
            .iter()
            .enumerate()
            .map(|(i, l)| light_of(i, l, exposure))
            .collect()
    }
}

/// Light `i` of the file, checked ([`Light::directional`], [`Light::point`]; an error names
/// `lights[i]`'s field) and exposed.
fn light_of(i: usize, l: &LightJson, exposure: Exposure) -> Result<Light, (String, String)> {
    let field = |name: &str| format!("lights[{i}].{name}");
    Ok(match *l {
        LightJson::Directional {
            direction,
            irradiance,
        } => {
            let e = exposure.apply(field("irradiance"), irradiance)?;
            Light::directional(Vec3::from(direction), e).map_err(|err| {
                let name = match err {
                    LightError::Direction(_) => "direction",
                    _ => "irradiance",
                };
                (field(name), err.to_string())
            })?
        }
        LightJson::Point {
            position_m,
            intensity,
        } => {
            let i_rgb = exposure.apply(field("intensity"), intensity)?;
            Light::point(Vec3::from(position_m), i_rgb).map_err(|err| {
                let name = match err {
                    LightError::Position(_) => "position_m",
                    _ => "intensity",
                };
                (field(name), err.to_string())
            })?
        }
    })
}

/// Refuses a point light inside the hair: within `reach_m` (the hair's reach: its longest
/// strand plus the head's largest radius) of the head centre `head_m` (world metres, first
/// pose). The map of a point light looks from the light at the hair; from inside it, hair lies
/// on every side and the map cannot hold it. The error is (field, rule).
pub fn check_point_lights_outside(
    lights: &[Light],
    head_m: Vec3,
    reach_m: f32,
) -> Result<(), (String, String)> {
    for (i, l) in lights.iter().enumerate() {
        if let Light::Point { position_m, .. } = l {
            let d = (*position_m - head_m).length();
            // Also refuses a NaN distance.
            if d.is_nan() || d <= reach_m {
                return Err((
                    format!("lights[{i}].position_m"),
                    format!(
                        "the point light at {position_m} m is {d:.3} m from the head centre \
                         {head_m}, inside the hair, which reaches {reach_m:.3} m from it; put it \
                         farther away"
                    ),
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
