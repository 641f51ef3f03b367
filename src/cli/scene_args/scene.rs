//! The scene's flags: a scene file (`--scene`, `wisp::scene::file`) and shortcuts for its
//! fields written over it (image size, camera, first light, ambient, exposure, solids). The
//! result is what `--print-scene` prints, validated into the run's [`Scene`]. Degrees stop
//! here.

use crate::cli::{
    AppError, parse_direction, parse_finite_f32, parse_point, parse_positive_f32, parse_rgb,
};
use glam::Vec3;
use std::path::PathBuf;
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;
use wisp::quality::Quality;
use wisp::scene::far_light::{self, far_point_lights_as_directional};
use wisp::scene::file::{CameraJson, LightJson, SceneError};
use wisp::scene::{Framing, Scene, SceneFile};

#[derive(clap::Args, Debug, Clone)]
#[command(next_help_heading = "Scene")]
pub struct SceneFileArgs {
    /// Scene file (camera, lights, image, …); the flags override its fields
    #[arg(long, value_name = "FILE.json")]
    pub scene: Option<PathBuf>,
    /// The engine's camera: head (close, following the head), upper (head to hips) or full
    /// (the whole figure), the last two still [default: upper with a character's body drawn,
    /// else head]
    #[arg(long, value_name = "FRAMING", value_parser = crate::cli::parse_framing, conflicts_with = "camera_eye")]
    pub framing: Option<Framing>,
    /// Fixed camera's eye, world metres [default: the engine's own, --framing]
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_hyphen_values = true, requires = "camera_target")]
    pub camera_eye: Option<Vec3>,
    /// Fixed camera's target, world metres; needs --camera-eye
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_hyphen_values = true, requires = "camera_eye")]
    pub camera_target: Option<Vec3>,
    /// Fixed camera's up hint; needs --camera-eye [default: 0,1,0]
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_hyphen_values = true, requires = "camera_eye")]
    pub camera_up: Option<Vec3>,
    /// Fixed camera's vertical field of view, deg, in (0, 180) [default: 30]
    #[arg(long, value_name = "DEG", value_parser = parse_positive_f32, requires = "camera_eye")]
    pub fov_deg: Option<f32>,
    /// Draw the hair only: no head, no body
    #[arg(long)]
    pub no_solids: bool,
    /// Direction the first (directional) light travels, world, Y up
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_direction, allow_hyphen_values = true, help_heading = "Light and shading")]
    pub light_dir: Option<Vec3>,
    /// First light's irradiance, linear, >= 0 [default: 6]
    #[arg(long, value_name = "E|R,G,B", value_parser = parse_rgb, help_heading = "Light and shading")]
    pub irradiance: Option<Vec3>,
    /// Ambient sky radiance, linear, >= 0 [default: 0.035,0.04,0.05]
    #[arg(long, value_name = "L|R,G,B", value_parser = parse_rgb, help_heading = "Light and shading")]
    pub ambient: Option<Vec3>,
    /// Image width, pixels, 16–8192 [default: 800]
    #[arg(long, value_name = "PX", value_parser = clap::value_parser!(u32).range(16..=8192), help_heading = "Image")]
    pub width: Option<u32>,
    /// Image height, pixels, 16–8192 [default: 800]
    #[arg(long, value_name = "PX", value_parser = clap::value_parser!(u32).range(16..=8192), help_heading = "Image")]
    pub height: Option<u32>,
    /// preview, final or reference: time against error (README) [default: preview for play,
    /// final for the other commands]
    #[arg(long, value_name = "LEVEL", value_parser = crate::cli::parse_quality, help_heading = "Quality")]
    pub quality: Option<Quality>,
    /// Exposure: radiance times 2^stops, in [−20, 20] [default: 0]
    #[arg(long, value_name = "STOPS", value_parser = parse_finite_f32, allow_hyphen_values = true, help_heading = "Image")]
    pub exposure_stops: Option<f32>,
}

