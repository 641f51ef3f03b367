//! Reference scenes out: a frame's render strands, camera, light and fibre, written so that a
//! path tracer can render the same scene (`tools/reference/`), next to wisp's own linear image
//! of it.
//!
//! [`write_reference_scene`] writes into a directory:
//! - `hair.hair`: the render strands as cyHair ([`cyhair`]), metres, root first, thickness =
//!   the fibre diameter (a path tracer draws each render strand as one fibre);
//! - `scene.json`: [`ReferenceScene`] — camera, light ([`LightJson`]: a directional light's
//!   direction of travel and irradiance, or a point light's position and intensity),
//!   ambient, image size, fibres per strand, wisp's fibre parameters verbatim and their
//!   mapping to Mitsuba 3's `hair` BSDF ([`mitsuba`]);
//! - `wisp.exr`: the frame as linear RGBA float, coverage in alpha (RGB premultiplied: the
//!   engine must have drawn over a black background), and `wisp.png` to look at;
//! - `vertex_rgb.f32`: the colour wisp shades each render-strand point with (linear RGB, three
//!   little-endian f32 per point, in `hair.hair`'s point order; every point, also those the
//!   frame left unshaded behind the solids: call `Engine::shade` first), so a reference can take
//!   wisp's shading apart from its raster: `tools/reference/visibility.py --decompose` puts
//!   these colours on the fibres the path tracer sees.
//!
//! Every file is written under a temporary name and renamed into place.
//!
//! [`usd`] writes the render strands of every frame of a run, for other tools (Blender,
//! Houdini): USD ASCII `BasisCurves` with a time sample per frame (`wisp render --curves`).

pub mod cyhair;
pub mod mitsuba;
pub mod usd;

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::engine::Engine;
use crate::output::{OutputError, write_atomically, write_exr_rgba_f32, write_png_rgb8};
use crate::scene::CameraSpec;
use cyhair::CyHairError;
use mitsuba::MitsubaHair;
pub use mitsuba::reference_light;

/// `scene.json`'s `format` value; bump the number when a field changes meaning.
pub const SCENE_FORMAT: &str = "wisp-reference-scene/1";

/// What `scene.json` holds. Angles in degrees (a file format is an edge), lengths in metres.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ReferenceScene {
    /// [`SCENE_FORMAT`].
    pub format: String,
    /// `wisp <version>`.
    pub generator: String,
    /// Hairstyle name.
    pub hairstyle: String,
    /// Time of the frame in seconds of the motion.
    pub time_s: f64,
    /// The strands (relative to `scene.json`), and wisp's image of the frame.
    pub hair_file: String,
    pub wisp_image: String,
    /// Render strands and points per strand in `hair_file`.
    pub strands: usize,
    pub points_per_strand: usize,
    /// Real fibres each render strand stands for in wisp. A path tracer draws each render
    /// strand as one fibre, so the two renderers see the same hair only when this is 1.
    pub fibers_per_strand: f32,
    /// Fibre radius in metres (the `.hair` thickness is twice this).
    pub fiber_radius_m: f32,
    pub image: ImageSize,
    pub camera: CameraJson,
    pub light: LightJson,
    /// Ambient (sky) radiance, linear RGB; 0 for a comparison with a directional light alone.
    pub ambient: [f32; 3],
    /// wisp's shader for `wisp_image`.
    pub shading: String,
    /// Whether wisp drew the head and body (a path tracer scene of hair alone needs `false`).
    pub draw_solids: bool,
    /// Fibre model (`fiber.model`, "marschner" when absent).
    pub fiber_model: String,
    /// wisp's fibre parameters exactly as the hairstyle JSON holds them.
    pub fiber: serde_json::Value,
    /// The same fibre for Mitsuba 3's `hair` BSDF (MAPPING.md).
    pub mitsuba_hair_bsdf: MitsubaHair,
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ImageSize {
    pub width: u32,
    pub height: u32,
}

/// A pinhole camera; `fov_y_deg` is the vertical field of view (Mitsuba: `fov_axis = "y"`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CameraJson {
    pub eye: [f32; 3],
    pub target: [f32; 3],
    pub up: [f32; 3],
    pub fov_y_deg: f32,
}

/// The scene's one light, told apart by its fields (no tag, so a directional light's JSON is
/// `{"direction", "irradiance"}` as it always was). Linear RGB in wisp's units (1 = white).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum LightJson {
    /// `direction` is the way its light travels (unit, world); `irradiance` on a surface
    /// facing it (Mitsuba's `directional` emitter's `irradiance`).
    Directional {
        direction: [f32; 3],
        irradiance: [f32; 3],
    },
    /// A point light at `position_m` (world metres) with radiant intensity `intensity` per
    /// steradian: a surface facing it at distance d receives `intensity` / d², as wisp's
    /// [`crate::light::Light::Point`] and Mitsuba's `point` emitter's `intensity` both mean.
    Point {
        position_m: [f32; 3],
        intensity: [f32; 3],
    },
}

