//! What a run is configured with, apart from the hairstyle and the motion: the scene (what is in
//! the frame and how it is looked at) and one config per pass. A pass reads only its own
//! config and the scene; a new option belongs to one pass's config.

use super::hair_map::HairMapConfig;
use super::interpolation::InterpolationConfig;
use super::occluders::OccluderConfig;
use super::raster::RasterConfig;
use super::shading::ShadingConfig;
use super::simulation::SimulationConfig;
use super::skin_texture::SkinTextureConfig;
use crate::quality::Quality;
use crate::scene::Scene;

/// Everything about a run that is not the hairstyle or the motion.
#[derive(Clone, Debug, Default)]
pub struct EngineConfig {
    /// Image size, camera, lights, ambient, background and whether the solids (character,
    /// head, body) are drawn: what every pass that lights or draws reads.
    pub scene: Scene,
    pub simulation: SimulationConfig,
    pub interpolation: InterpolationConfig,
    pub hair_map: HairMapConfig,
    pub occluders: OccluderConfig,
    pub skin_texture: SkinTextureConfig,
    pub shading: ShadingConfig,
    pub raster: RasterConfig,
    /// The quality level the pass configs were set from ([`EngineConfig::apply_quality`];
    /// default `final`, the configs' defaults). A choice written after the level may differ
    /// from the level's.
    pub level: Quality,
}

impl EngineConfig {
    /// This configuration with a validated scene (image size, camera, lights, ambient,
    /// background, solids).
    pub fn with_scene(self, scene: &Scene) -> Self {
        Self {
            scene: scene.clone(),
            ..self
        }
    }

    /// The default configuration at an image size of `width` × `height` pixels.
    pub fn sized(width: u32, height: u32) -> Self {
        let mut config = Self::default();
        config.scene.width = width;
        config.scene.height = height;
        config
    }
}
