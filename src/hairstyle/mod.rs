//! Hairstyles: the JSON description (`hairstyles/*.json`), its validation, and the generated
//! hair model (guides in a rest pose, render-strand layout).
//!
//! A hairstyle is read with serde; every error names the file, the field path (for example
//! `wisps.count`) and the rule that failed. Sizes are bounded so that a hostile file cannot make
//! the engine allocate gigabytes.

mod advice;
pub mod dynamics;
mod generate;
mod model;

pub use advice::{Advisory, MAX_CURL_TURN_PER_SEGMENT_DEG};
pub use generate::{SplitMix64, generate};
pub use model::{GuideSet, StrandLayout};

use crate::fiber::FiberParams;
use crate::input::{self, ReadError};
pub use dynamics::SimParams;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The default hairstyle, embedded in the binary.
pub const SMOOTH_JSON: &str = include_str!("../../hairstyles/smooth.json");
/// The curly preset, embedded too.
pub const CURLY_JSON: &str = include_str!("../../hairstyles/curly.json");

/// Upper bounds of single fields. They are absolute limits; what a whole run may allocate is
/// checked against the memory budget (`wisp::budget`), which the product of these can exceed.
pub const MAX_WISPS: u32 = 100_000;
pub const MAX_STRANDS: u64 = 2_000_000;
pub const MAX_RENDER_POINTS: u64 = 40_000_000;
pub const MAX_GUIDE_LINKS: u32 = 256;
/// Smallest scalp polar angle in degrees. Roots come from a Fibonacci lattice grown until the
/// scalp cap holds enough points; a cap of 5° is 0.19% of the sphere (100,000 wisps need a
/// lattice of about 50 M points, a few seconds), while 1e-30° never held one (a hang).
pub const MIN_SCALP_POLAR_DEG: f32 = 5.0;
/// Shortest wave or curl period in metres. Phases are 2π·s / period: a denormal period made
/// them infinite and the strands NaN (blank frames); real curls are 5 mm and longer.
pub const MIN_PERIOD_M: f32 = 0.001;
/// Largest hairstyle file read, in bytes (a hairstyle is a few dozen numbers; the presets are
/// about 1 KB).
pub const MAX_FILE_BYTES: u64 = 1 << 20;
/// Smallest head semi-axis in metres. The hair model works at millimetres: roots sit on wisp
/// layers 2–8 mm above the scalp and collisions keep a 1 mm margin, so a head smaller than
/// 1 cm would be a point inside its own hair (at 1e-30 m the scalp area was 0, the strand
/// spacing 0 and the map 1024³).
pub const MIN_HEAD_RADIUS_M: f32 = 0.01;

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

/// Why a hairstyle could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum HairstyleError {
    /// The file could not be read (missing, not a regular file, over [`MAX_FILE_BYTES`]).
    #[error("{file}: {error}")]
    Io { file: String, error: ReadError },
    #[error("{file}: field `{field}`: {message}")]
    Parse {
        file: String,
        field: String,
        message: String,
    },
    #[error("{file}: field `{field}`: {rule}")]
    Invalid {
        file: String,
        field: String,
        rule: String,
    },
}

impl Hairstyle {
    /// Reads and validates a hairstyle file (at most [`MAX_FILE_BYTES`], UTF-8, a leading
    /// byte-order mark is skipped).
    pub fn load(path: &Path) -> Result<Self, HairstyleError> {
        let file = path.display().to_string();
        let bytes =
            input::read_capped(path, MAX_FILE_BYTES, "a hairstyle file").map_err(|error| {
                HairstyleError::Io {
                    file: file.clone(),
                    error,
                }
            })?;
        Self::from_bytes(&bytes, &file)
    }

    /// Parses and validates the bytes of a hairstyle file; `file` names it in errors.
    pub fn from_bytes(bytes: &[u8], file: &str) -> Result<Self, HairstyleError> {
        let text = input::json::decode_text(bytes).map_err(|e| HairstyleError::Parse {
            file: file.to_string(),
            field: e.field,
            message: e.message,
        })?;
        Self::from_json(text, file)
    }

    /// The embedded default (`smooth`).
    pub fn default_smooth() -> Self {
        Self::from_json(SMOOTH_JSON, "<embedded smooth.json>").expect("embedded hairstyle is valid")
    }

    /// The `dense` preset, generated from `smooth` (no file): Bertails 2005's scale of one
    /// fibre per render strand, 653 render strands per wisp (87,502 strands) of 14 points
    /// (1.14 M segments). The heavy scene of the speed benchmarks (issue 12).
    pub fn dense() -> Self {
        let mut style = Self::default_smooth();
        style.name = "dense".into();
        style.wisps.strands_per_wisp = 653;
        style.strands.points = 14;
        style.strands.fibers_per_strand = 1.0;
        style
            .validate()
            .map_err(|(field, rule)| format!("{field}: {rule}"))
            .expect("the dense preset is valid");
        style
    }

    /// The embedded `curly` preset.
    pub fn default_curly() -> Self {
        Self::from_json(CURLY_JSON, "<embedded curly.json>").expect("embedded hairstyle is valid")
    }

