//! The light paths' flags (`--shading volume`, `wisp::light_paths`), flattened into `SceneArgs`.

use super::parse_finite_f32;
use wisp::engine::EngineConfig;

/// Cell edges of the volume of `--shading volume`, millimetres.
pub const VOLUME_CELL_MM: std::ops::RangeInclusive<f32> = 0.5..=100.0;

/// A volume cell edge in millimetres, within [`VOLUME_CELL_MM`].
pub fn parse_volume_cell_mm(s: &str) -> Result<f32, String> {
    let v = parse_finite_f32(s)?;
    if VOLUME_CELL_MM.contains(&v) {
        Ok(v)
    } else {
        Err(format!(
            "must be {} to {} mm (got {v})",
            VOLUME_CELL_MM.start(),
            VOLUME_CELL_MM.end()
        ))
    }
}

#[derive(clap::Args, Debug, Clone)]
pub struct LightPathArgs {
    /// `--shading volume`: the volume's cell edge in millimetres, 0.5..=100 (default 4).
    #[arg(long, value_name = "MM", value_parser = parse_volume_cell_mm)]
    pub volume_cell_mm: Option<f32>,
    /// `--shading volume`: light paths per light, 1000..=50000000 (default 2000000).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1000..=50_000_000))]
    pub volume_paths: Option<u32>,
    /// `--shading volume`: each cell's light merged into N × N direction bins (1..=16, default
    /// 8).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=16))]
    pub volume_bins: Option<u32>,
}

impl LightPathArgs {
    /// Writes the flags given over the configuration's defaults.
    pub fn apply(&self, config: &mut EngineConfig) {
        if let Some(mm) = self.volume_cell_mm {
            config.shading.light_paths.cell_m = mm * 1e-3;
        }
        if let Some(n) = self.volume_paths {
            config.shading.light_paths.paths = n;
        }
        if let Some(n) = self.volume_bins {
            config.shading.light_paths.bins_per_axis = n;
        }
    }
}
