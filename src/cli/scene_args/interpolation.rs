//! The interpolation pass's flags ([`InterpolationConfig`]).

use crate::cli::parse_finite_f32;
use wisp::engine::InterpolationConfig;

#[derive(clap::Args, Debug, Clone)]
#[command(next_help_heading = "Image")]
pub struct InterpolationArgs {
    /// Lit pieces each strand segment is cut into, 1–16 [default: 1; 2 at --quality reference]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=16))]
    pub segment_pieces: Option<u32>,
    /// Share of each wisp's strands drawn, each with the fibres of those left out, in (0, 1]
    /// [default: 1; 0.5 at --quality preview]
    #[arg(long, value_name = "F", value_parser = parse_fraction, help_heading = "Quality")]
    pub strand_fraction: Option<f32>,
}

/// A fraction in (0, 1].
fn parse_fraction(s: &str) -> Result<f32, String> {
    let v = parse_finite_f32(s)?;
    if v > 0.0 && v <= 1.0 {
        Ok(v)
    } else {
        Err(format!("must be in (0, 1] (got {v})"))
    }
}

impl InterpolationArgs {
    /// Writes the flags given over the interpolation's config.
    pub fn apply(&self, config: &mut InterpolationConfig) {
        if let Some(n) = self.segment_pieces {
            config.segment_pieces = n;
        }
        if let Some(f) = self.strand_fraction {
            config.strand_fraction = f;
        }
    }
}
