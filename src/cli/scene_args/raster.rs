//! The raster pass's flags ([`RasterConfig`]).

use crate::cli::parse_positive_f32;
use wisp::engine::RasterConfig;
use wisp::raster::LineWidth;

#[derive(clap::Args, Debug, Clone)]
#[command(next_help_heading = "Image")]
pub struct RasterArgs {
    /// Narrowest hair line, pixels; thinner ones are fainter [default: 0.5]
    #[arg(long, value_name = "PX", value_parser = parse_positive_f32)]
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
