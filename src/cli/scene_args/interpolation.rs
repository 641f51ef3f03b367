//! The interpolation pass's flags ([`InterpolationConfig`]).

use wisp::engine::InterpolationConfig;

#[derive(clap::Args, Debug, Clone)]
#[command(next_help_heading = "Image")]
pub struct InterpolationArgs {
    /// Lit pieces each strand segment is cut into, 1–16 [default: 1]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=16))]
    pub segment_pieces: Option<u32>,
}

impl InterpolationArgs {
    /// Writes the flags given over the interpolation's config.
    pub fn apply(&self, config: &mut InterpolationConfig) {
        if let Some(n) = self.segment_pieces {
            config.segment_pieces = n;
        }
    }
}
