//! The rules of a hairstyle ([`Hairstyle::validate`]): every field in its range, and the sizes
//! the whole style implies (render strands, render points) under the crate's limits, so a
//! hostile file cannot make the engine allocate gigabytes or divide by a denormal. A refusal is
//! the dotted field path (`wisps.count`, `head.radii_m[0]`) and the rule, with the value
//! found; the loaders add the file name.
//!
//! The rules run in the order of the file's sections (head, scalp, wisps, guides, strands,
//! curl, fiber, dynamics), so the first broken field is reported.

use super::spec::Hairstyle;

/// Upper bounds of single fields. They are absolute limits; what a whole run may allocate is
/// checked against the memory budget (`wisp::budget`), which the product of these can exceed.
pub const MAX_WISPS: u32 = 100_000;
pub const MAX_STRANDS: u64 = 2_000_000;
pub const MAX_RENDER_POINTS: u64 = 40_000_000;
pub const MAX_GUIDE_LINKS: u32 = 256;
/// Smallest scalp polar angle in degrees. Roots come from a Fibonacci lattice grown until the
/// scalp cap holds enough points; a cap of 5° is 0.19% of the sphere (100,000 wisps need a
/// lattice of about 50 M points, a few seconds), while a cap of 1e-30° never holds one and
/// the lattice would grow without end.
pub const MIN_SCALP_POLAR_DEG: f32 = 5.0;
/// Shortest wave or curl period in metres. Phases are 2π·s / period: a denormal period makes
/// them infinite and the strands NaN (blank frames); real curls are 5 mm and longer.
pub const MIN_PERIOD_M: f32 = 0.001;
/// Smallest head semi-axis in metres. The hair model works at millimetres: roots sit on wisp
/// layers 2–8 mm above the scalp and collisions keep a 1 mm margin, so a head smaller than
/// 1 cm would be a point inside its own hair (at 1e-30 m the scalp area is 0, the strand
/// spacing 0 and the map 1024³).
pub const MIN_HEAD_RADIUS_M: f32 = 0.01;

/// A rule's outcome: `Err((field path, rule))` when broken.
type Rule = Result<(), (String, String)>;

impl Hairstyle {
    /// Checks every rule; the error is (field path, rule).
    pub fn validate(&self) -> Result<(), (String, String)> {
        self.check_head_and_scalp()?;
        let strands = self.check_wisps()?;
        self.check_guides()?;
        self.check_strands(strands)?;
        self.check_curl()?;
        self.fiber
            .validate()
            .map_err(|rule| field_of("fiber", rule))?;
        self.dynamics
            .validate()
            .map_err(|rule| field_of("dynamics", rule))?;
        Ok(())
    }

    /// `head.radii_m` (see [`MIN_HEAD_RADIUS_M`]) and the scalp's polar limits.
    fn check_head_and_scalp(&self) -> Rule {
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
        )
    }

    /// The wisps' count, radius and strands, and the render strands they make (returned).
    fn check_wisps(&self) -> Result<u64, (String, String)> {
        if self.wisps.count == 0 || self.wisps.count > MAX_WISPS {
            bad(
                "wisps.count",
                format!("must be in [1, {MAX_WISPS}] (got {})", self.wisps.count),
            )?;
        }
        in_range("wisps.radius_m", self.wisps.radius_m, 0.0, 0.1, true)?;
        if self.wisps.strands_per_wisp == 0 {
            bad("wisps.strands_per_wisp", "must be >= 1 (got 0)".into())?;
        }
        let strands = self.wisps.count as u64 * self.wisps.strands_per_wisp as u64;
        if strands > MAX_STRANDS {
            bad(
                "wisps.strands_per_wisp",
                format!(
                    "wisps.count x strands_per_wisp = {strands} render strands exceeds the limit {MAX_STRANDS}"
                ),
            )?;
        }
        Ok(strands)
    }

    /// The guides' links, length, length jitter and rest wave.
    fn check_guides(&self) -> Rule {
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
        match self.guides.reach_m {
            Some(r) => in_range("guides.reach_m", r, 0.0, 10.0, true),
            None => Ok(()),
        }
    }

    /// The render strands' points (with the `strands` render strands, under
    /// [`MAX_RENDER_POINTS`]), fibres, length variation and tip taper.
    fn check_strands(&self, strands: u64) -> Rule {
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
        in_range("strands.tip_taper", self.strands.tip_taper, 0.0, 1.0, false)
    }

    /// The curl's radius and, for a curl, its period (see [`MIN_PERIOD_M`]).
    fn check_curl(&self) -> Rule {
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
        Ok(())
    }
}

/// The rule `rule` broken at `field`.
fn bad(field: &str, rule: String) -> Rule {
    Err((field.to_string(), rule))
}

/// `v` must be finite and in `[lo, hi]` (`(lo, hi]` when `lo_open`).
fn in_range(field: &str, v: f32, lo: f32, hi: f32, lo_open: bool) -> Rule {
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

/// Splits "name must ..." from a sub-validator into ("prefix.name", "must ...").
fn field_of(prefix: &str, rule: String) -> (String, String) {
    match rule.split_once(' ') {
        Some((name, rest)) => (format!("{prefix}.{name}"), rest.to_string()),
        None => (prefix.to_string(), rule),
    }
}
