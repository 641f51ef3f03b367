//! The hair's flags: a hairstyle (an embedded preset or a JSON file), or a captured groom
//! (TressFX `.tfx`, cyHair `.hair`, PLY `.ply`, USC-HairSalon `.data` files) with the hairstyle
//! whose head, fibre and dynamics it takes.
//!
//! An imported groom is placed on the hairstyle's own head ellipsoid, not on one fitted to a
//! character's head mesh: a mesh's bounding box is a poor scalp for a human groom (the TressFX
//! ponytail on RobotExpressive's boxy head: 19% of roots over 30 mm off). The roots are then
//! checked on the drawn head mesh ([`HairArgs::check_roots_on_head`]).

use crate::cli::{AppError, parse_finite_f32, parse_positive_f32, printable};
use glam::Vec3;
use std::path::Path;
use wisp::groom::{Groom, GroomError, GroomOptions, Placement};
use wisp::hairstyle::{GuideSet, Hairstyle, HairstyleError, StrandLayout};
use wisp::motion::Motion;

/// Embedded hairstyle presets, by `--hairstyle` name.
pub const PRESETS: [&str; 3] = ["smooth", "curly", "dense"];

/// Hair built elsewhere than from a hairstyle's parameters: an imported groom's guides and
/// layout (`None`: generate from the hairstyle).
pub type ImportedHair = Option<(GuideSet, StrandLayout)>;

#[derive(clap::Args, Debug, Clone)]
#[command(next_help_heading = "Hair")]
pub struct HairArgs {
    /// smooth|curly|dense or JSON; .tfx/.hair/.ply/.data groom files
    #[arg(
        long,
        value_name = "STYLE",
        default_value = "smooth",
        value_delimiter = ','
    )]
    pub hairstyle: Vec<String>,
    /// Wisps of an imported groom [default: one per 25 strands, at most 400]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub groom_wisps: Option<u32>,
    /// Imported groom's turn about the vertical, degrees [default: 0 or 180]
    #[arg(long, value_name = "DEG", value_parser = parse_finite_f32, allow_hyphen_values = true)]
    pub groom_turn_deg: Option<f32>,
    /// Keep an imported groom where it was authored (fur, a groom without its head): roots
    /// pinned in place (with --animation, each to the nearest bone of that file's character,
    /// which the groom was authored on), not fitted onto a head
    #[arg(long)]
    pub groom_as_authored: bool,
    /// Metres per unit of a groom kept as authored [default: guessed from its size]
    #[arg(long, value_name = "M", value_parser = parse_positive_f32, requires = "groom_as_authored")]
    pub groom_unit_m: Option<f32>,
}

impl HairArgs {
    /// The hairstyle, and the hair of an imported groom when `--hairstyle` names strand files
    /// (the import's figures go to stderr).
    /// `authored_on`: where the character of a groom kept as authored has its head, when
    /// there is one (`--groom-as-authored` with `--animation`). Also returns the metres per
    /// unit of a groom kept as authored. Groom meshes (`.tfxmesh`) are left to
    /// [`super::groom_mesh`].
    pub fn load(
        &self,
        authored_on: Option<wisp::groom::AuthoredFrame>,
    ) -> Result<(Hairstyle, ImportedHair, Option<f32>), AppError> {
        let (files, styles): (Vec<&String>, Vec<&String>) = self
            .hairstyle
            .iter()
            .filter(|a| !super::groom_mesh::is_groom_mesh(a))
            .partition(|a| wisp::input::strand_file::is_strand_file_name(a));
        if styles.len() > 1 || (styles.is_empty() && files.is_empty()) {
            return Err(AppError::input(anyhow::anyhow!(
                "--hairstyle {}: give one preset or JSON hairstyle, plus any number of .tfx/.hair/.ply/.data strand files",
                self.hairstyle.join(",")
            )));
        }
        let source = styles.first().map_or("smooth", |s| s.as_str());
        let base = load_hairstyle(source)?;
        if files.is_empty() {
            warn_advisories(source, &base);
            return Ok((base, None, None));
        }
        let opts = GroomOptions {
            wisps: self.groom_wisps.map(|w| w as usize),
            yaw_rad: self.groom_turn_deg.map(f32::to_radians),
            as_authored: self.groom_as_authored,
            unit_m: self.groom_unit_m,
            authored_on,
        };
        let paths: Vec<&Path> = files.iter().map(|f| Path::new(f.as_str())).collect();
        let started = std::time::Instant::now();
        let groom = wisp::groom::load_groom(&paths, &base, &opts).map_err(|e| match e {
            GroomError::RootsOffHead { .. } | GroomError::NotOnAHead { .. } => AppError::input(anyhow::anyhow!(
                "{e}; a groom that is not a scalp's (fur, a groom made on another head) renders \
                 where it was authored with --groom-as-authored"
            )),
            e => AppError::input(e),
        })?;
        report_import(&groom, started.elapsed().as_secs_f64());
        // What the groom keeps of the hairstyle (not its curls: an imported groom has its own
        // shape) is checked as it will be drawn.
        warn_advisories(source, &groom.style);
        let unit = groom.report.as_authored_unit_m.map(|(unit, _)| unit);
        Ok((groom.style, Some((groom.guides, groom.layout)), unit))
    }