    /// Parses and validates JSON text; `file` names the source in errors. Parsing is strict
    /// ([`input::json::from_str`]): no array for an object, no number beyond `f32`, no text
    /// after the object.
    pub fn from_json(text: &str, file: &str) -> Result<Self, HairstyleError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let style: Hairstyle = input::json::from_str(text).map_err(|e| HairstyleError::Parse {
            file: file.to_string(),
            field: e.field,
            message: e.message,
        })?;
        style
            .validate()
            .map_err(|(field, rule)| HairstyleError::Invalid {
                file: file.to_string(),
                field,
                rule,
            })?;
        Ok(style)
    }

    /// Checks every rule; the error is (field path, rule).
    pub fn validate(&self) -> Result<(), (String, String)> {
        fn bad(field: &str, rule: String) -> Result<(), (String, String)> {
            Err((field.to_string(), rule))
        }
        fn in_range(
            field: &str,
            v: f32,
            lo: f32,
            hi: f32,
            lo_open: bool,
        ) -> Result<(), (String, String)> {
            let ok = v.is_finite() && (if lo_open { v > lo } else { v >= lo }) && v <= hi;
            if ok {
                Ok(())
            } else {
                let open = if lo_open { "(" } else { "[" };
                bad(
                    field,
                    format!("must be a finite number in {open}{lo}, {hi}] (got {v})"),
                )
            }
        }
        for (i, r) in self.head.radii_m.iter().enumerate() {
            if !(r.is_finite() && (MIN_HEAD_RADIUS_M..=1.0).contains(r)) {
                return bad(
                    &format!("head.radii_m[{i}]"),
                    format!(
                        "must be a finite number in [{MIN_HEAD_RADIUS_M}, 1] metres (got {r}): the hair model \
                         works at millimetres (1 mm collision margin, 2-8 mm wisp layers), so a \
                         head needs at least 1 cm"
                    ),
                );
            }
        }
        in_range(
            "scalp.max_polar_deg",
            self.scalp.max_polar_deg,
            MIN_SCALP_POLAR_DEG,
            150.0,
            false,
        )?;
        in_range(
            "scalp.front_polar_deg",
            self.scalp.front_polar_deg,
            MIN_SCALP_POLAR_DEG,
            self.scalp.max_polar_deg.max(MIN_SCALP_POLAR_DEG),
            false,
        )?;
        if self.wisps.count == 0 || self.wisps.count > MAX_WISPS {
            return bad(
                "wisps.count",
                format!("must be in [1, {MAX_WISPS}] (got {})", self.wisps.count),
            );
        }
        in_range("wisps.radius_m", self.wisps.radius_m, 0.0, 0.1, true)?;
        if self.wisps.strands_per_wisp == 0 {
            return bad("wisps.strands_per_wisp", "must be >= 1 (got 0)".into());
        }
        let strands = self.wisps.count as u64 * self.wisps.strands_per_wisp as u64;
        if strands > MAX_STRANDS {
            return bad(
                "wisps.strands_per_wisp",
                format!(
                    "wisps.count x strands_per_wisp = {strands} render strands exceeds the limit {MAX_STRANDS}"
                ),
            );
        }
        if self.guides.links == 0 || self.guides.links > MAX_GUIDE_LINKS {
            return bad(
                "guides.links",
                format!(
                    "must be in [1, {MAX_GUIDE_LINKS}] (got {})",
                    self.guides.links
                ),
            );
        }
        in_range("guides.length_m", self.guides.length_m, 0.0, 2.0, true)?;
        in_range(
            "guides.length_jitter",
            self.guides.length_jitter,
            0.0,
            0.9,
            false,
        )?;
        in_range(
            "guides.wave_amplitude_m",
            self.guides.wave_amplitude_m,
            0.0,
            0.2,
            false,
        )?;
        in_range(
            "guides.wave_period_m",
            self.guides.wave_period_m,
            MIN_PERIOD_M,
            10.0,
            false,
        )?;
        if self.strands.points < 2 {
            return bad(
                "strands.points",
                format!("must be >= 2 (got {})", self.strands.points),
            );
        }
        let points = strands * self.strands.points as u64;
        if points > MAX_RENDER_POINTS {
            return bad(
                "strands.points",
                format!(
                    "{strands} strands x {} points = {points} exceeds the limit {MAX_RENDER_POINTS}",
                    self.strands.points
                ),
            );
        }
        in_range(
            "strands.fibers_per_strand",
            self.strands.fibers_per_strand,
            0.0,
            1.0e5,
            true,
        )?;
        in_range(
            "strands.length_variation",
            self.strands.length_variation,
            0.0,
            0.9,
            false,
        )?;
        in_range("strands.tip_taper", self.strands.tip_taper, 0.0, 1.0, false)?;
        in_range("curl.radius_m", self.curl.radius_m, 0.0, 0.1, false)?;
        if self.curl.radius_m > 0.0 {
            in_range(
                "curl.period_m",
                self.curl.period_m,
                MIN_PERIOD_M,
                10.0,
                false,
            )?;
        }
        self.fiber
            .validate()
            .map_err(|rule| field_of("fiber", rule))?;
        self.dynamics
            .validate()
            .map_err(|rule| field_of("dynamics", rule))?;
        Ok(())
    }

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
}

/// Splits "name must ..." from a sub-validator into ("prefix.name", "must ...").
fn field_of(prefix: &str, rule: String) -> (String, String) {
    match rule.split_once(' ') {
        Some((name, rest)) => (format!("{prefix}.{name}"), rest.to_string()),
        None => (prefix.to_string(), rule),
    }
}
