//! The raster pass's flags ([`RasterConfig`]).

use crate::cli::parse_positive_f32;
use wisp::engine::RasterConfig;
use wisp::raster::{LineWidth, MAX_WIDTH_PX};

#[derive(clap::Args, Debug, Clone)]
#[command(next_help_heading = "Image")]
pub struct RasterArgs {
    /// Narrowest hair line, pixels, at most 64; thinner ones are fainter [default: 0.5]
    #[arg(long, value_name = "PX", value_parser = parse_min_line_width_px)]
    pub min_line_width_px: Option<f32>,
}

impl RasterArgs {
    /// Writes the flags given over the raster's config.
    pub fn apply(&self, config: &mut RasterConfig) {
        if let Some(w) = self.min_line_width_px {
            config.line.width = LineWidth::Projected { min_px: w };
        }
    }
}

/// A narrowest line width in (0, [`MAX_WIDTH_PX`]] pixels. No line is drawn wider than
/// [`MAX_WIDTH_PX`], so a larger minimum would draw every segment at that cap with its opacity
/// cut to `w / minimum` (at 1e30 the hair vanishes) while each segment covers the cap's
/// pixels: the raster's memory and time grow with the drawn width (3.5× the memory and 19×
/// the raster time at 64 px against 0.5 px, 800×800).
fn parse_min_line_width_px(s: &str) -> Result<f32, String> {
    let v = parse_positive_f32(s)?;
    if v > MAX_WIDTH_PX {
        return Err(format!(
            "must be at most {MAX_WIDTH_PX} px, the widest line drawn (got {})",
            s.trim()
        ));
    }
    Ok(v)
}
