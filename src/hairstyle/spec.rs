//! A hairstyle as written in JSON ([`Hairstyle`] and its sections), with the quantities derived
//! from it that the engine sizes itself by (longest guide, scalp area, strand spacing, head
//! size). Lengths are in metres and angles in degrees, as the field names say; optional fields
//! have the defaults given on them. Reading is `load.rs`, the rules `validate.rs`.

use super::dynamics::SimParams;
use crate::fiber::FiberParams;
use serde::{Deserialize, Serialize};

/// A hairstyle as written in JSON. Lengths in metres, angles in degrees (`*_deg`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Hairstyle {
    /// Display name.
    pub name: String,
    /// The head the hair grows on.
    pub head: HeadSpec,
    /// Where roots are placed on the scalp.
    pub scalp: ScalpSpec,
    /// Wisps: count and size.
    pub wisps: WispSpec,
    /// Guide strands: links and length.
    pub guides: GuideSpec,
    /// Render strands: smoothing resolution and fibres each one stands for.
    pub strands: StrandSpec,
    /// Curls of the render strands (absent or zero radius: straight hair).
    #[serde(default)]
    pub curl: CurlSpec,
    /// The fibre's optical parameters.
    #[serde(default)]
    pub fiber: FiberParams,
    /// Simulation parameters.
    #[serde(default)]
    pub dynamics: SimParams,
    /// Seed of the deterministic random placement (default 1).
    #[serde(default = "default_seed")]
    pub seed: u64,
}

fn default_seed() -> u64 {
    1
}

/// Head ellipsoid in the head frame (centre at the origin).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeadSpec {
    /// Semi-axes in metres: x (ear to ear), y (up), z (face direction). A human head: about
    /// [0.075, 0.10, 0.095].
    pub radii_m: [f32; 3],
}

/// Scalp region: roots are placed where the polar angle from +Y is below `max_polar_deg`,
/// except in front (toward +Z) where it is below `front_polar_deg` (the hairline).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScalpSpec {
    /// Largest polar angle of a root at the back and sides, degrees in [5, 150].
    pub max_polar_deg: f32,
    /// Largest polar angle of a root at the front (hairline), degrees in [5, max_polar_deg].
    pub front_polar_deg: f32,
}

/// Wisps (Bertails 2005: about 134, each simulated by 3 guides).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WispSpec {
    /// Number of wisps, in [1, MAX_WISPS].
    pub count: u32,
    /// Radius of a wisp's root disc in metres (the 3 guides sit on it).
    pub radius_m: f32,
    /// Render strands interpolated in each wisp, >= 1.
    pub strands_per_wisp: u32,
}

/// Guide strands: chains of rigid links.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GuideSpec {
    /// Links per guide, in [1, MAX_GUIDE_LINKS].
    pub links: u32,
    /// Mean guide length in metres, in (0, 2].
    pub length_m: f32,
    /// Relative length variation between wisps, in [0, 0.9].
    #[serde(default)]
    pub length_jitter: f32,
    /// Wave amplitude of the guides' rest shape in metres (kept by bending stiffness), >= 0.
    #[serde(default)]
    pub wave_amplitude_m: f32,
    /// Wave period along the guide in metres (used when the amplitude is > 0), in [0.001, 10].
    #[serde(default = "default_wave_period")]
    pub wave_period_m: f32,
    /// The farthest any hair reaches from the head's centre, metres, in (0, 10]: an imported
    /// groom's own extent (its roots' distance plus their strands' lengths), whose roots may lie
    /// off the head ellipsoid. Absent (the default): the head's largest radius plus the longest
    /// guide. The light map's span holds twice the larger of the two ([`Hairstyle::reach_m`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reach_m: Option<f32>,
}

fn default_wave_period() -> f32 {
    0.1
}

/// Render strands.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrandSpec {
    /// Points per render strand after Catmull-Rom smoothing (the nSmooth of Bertails §3.1);
    /// these points are both filled into the map and drawn. >= 2.
    pub points: u32,
    /// Real hair fibres that one render strand stands for (> 0): it scales the optical
    /// density the strand puts into the map.
    pub fibers_per_strand: f32,
    /// How much shorter than its guides a render strand may be, as a fraction of their length
    /// in [0, 0.9] (default 0: every strand reaches its guides' tips). Each strand draws its
    /// own length in [1 − v, 1] of the guides', so a wisp ends in a spread of tips, not a cut.
    #[serde(default)]
    pub length_variation: f32,
    /// The last fraction of each render strand, in [0, 1], over which its fibres end one by one
    /// (default 0: all F fibres reach the tip). Real hair thins toward the tips because its
    /// fibres have different lengths; the share of a strand's fibres present falls linearly to
    /// 0 over this fraction, in the map's fill as in the drawn coverage.
    #[serde(default)]
    pub tip_taper: f32,
}

/// Helical curls added to each render strand around its interpolated centre line.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CurlSpec {
    /// Helix radius in metres (0: straight hair).
    #[serde(default)]
    pub radius_m: f32,
    /// Helix period along the strand in metres (in [0.001, 10] when the radius is > 0).
    #[serde(default)]
    pub period_m: f32,
}

impl Hairstyle {
    /// Longest possible guide in metres (the lmax of Bertails §2.2).
    pub fn max_length_m(&self) -> f32 {
        self.guides.length_m * (1.0 + self.guides.length_jitter)
    }

    /// Approximate scalp area in m²: the cap of the head's mean radius out to the mean of the
    /// front and back polar limits.
    pub fn scalp_area_m2(&self) -> f32 {
        let r = self.head.radii_m.iter().sum::<f32>() / 3.0;
        let polar = 0.5 * (self.scalp.front_polar_deg + self.scalp.max_polar_deg);
        2.0 * std::f32::consts::PI * r * r * (1.0 - polar.to_radians().cos())
    }

    /// Mean spacing between neighbouring render strands at the scalp, metres.
    pub fn strand_spacing_m(&self) -> f32 {
        let strands = self.wisps.count as f32 * self.wisps.strands_per_wisp as f32;
        (self.scalp_area_m2() / strands.max(1.0)).sqrt()
    }

    /// Largest head dimension in metres (the hmax of Bertails §2.2).
    pub fn head_size_m(&self) -> f32 {
        2.0 * self.head.radii_m.iter().copied().fold(0.0, f32::max)
    }

    /// The farthest hair can reach from the head's centre, metres: the head's largest radius
    /// plus the longest guide (a strand swinging about a root on the head, Bertails §2.2), or
    /// `guides.reach_m` when that is farther.
    pub fn reach_m(&self) -> f32 {
        let swing = self.max_length_m() + 0.5 * self.head_size_m();
        self.guides.reach_m.map_or(swing, |r| r.max(swing))
    }
}
