//! The shading pass's flags ([`ShadingConfig`]): the fibre shader, and the light paths of
//! `--shading volume` (`wisp::light_paths`).

use crate::cli::parse_finite_f32;
use wisp::engine::ShadingConfig;
use wisp::fiber::ShadingMode;
use wisp::light_paths::Directions;

/// Fibre shader choice on the command line.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum ShadingArg {
    // Dual scattering (Zinke 2008): the fibre's BCSDF plus multiple scattering.
    Dual,
    // Single scattering with hard shadows: the BCSDF times the light that reaches the point
    // through no fibre.
    Single,
    // Kajiya-Kay scaled by transmittance (Bertails 2005).
    KajiyaKay,
    // The shadows alone: grey = the irradiance reaching the hair through no fibre (no fibre
    // model, no ambient on the hair).
    Visibility,
    // Single scattering plus multiply scattered light from paths traced through the hair
    // volume (the path count and cells set by the quality level).
    Volume,
}

impl From<ShadingArg> for ShadingMode {
    fn from(s: ShadingArg) -> Self {
        match s {
            ShadingArg::Dual => ShadingMode::DualScattering,
            ShadingArg::Single => ShadingMode::SingleScattering,
            ShadingArg::KajiyaKay => ShadingMode::KajiyaKay,
            ShadingArg::Visibility => ShadingMode::Visibility,
            ShadingArg::Volume => ShadingMode::Volume,
        }
    }
}

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
#[command(next_help_heading = "Light and shading")]
pub struct ShadingArgs {
    /// Shader: dual, single, kajiya-kay, visibility or volume [default: volume at --quality
    /// final and reference, dual at preview]
    #[arg(long, value_name = "SHADER", value_enum, hide_possible_values = true)]
    pub shading: Option<ShadingArg>,
    /// --shading volume: cell edge, mm, 0.5–100 [default: 6 at --quality final, else 4]
    #[arg(long, value_name = "MM", value_parser = parse_volume_cell_mm)]
    pub volume_cell_mm: Option<f32>,
    /// --shading volume: paths per light, 1000–50000000 [default: 200000 at --quality final,
    /// else 2000000]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1000..=50_000_000))]
    pub volume_paths: Option<u32>,
    /// --shading volume: N × N direction bins per cell, 1–16 [default: 8]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=16))]
    pub volume_bins: Option<u32>,
    /// --shading volume: each cell's strongest N direction bins gathered through the fibre,
    /// the rest through tables of its moments, 1–256 [default: 16 at --quality final, else
    /// every bin]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=256))]
    pub volume_strongest: Option<u32>,
    /// --shading volume: builds of the light paths per second of motion, 1–1000, or 0 for
    /// every frame; the frames between gather the last build where their hair was then
    /// [default: 6 at --quality final, else every frame]
    #[arg(long, value_name = "HZ", value_parser = clap::value_parser!(u32).range(0..=1000), help_heading = "Quality")]
    pub volume_hz: Option<u32>,
}

impl ShadingArgs {
    /// Writes the flags given over the shading's config.
    pub fn apply(&self, config: &mut ShadingConfig) {
        if let Some(mode) = self.shading {
            config.mode = mode.into();
        }
        if let Some(mm) = self.volume_cell_mm {
            config.light_paths.cell_m = mm * 1e-3;
        }
        if let Some(n) = self.volume_paths {
            config.light_paths.paths = n;
        }
        if let Some(n) = self.volume_bins {
            config.light_paths.bins_per_axis = n;
        }
        if let Some(k) = self.volume_strongest {
            config.light_paths.directions = Directions::Strongest(k);
        }
        if let Some(hz) = self.volume_hz {
            config.paths_interval_s = if hz == 0 { 0.0 } else { 1.0 / hz as f64 };
        }
    }
}
