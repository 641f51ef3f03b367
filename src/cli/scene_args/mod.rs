//! The flags of a run, taken by every command that builds an engine (`render`, `simulate`,
//! `play`, `bench`, `accuracy`, `export`), and how they become its hairstyle, motion and
//! [`EngineConfig`].
//!
//! The flags are grouped by what they set, one struct per file beside the one function that
//! writes them into their part of the run:
//!
//! ```text
//! hair           --hairstyle, --groom-*          -> Hairstyle, an imported groom's hair
//! motion         --animation, --clip, --head-*   -> Motion
//! scene          --scene and its shortcuts       -> Scene (image, camera, lights, solids),
//!                --quality                          the quality level (every pass's config)
//! simulation     --no-sim, --no-self-collision,  -> SimulationConfig
//!                --sim-hz
//! interpolation  --segment-pieces,               -> InterpolationConfig
//!                --strand-fraction
//! hair_map       --map-res, --map-hz,            -> HairMapConfig
//!                --contact-mm
//! shading        --shading, --volume-*           -> ShadingConfig
//! raster         --min-line-width-px             -> RasterConfig
//! budget         --max-memory-gb, --max-work-*   -> Budget (checked before the engine is built)
//! ```
//!
//! A new option of a pass is a field of its pass's config (library), its use in the pass, and
//! a field and a line in that pass's file here. The help's headings group the flags for the
//! user (hair, motion, scene, light and shading, image, budget), across these structs.

mod budget;
mod groom_mesh;
mod hair;
mod hair_map;
mod interpolation;
mod motion;
mod raster;
mod scene;
mod shading;
mod simulation;

pub use hair::ImportedHair;

use super::AppError;
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;
use wisp::quality::Quality;
use wisp::scene::{CameraSetup, Framing, Scene};

/// What is rendered: hair, motion, scene, each pass's options and the budget.
#[derive(clap::Args, Debug, Clone)]
pub struct SceneArgs {
    #[command(flatten)]
    pub hair: hair::HairArgs,
    #[command(flatten)]
    pub motion: motion::MotionArgs,
    #[command(flatten)]
    pub simulation: simulation::SimulationArgs,
    #[command(flatten)]
    pub scene_file: scene::SceneFileArgs,
    #[command(flatten)]
    pub shading: shading::ShadingArgs,
    #[command(flatten)]
    pub hair_map: hair_map::HairMapArgs,
    #[command(flatten)]
    pub interpolation: interpolation::InterpolationArgs,
    #[command(flatten)]
    pub raster: raster::RasterArgs,
    #[command(flatten)]
    pub budget: budget::BudgetArgs,
    /// The quality level when neither `--quality` nor the scene file names one: `final`, and
    /// `preview` for `wisp play` (set by the command, not a flag).
    #[arg(skip)]
    pub default_quality: Quality,
}

impl SceneArgs {
    /// Loads the motion and the hairstyle (and an imported groom's hair), and builds the scene
    /// and the engine configuration; refuses a groom whose roots miss the character's head.
    pub fn resolve(&self) -> Result<(Hairstyle, ImportedHair, Motion, EngineConfig), AppError> {
        let on_character = self.hair.groom_as_authored && self.motion.animation.is_some();
        let mut motion = if self.hair.groom_as_authored {
            // Roots pinned where the file has them, or on the bones of the character the
            // groom was authored on.
            self.motion.load_for_authored_groom()?
        } else {
            self.motion.load(self.hair_alone()?)?
        };
        let authored_on = on_character.then(|| wisp::groom::AuthoredFrame {
            upright: motion.file_turn(),
            head_at_rest_m: glam::Vec3::from(motion.head_at_rest().translation),
        });
        let (style, mut hair, unit_m) = self.hair.load(authored_on)?;
        let meshes = self.groom_meshes()?;
        if !meshes.is_empty() {
            motion = groom_mesh::motion_of_meshes(&meshes, unit_m.unwrap_or(1.0))?;
        }
        if on_character && let Some((guides, _)) = &mut hair {
            let bones = wisp::engine::carry_roots_by_bones(guides, &mut motion)
                .map_err(|e| AppError::input(anyhow::anyhow!("{}: {e}", self.motion.source())))?;
            eprintln!(
                "wisp: groom kept as authored on {}: each root pinned to the nearest of its \
                 bones ({bones} carry roots); no body colliders",
                self.motion.source()
            );
        }
        let (mut scene, quality) = self.scene_file.scene(&style, &motion)?;
        if self.hair.groom_as_authored && !on_character && meshes.is_empty() {
            // No head or body is drawn: the groom's own is not in the files.
            scene.draw_solids = false;
        }
        let on_a_body = on_character || !meshes.is_empty();
        if on_a_body && scene.camera == CameraSetup::Framed(None) {
            // The groom covers the character, not only its head.
            scene.camera = CameraSetup::Framed(Some(Framing::Full));
        }
        let mut config = self.config(scene, quality.unwrap_or(self.default_quality));
        if hair.is_some() {
            // An imported groom's hair falls from its captured pose: settle it in coarse steps.
            config.simulation.settle_step_s = Some(wisp::engine::GROOM_SETTLE_STEP_S);
        }
        if !self.hair.groom_as_authored {
            self.hair
                .check_roots_on_head(&style, &hair, &motion, &self.motion.source())?;
        }
        Ok((style, hair, motion, config))
    }

    /// The groom's own meshes among `--hairstyle` (`.tfxmesh`): only for a groom kept as
    /// authored without `--animation` (they are the groom's character).
    fn groom_meshes(&self) -> Result<Vec<&str>, AppError> {
        let meshes: Vec<&str> = (self.hair.hairstyle.iter())
            .map(String::as_str)
            .filter(|a| groom_mesh::is_groom_mesh(a))
            .collect();
        if !meshes.is_empty() && (!self.hair.groom_as_authored || self.motion.animation.is_some()) {
            return Err(AppError::input(anyhow::anyhow!(
                "--hairstyle {}: a groom's own mesh is drawn under the groom kept where it was \
                 authored: give --groom-as-authored, and no --animation (the mesh is the \
                 groom's character)",
                meshes.join(",")
            )));
        }
        Ok(meshes)
    }

    /// Whether no solids are drawn (`--no-solids`, or the scene file's `draw_solids`): with
    /// `--still`, the motion is then the head alone (`MotionArgs::load`).
    pub fn hair_alone(&self) -> Result<bool, AppError> {
        Ok(!self.scene_file.effective()?.1.draw_solids)
    }

    /// The engine configuration: `scene`, each pass's config at `quality`, and the flags
    /// given written over the level's choices.
    pub fn config(&self, scene: Scene, quality: Quality) -> EngineConfig {
        let mut config = EngineConfig {
            scene,
            ..EngineConfig::at_quality(quality)
        };
        self.simulation.apply(&mut config.simulation);
        self.interpolation.apply(&mut config.interpolation);
        self.hair_map.apply(&mut config.hair_map);
        self.shading.apply(&mut config.shading);
        self.raster.apply(&mut config.raster);
        config
    }
}

/// The engine for a resolved scene: generated hair, or the imported groom's.
pub fn engine(
    style: Hairstyle,
    hair: ImportedHair,
    motion: Motion,
    config: EngineConfig,
) -> Engine {
    match hair {
        Some((guides, layout)) => Engine::with_hair(style, guides, layout, motion, config),
        None => Engine::new(style, motion, config),
    }
}
