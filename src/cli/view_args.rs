//! Scene flags: shortcuts for fields of the scene file (`--scene`, `wisp::scene::file`), applied
//! on top of it, plus the narrowest hair line. Flattened into `SceneArgs`, so `render`, `play`,
//! `bench` and `export` all take them. Degrees stop here.

use super::{AppError, parse_finite_f32, parse_point, parse_positive_f32};
use glam::Vec3;
use wisp::engine::EngineConfig;
use wisp::raster::LineWidth;
use wisp::scene::SceneFile;
use wisp::scene::file::{CameraJson, LightJson};

#[derive(clap::Args, Debug, Clone)]
pub struct ViewArgs {
    /// Fixed camera eye X,Y,Z in world metres (needs --camera-target; scene `camera.position_m`).
    /// Default: frame the hair from three-quarters front and follow the head.
    #[arg(long, value_parser = parse_point, allow_hyphen_values = true, requires = "camera_target")]
    pub camera_eye: Option<Vec3>,
    /// Fixed camera target X,Y,Z in world metres (needs --camera-eye; scene `camera.target_m`).
    #[arg(long, value_parser = parse_point, allow_hyphen_values = true, requires = "camera_eye")]
    pub camera_target: Option<Vec3>,
    /// Fixed camera up hint X,Y,Z (default 0,1,0; needs --camera-eye; scene `camera.up`).
    #[arg(long, value_parser = parse_point, allow_hyphen_values = true, requires = "camera_eye")]
    pub camera_up: Option<Vec3>,
    /// Vertical field of view of the fixed camera in degrees, in (0, 180) (default 30; needs
    /// --camera-eye; scene `camera.fov_y_deg`).
    #[arg(long, value_parser = parse_positive_f32, requires = "camera_eye")]
    pub fov_deg: Option<f32>,
    /// Draw hair only: no head, no body (scene `draw_solids: false`).
    #[arg(long)]
    pub no_solids: bool,
    /// Irradiance of the first light (a directional one) on a surface facing it: E or R,G,B,
    /// linear, >= 0 (default 6; scene `lights[0].irradiance`).
    #[arg(long, value_parser = parse_rgb)]
    pub irradiance: Option<Vec3>,
    /// Ambient (sky) radiance: L or R,G,B, linear, >= 0 (default 0.035,0.04,0.05; scene
    /// `ambient`).
    #[arg(long, value_parser = parse_rgb)]
    pub ambient: Option<Vec3>,
    /// Exposure in stops: the image's radiance times 2^stops, in [-20, 20] (default 0; scene
    /// `exposure_stops`).
    #[arg(long, value_parser = parse_finite_f32, allow_hyphen_values = true)]
    pub exposure_stops: Option<f32>,
    /// Narrowest hair line in pixels (default 0.5); thinner strands are drawn this wide at an
    /// opacity that conserves their coverage.
    #[arg(long, value_parser = parse_positive_f32)]
    pub min_line_width_px: Option<f32>,
}

impl ViewArgs {
    /// Writes the flags into `scene` (each is a shortcut for one of its fields).
    pub fn apply_to_scene(&self, scene: &mut SceneFile) -> Result<(), AppError> {
        if let (Some(eye), Some(target)) = (self.camera_eye, self.camera_target) {
            scene.camera = CameraJson::Fixed {
                position_m: eye.to_array(),
                target_m: target.to_array(),
                up: self.camera_up.unwrap_or(Vec3::Y).to_array(),
                fov_y_deg: self.fov_deg.unwrap_or(30.0),
            };
        }
        if self.no_solids {
            scene.draw_solids = false;
        }
        if let Some(e) = self.irradiance {
            match scene.lights.first_mut() {
                Some(LightJson::Directional { irradiance, .. }) => *irradiance = e.to_array(),
                _ => {
                    return Err(AppError::input(anyhow::anyhow!(
                        "--irradiance sets the first light's irradiance, and the scene's first light is not a directional light"
                    )));
                }
            }
        }
        if let Some(a) = self.ambient {
            scene.ambient = a.to_array();
        }
        if let Some(x) = self.exposure_stops {
            scene.exposure_stops = x;
        }
        Ok(())
    }

    /// The flags that are not part of the scene.
    pub fn apply(&self, config: &mut EngineConfig) {
        if let Some(w) = self.min_line_width_px {
            config.raster.line.width = LineWidth::Projected { min_px: w };
        }
    }
}

/// `V` or `R,G,B`: finite numbers >= 0 (one number is grey).
pub fn parse_rgb(s: &str) -> Result<Vec3, String> {
    let parts: Vec<&str> = s.split(',').collect();
    let values = parts
        .iter()
        .map(|p| parse_finite_f32(p))
        .collect::<Result<Vec<f32>, String>>()?;
    let v = match values[..] {
        [g] => Vec3::splat(g),
        [r, g, b] => Vec3::new(r, g, b),
        _ => return Err(format!("expected one number or three R,G,B (got `{s}`)")),
    };
    if v.min_element() < 0.0 {
        return Err(format!("must be >= 0 (got `{s}`)"));
    }
    Ok(v)
}
