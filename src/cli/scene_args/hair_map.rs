//! The hair map pass's flags ([`HairMapConfig`]): the map's resolution, how often the maps
//! are built, and contact shadows.

use crate::cli::parse_contact_mm;
use wisp::engine::{ContactShadowing, HairMapConfig};

#[derive(clap::Args, Debug, Clone)]
#[command(next_help_heading = "Light and shading")]
pub struct HairMapArgs {
    /// Light map cells per axis, 4–1024 [default: from the strand spacing; cells 1.5× as
    /// wide at --quality preview]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(4..=1024))]
    pub map_res: Option<u32>,
    /// Builds of the hair's light maps per second of motion, 1–1000, or 0 for every frame
    /// [default: every frame; 30 at --quality preview]
    #[arg(long, value_name = "HZ", value_parser = clap::value_parser!(u32).range(0..=1000), help_heading = "Quality")]
    pub map_hz: Option<u32>,
    /// Contact shadows of one-fibre strands, mm to the light [default: off]
    #[arg(long, value_name = "MM", value_parser = parse_contact_mm, allow_hyphen_values = true)]
    pub contact_mm: Option<f32>,
}

impl HairMapArgs {
    /// Writes the flags into the hair map's config.
    pub fn apply(&self, config: &mut HairMapConfig) {
        if self.map_res.is_some() {
            config.map_res = self.map_res;
        }
        if let Some(hz) = self.map_hz {
            config.rebuild_interval_s = if hz == 0 { 0.0 } else { 1.0 / hz as f64 };
        }
        if let Some(mm) = self.contact_mm {
            config.contact = ContactShadowing::from_mm(mm);
        }
    }
}
