//! What each [`Quality`] level chooses for the passes: a set of the pass configs' values that
//! trade time for error. A level is applied to a config first ([`EngineConfig::at_quality`]);
//! a caller's own choices written after it override it (the command line writes its flags
//! last). The time and error of each level are measured by `wisp bench --quality-list` and
//! published in BENCHMARKS.md, with these values:
//!
//! | choice | preview | final | reference |
//! |---|---|---|---|
//! | simulation step | 1/240 s | the hairstyle's (1/480 s) | 1/960 s |
//! | render strands made per wisp | half, each with twice the fibres | all | all |
//! | skin-texture texels per map column | 1 | 2 | 2 |
//! | light map cells | 1.5 × as wide as the scene's choice | the scene's choice | the scene's choice |
//! | hair maps built | 30 times a second of motion | every frame | every frame |
//! | segment pieces | 1 | 1 | 2 |
//! | shader | dual scattering | light paths (`volume`) | light paths (`volume`) |
//! | light paths per light | | 200,000 | 2,000,000 |
//! | light paths built | | 6 times a second of motion | every frame |
//! | light-path cells | | 6 mm | 4 mm |
//! | direction bins gathered through the fibre, per cell | | the 16 strongest, the rest as moments | all |
//! | contact shadows (one-fibre strands) | off | off | 120 mm |
//!
//! The map's resolution follows the strand spacing at every level (`MapGeometry::for_scene`).

use super::config::EngineConfig;
use super::hair_map::{ContactShadowing, DEFAULT_CONTACT_WINDOW_M};
use crate::fiber::ShadingMode;
use crate::light_paths::{Directions, LightPathParams};
use crate::map::surface::DEFAULT_TEXELS_PER_COLUMN;
pub use crate::quality::Quality;

/// How much wider `preview`'s map cells are than the scene's choice: T_f MAE against the
/// exact reference 0.017 where the default reads 0.012, at about half the map build's time
/// (ACCURACY.md, BENCHMARKS.md).
const PREVIEW_MAP_CELL_SCALE: f32 = 1.5;

/// The values of one level (the table in the module doc).
struct LevelChoices {
    step_s: Option<f32>,
    strand_fraction: f32,
    texels_per_column: f32,
    map_cell_scale: f32,
    map_interval_s: f64,
    segment_pieces: u32,
    mode: ShadingMode,
    light_paths: LightPathParams,
    paths_interval_s: f64,
    contact: ContactShadowing,
}

/// `final`'s light paths: a tenth of `reference`'s paths in cells 1.5× as wide, each cell's 16
/// strongest direction bins gathered through the fibre and the rest through their moments
/// (ACCURACY.md §2 and its decisions: fewer bins read side-lit dense blond darker, 0.82–0.86
/// of the path tracer with 4 or 8 against 0.89–0.91 with 16; 8 mm cells spread light past
/// back-lit silhouettes; half the paths, 100,000, lose up to 7 points of blocks within 2× in
/// the side- and point-lit cases, BENCHMARKS.md). Its bins are capped at 256 MB, a third of `reference`'s: the smooth
/// dance's need about 110 MB at 6 mm (cells grow past the cap), and the run's memory estimate
/// counts the cap.
fn final_light_paths() -> LightPathParams {
    LightPathParams {
        cell_m: 0.006,
        paths: 200_000,
        directions: Directions::Strongest(16),
        max_bins_bytes: 256_000_000,
        ..LightPathParams::default()
    }
}

/// `final` builds its light paths 6 times a second of motion (every fifth frame of a 30 frames a
/// second export) and the frames between gather them where the hair was then
/// (`engine::paths_rate`): its shading 3.4–4.1× dual scattering's on the dance instead of
/// 9.4–9.9×, for light late by up to a sixth of a second. Over the dance's fastest 0.7 s, against 10×
/// the paths built for every frame, the mean relative luminance error over the hair is 5.3%
/// where a build for every frame has its own noise's 2.6%; halving the paths and building 10
/// times a second costs as much time and reads 5.1%, but would lose stills' accuracy, which a
/// lower rate leaves as it was (BENCHMARKS.md, "`final`'s light paths").
const FINAL_PATHS_INTERVAL_S: f64 = 1.0 / 6.0;

fn choices(quality: Quality) -> LevelChoices {
    match quality {
        Quality::Preview => LevelChoices {
            step_s: Some(1.0 / 240.0),
            strand_fraction: 0.5,
            texels_per_column: 1.0,
            map_cell_scale: PREVIEW_MAP_CELL_SCALE,
            map_interval_s: 1.0 / 30.0,
            segment_pieces: 1,
            mode: ShadingMode::DualScattering,
            light_paths: LightPathParams::default(),
            paths_interval_s: 0.0,
            contact: ContactShadowing::Off,
        },
        Quality::Final => LevelChoices {
            step_s: None,
            strand_fraction: 1.0,
            texels_per_column: DEFAULT_TEXELS_PER_COLUMN,
            map_cell_scale: 1.0,
            map_interval_s: 0.0,
            segment_pieces: 1,
            mode: ShadingMode::Volume,
            light_paths: final_light_paths(),
            paths_interval_s: FINAL_PATHS_INTERVAL_S,
            contact: ContactShadowing::Off,
        },
        Quality::Reference => LevelChoices {
            step_s: Some(1.0 / 960.0),
            strand_fraction: 1.0,
            texels_per_column: DEFAULT_TEXELS_PER_COLUMN,
            map_cell_scale: 1.0,
            map_interval_s: 0.0,
            segment_pieces: 2,
            mode: ShadingMode::Volume,
            light_paths: LightPathParams::default(),
            paths_interval_s: 0.0,
            contact: ContactShadowing::WindowM(DEFAULT_CONTACT_WINDOW_M),
        },
    }
}

impl EngineConfig {
    /// Writes `quality`'s choices (the module doc's table) into the pass configs; the scene
    /// and every choice the table does not name are left as they are.
    pub fn apply_quality(&mut self, quality: Quality) {
        let c = choices(quality);
        self.level = quality;
        self.simulation.step_s = c.step_s;
        self.interpolation.strand_fraction = c.strand_fraction;
        self.interpolation.segment_pieces = c.segment_pieces;
        self.skin_texture.texels_per_column = c.texels_per_column;
        self.shading.mode = c.mode;
        self.shading.light_paths = c.light_paths;
        self.shading.paths_interval_s = c.paths_interval_s;
        self.hair_map.contact = c.contact;
        self.hair_map.cell_scale = c.map_cell_scale;
        self.hair_map.rebuild_interval_s = c.map_interval_s;
    }

    /// The configuration at `quality` for the default scene.
    pub fn at_quality(quality: Quality) -> Self {
        let mut config = Self::default();
        config.apply_quality(quality);
        config
    }
}