impl SceneFileArgs {
    /// The effective scene: the scene file (or the default scene) with the flags written over
    /// it (`--print-scene` prints it), and the name errors give it. Errors name the file, the
    /// field and the rule.
    pub fn effective(&self) -> Result<(String, SceneFile), AppError> {
        let (name, mut file) = match &self.scene {
            Some(path) => {
                let name = path.display().to_string();
                let (file, _) = SceneFile::load(path).map_err(AppError::input)?;
                (name, file)
            }
            None => ("scene flags".to_string(), SceneFile::default()),
        };
        if let Some(w) = self.width {
            file.image.width = w;
        }
        if let Some(h) = self.height {
            file.image.height = h;
        }
        if let Some(q) = self.quality {
            file.quality = Some(q);
        }
        if let Some(l) = self.light_dir {
            match file.lights.first_mut() {
                Some(LightJson::Directional { direction, .. }) => *direction = l.to_array(),
                _ => {
                    return Err(AppError::input(anyhow::anyhow!(
                        "--light-dir sets the first light's direction, and the first light of {name} is not a directional light"
                    )));
                }
            }
        }
        self.write_view(&mut file)?;
        Ok((name, file))
    }

    /// Writes the camera, solids, irradiance, ambient and exposure flags into `scene`.
    fn write_view(&self, scene: &mut SceneFile) -> Result<(), AppError> {
        if let Some(f) = self.framing {
            match &mut scene.camera {
                CameraJson::FollowHead { framing } => *framing = Some(f),
                CameraJson::Fixed { .. } => {
                    return Err(AppError::input(anyhow::anyhow!(
                        "--framing chooses how the engine's own camera frames the figure, and the scene's camera is fixed (camera.type \"fixed\")"
                    )));
                }
            }
        }
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

    /// A refused scene, naming the flags that set the field (the error names it as the scene
    /// file does): `scene flags: camera.position_m (set by --camera-eye): ...`.
    fn blame(&self, e: SceneError) -> AppError {
        if let SceneError::Invalid { file, field, rule } = &e {
            let mut flags: Vec<&str> = self.flag_of(field).into_iter().collect();
            if self.exposure_stops.is_some() && rule.contains("exposure_stops") {
                flags.push("--exposure-stops");
            }
            if !flags.is_empty() {
                return AppError::input(anyhow::anyhow!(
                    "{file}: {field} (set by {}): {rule}",
                    flags.join(" and ")
                ));
            }
        }
        AppError::input(e)
    }

    /// The flag given that wrote the scene field `field` ([`Self::write_view`]), if any.
    fn flag_of(&self, field: &str) -> Option<&'static str> {
        let (given, flag) = match field {
            "camera.position_m" => (self.camera_eye.is_some(), "--camera-eye"),
            "camera.target_m" => (self.camera_target.is_some(), "--camera-target"),
            "camera.up" => (self.camera_up.is_some(), "--camera-up"),
            "camera.fov_y_deg" => (self.fov_deg.is_some(), "--fov-deg"),
            "ambient" => (self.ambient.is_some(), "--ambient"),
            "exposure_stops" => (self.exposure_stops.is_some(), "--exposure-stops"),
            "lights[0].irradiance" => (self.irradiance.is_some(), "--irradiance"),
            "lights[0].direction" => (self.light_dir.is_some(), "--light-dir"),
            _ => (false, ""),
        };
        given.then_some(flag)
    }

    /// The run's scene: [`Self::effective`], validated, with its point lights checked to lie
    /// beyond the reach of the hair of `style` on the head at the motion's first pose; and the
    /// quality level the flag or the file asks for.
    pub fn scene(
        &self,
        style: &Hairstyle,
        motion: &Motion,
    ) -> Result<(Scene, Option<Quality>), AppError> {
        let (name, file) = self.effective()?;
        let mut scene = file.validate(&name).map_err(|e| self.blame(e))?;
        let head = Vec3::from(motion.sample(0.0).head.translation);
        let reach = style.max_length_m() + style.head.radii_m.iter().copied().fold(0.0, f32::max);
        wisp::scene::file::check_point_lights_outside(&scene.lights, head, reach)
            .map_err(|(field, rule)| AppError::input(anyhow::anyhow!("{name}: {field}: {rule}")))?;
        // Said here, once; the engine applies the same rule to the lights it is given.
        let far_reach = style.reach_m();
        for far in far_point_lights_as_directional(&mut scene.lights, head, far_reach) {
            eprintln!("wisp: {name}: {}", far_light::describe(&far, far_reach));
        }
        Ok((scene, file.quality))
    }
}