    /// Refuses (exit code 2) a groom whose roots do not lie on the character's head mesh
    /// (`wisp::motion::scalp`), naming the fit and the flags that change it; `animation` names
    /// the file the motion came from.
    pub fn check_roots_on_head(
        &self,
        style: &Hairstyle,
        hair: &ImportedHair,
        motion: &Motion,
        animation: &str,
    ) -> Result<(), AppError> {
        let roots = match hair {
            Some((guides, _)) => wisp::engine::roots_of_guides_on_head(guides, style, motion),
            None => wisp::engine::roots_on_head(style, motion),
        };
        let Some(r) = roots else {
            return Ok(());
        };
        if r.on_head() {
            return Ok(());
        }
        let fit = motion.fit();
        Err(AppError::input(anyhow::anyhow!(
            "{}: the hairstyle's roots do not lie on the head mesh of {}: the median root is \
             {:.3} m from it, the farthest {:.3} m ({} of {} roots within the tolerance of \
             {:.3} m); the head was fitted by {:?} (scale {}, offset \
             {},{},{} m); give the fit with --head-scale S --head-offset X,Y,Z",
            printable(&self.hairstyle.join(",")),
            animation,
            r.median_m,
            r.worst_m,
            r.near,
            r.roots,
            r.tolerance_m,
            motion.fit_method(),
            fit.scale,
            fit.offset_m.x,
            fit.offset_m.y,
            fit.offset_m.z,
        )))
    }
}

/// The import's figures on stderr: strands kept and dropped, wisps, time, and where the groom
/// was placed on the head (or kept as authored).
fn report_import(groom: &Groom, seconds: f64) {
    let r = &groom.report;
    let p = r.placement.unwrap_or(Placement {
        scale: 1.0,
        yaw_rad: 0.0,
        offset_m: Vec3::ZERO,
        upright: glam::Quat::IDENTITY,
    });
    let placed = match r.as_authored_unit_m {
        Some((unit, guessed)) => format!(
            "kept as authored at {unit} m a unit{}",
            if guessed {
                " (guessed from its size; --groom-unit-m gives it)"
            } else {
                ""
            }
        ),
        None => format!(
            "placed on the head{} at scale {:.5}, turn {:.0}°, roots {:.1} mm from the scalp \
             (mean, max {:.1})",
            if r.placed_by_root_sphere {
                " by the sphere through its roots (a partial groom)"
            } else {
                ""
            },
            p.scale,
            p.yaw_rad.to_degrees(),
            r.root_distance_mean_m * 1e3,
            r.root_distance_max_m * 1e3,
        ),
    };
    eprintln!(
        "wisp: groom {}: {} strands ({} dropped: zero length) in {} wisps, imported in {:.2} s; \
         {placed}; rest pose vs file: mean {:.3} mm, max {:.3} mm",
        printable(&groom.style.name),
        r.strands_read - r.strands_dropped,
        r.strands_dropped,
        r.wisps,
        seconds,
        r.rest_distance_mean_m * 1e3,
        r.rest_distance_max_m * 1e3,
    );
}

/// A preset by name, else a hairstyle file; a missing file that is no preset says which
/// presets exist.
pub fn load_hairstyle(arg: &str) -> Result<Hairstyle, AppError> {
    match arg {
        "smooth" => return Ok(Hairstyle::default_smooth()),
        "curly" => return Ok(Hairstyle::default_curly()),
        "dense" => return Ok(Hairstyle::dense()),
        _ => {}
    }
    let path = Path::new(arg);
    // A file of another hair format would be read as JSON and fail on its first binary byte.
    if let Some(ext) = path.extension().and_then(|e| e.to_str())
        && !ext.eq_ignore_ascii_case("json")
    {
        return Err(AppError::input(anyhow::anyhow!(
            "--hairstyle {arg}: unsupported hair format .{ext}; wisp reads .json, .tfx, .hair, \
             .ply, .data (hairstyle JSON; TressFX, cyHair, PLY and USC-HairSalon strands)"
        )));
    }
    Hairstyle::load(path).map_err(|e| match e {
        HairstyleError::Io { .. } if !path.exists() => AppError::input(anyhow::anyhow!(
            "--hairstyle {arg}: not a preset ({}) and no such file",
            PRESETS.join(", ")
        )),
        e => AppError::input(e),
    })
}

/// Prints the hairstyle's advisories (`Hairstyle::advisories`: what it may ask for but is
/// measured to render wrongly) as warnings naming `source`, the file it came from.
fn warn_advisories(source: &str, style: &Hairstyle) {
    for a in style.advisories() {
        eprintln!(
            "wisp: warning: {source}: field `{}`: {}",
            a.field, a.message
        );
    }
}