/// Why a reference scene could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error(transparent)]
    Hair(#[from] CyHairError),
    #[error(transparent)]
    Output(#[from] OutputError),
    #[error("{path}: {message}")]
    Scene { path: PathBuf, message: String },
}

/// File names inside the export directory.
pub const HAIR_FILE: &str = "hair.hair";
pub const SCENE_FILE: &str = "scene.json";
pub const WISP_EXR: &str = "wisp.exr";
pub const WISP_PNG: &str = "wisp.png";
pub const VERTEX_RGB: &str = "vertex_rgb.f32";

impl ReferenceScene {
    /// The description of `engine`'s last rendered frame at time `time_s`.
    pub fn of_engine(engine: &Engine, time_s: f64) -> Result<ReferenceScene, String> {
        let cam = engine.camera();
        let spec = CameraSpec::from_camera(cam)
            .ok_or_else(|| format!("the engine's camera is degenerate: {cam:?}"))?;
        // Through text, so that f32 fields read back as written (0.7, not 0.699999988).
        let fiber = serde_json::to_string(&engine.style.fiber)
            .and_then(|t| serde_json::from_str::<serde_json::Value>(&t))
            .map_err(|e| e.to_string())?;
        let l = engine.shading.lighting(&engine.scene);
        let light = reference_light(l.lights)?;
        let fb = engine.framebuffer();
        Ok(ReferenceScene {
            format: SCENE_FORMAT.into(),
            generator: format!("wisp {}", env!("CARGO_PKG_VERSION")),
            hairstyle: engine.style.name.clone(),
            time_s,
            hair_file: HAIR_FILE.into(),
            wisp_image: WISP_EXR.into(),
            strands: engine.strands().strand_count(),
            points_per_strand: engine.strands().points_per_strand,
            fibers_per_strand: engine.style.strands.fibers_per_strand,
            fiber_radius_m: engine.style.fiber.radius_m,
            image: ImageSize {
                width: fb.width,
                height: fb.height,
            },
            camera: CameraJson {
                eye: spec.eye().to_array(),
                target: spec.target().to_array(),
                up: spec.up().to_array(),
                fov_y_deg: spec.fov_y_rad().to_degrees(),
            },
            light,
            ambient: l.ambient.to_array(),
            shading: format!("{:?}", l.mode),
            draw_solids: engine.scene.draw_solids,
            fiber_model: mitsuba::fiber_model(&fiber),
            mitsuba_hair_bsdf: mitsuba::mitsuba_hair(&fiber),
            fiber,
        })
    }
}

/// Writes `colors` as three little-endian f32 per point ([`VERTEX_RGB`]), atomically.
fn write_vertex_rgb(path: &Path, colors: &[glam::Vec3]) -> Result<(), OutputError> {
    let bytes: Vec<u8> = colors
        .iter()
        .flat_map(|c| c.to_array())
        .flat_map(f32::to_le_bytes)
        .collect();
    write_atomically(path, |mut file| {
        use std::io::Write;
        file.write_all(&bytes).map_err(|error| OutputError::Io {
            path: path.to_path_buf(),
            error,
        })?;
        Ok(file)
    })
}

/// Writes `hair.hair`, `scene.json`, `wisp.exr`, `wisp.png` and `vertex_rgb.f32` for `engine`'s last rendered
/// frame (call [`Engine::frame`] first, then [`Engine::shade`] so every point has its colour)
/// into the existing directory `dir`. Returns the scene description written.
pub fn write_reference_scene(
    engine: &Engine,
    dir: &Path,
    time_s: f64,
) -> Result<ReferenceScene, ExportError> {
    let scene_path = dir.join(SCENE_FILE);
    let scene =
        ReferenceScene::of_engine(engine, time_s).map_err(|message| ExportError::Scene {
            path: scene_path.clone(),
            message,
        })?;
    cyhair::write_hair(
        &dir.join(HAIR_FILE),
        &engine.strands().positions,
        engine.strands().points_per_strand,
        2.0 * engine.style.fiber.radius_m,
        &format!(
            "{}: {}, metres, root first",
            scene.generator, scene.hairstyle
        ),
    )?;
    let fb = engine.framebuffer();
    write_exr_rgba_f32(
        &dir.join(WISP_EXR),
        fb.width,
        fb.height,
        &fb.color,
        &fb.coverage,
    )?;
    write_png_rgb8(&dir.join(WISP_PNG), fb.width, fb.height, &fb.to_srgb8())?;
    write_vertex_rgb(&dir.join(VERTEX_RGB), engine.colors())?;
    let text = serde_json::to_string_pretty(&scene).map_err(|e| ExportError::Scene {
        path: scene_path.clone(),
        message: e.to_string(),
    })?;
    write_atomically(&scene_path, |mut file| {
        use std::io::Write;
        file.write_all(text.as_bytes())
            .and_then(|()| file.write_all(b"\n"))
            .map_err(|error| OutputError::Io {
                path: scene_path.clone(),
                error,
            })?;
        Ok(file)
    })?;
    Ok(scene)
}
