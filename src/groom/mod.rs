//! Captured grooms: strands from TressFX `.tfx`, cyHair `.hair`, PLY `.ply` and USC-HairSalon
//! `.data` files turned into wisp's hair model (guides, render-strand layout), placed on wisp's
//! head.
//!
//! ```text
//! read      input::strand_file             strands in the file's units (several files: one groom)
//! drop      strands::keep_strands          zero-length strands (counted in the report)
//! place     place::place_on_head           scale, 0°/180° turn and offset (fit::fit_to_head):
//!                                          roots on the head, hair outside; far roots refused
//! resample  build::resample_placed         links + 1 guide points, `strands.points` render points
//! cluster   cluster::cluster               k-means on root + shape, grid-accelerated (no O(N²))
//! guides    build::pick_guides             3 strands of each wisp, spanning its roots
//! offsets   interp::rest_offsets_of        each strand's own departure from its wisp's blend
//! densify   densify::densify               a sparse groom: render strands added among its
//!                                          guides up to a head's density (`densify.rs`)
//! style     style::groom_style             the base style with the groom's counts and lengths
//! ```
//!
//! A captured groom becomes a [`Groom`]: a [`Hairstyle`] (the base style's head, fibre and
//! dynamics, with counts and lengths set from the file, so the budget, the map sizing and the
//! camera work unchanged), the guides and the layout. At rest, interpolation with the rest
//! offsets reproduces every strand's arc-length resampling of the file; [`GroomReport`] says how
//! far that is from the file's polylines ([`rest_distance_m`]).
//!
//! Wisps per strand: [`STRANDS_PER_WISP`] = 25 (Bertails 2005 §5: 134 wisps for 3,350
//! strands), capped at [`MAX_AUTO_WISPS`] wisps so the simulation costs at most about 3× the
//! `smooth` preset's 134 wisps: the rest pose is exact whatever the count (offsets), so more
//! wisps only buy finer motion at a linear simulation cost. A sparse groom (fewer strands than
//! a head of hair renders, [`density_of`]) is clustered into wisps of about 3 strands instead,
//! and render strands are interpolated among them ([`densify`](densify::densify)).
//!
//! The light map holds the groom wherever it swings: its style's `guides.reach_m` is the
//! farthest a placed root plus its strand's length reaches from the head's centre, which the
//! map's span holds when it is farther than the head's largest radius plus the longest strand
//! (roots off the ellipsoid).

mod as_authored;
mod build;
pub mod cluster;
pub mod densify;
mod error;
pub mod fit;
mod place;
mod polyline;
mod rest_distance;
mod root_sphere;
mod strands;
mod style;
mod synthetic;
mod synthetic_fur;

pub use as_authored::{AuthoredFrame, guess_unit_m};
pub use densify::{Density, density_of};
pub use error::GroomError;
pub use fit::Placement;
pub use place::{ROOT_TOLERANCE_M, ROOTS_OFF_HEAD_SHARE};
pub use polyline::{arc_length, resample_by_arc_length};
pub use rest_distance::rest_distance_m;
pub use synthetic::synthetic_strands;
pub use synthetic_fur::{FUR_POINTS, synthetic_fur};

use crate::hairstyle::{GuideSet, Hairstyle, StrandLayout};
use crate::input::strand_file::load_strand_file;
use crate::input::strands::StrandFile;
use glam::Vec3;
use std::path::Path;

/// Render strands per wisp aimed at (Bertails 2005 §5: 3,350 strands in 134 wisps).
pub const STRANDS_PER_WISP: usize = 25;
/// Most wisps chosen automatically (3× the `smooth` preset's 134, rounded).
pub const MAX_AUTO_WISPS: usize = 400;
/// How a groom is imported.
#[derive(Clone, Debug, Default)]
pub struct GroomOptions {
    /// Number of wisps (default: strands / [`STRANDS_PER_WISP`], at most [`MAX_AUTO_WISPS`]).
    pub wisps: Option<usize>,
    /// Turn of the groom about +Y in radians before the fit (default: 0 or π, whichever puts
    /// most hair behind the head).
    pub yaw_rad: Option<f32>,
    /// Keep the groom where it was authored instead of fitting it onto the head: only scaled
    /// to metres, roots pinned in place (see `as_authored.rs`).
    pub as_authored: bool,
    /// Metres per file unit for a groom kept as authored (default: guessed from its size).
    pub unit_m: Option<f32>,
    /// A groom kept as authored on its own character: where the character's head is
    /// (default `None`: no character, the file's coordinates are the world's).
    pub authored_on: Option<AuthoredFrame>,
}

/// Figures of an import.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GroomReport {
    /// Strands in the files.
    pub strands_read: usize,
    /// Strands dropped: fewer than 2 points, or shorter than a millionth of the longest.
    pub strands_dropped: usize,
    pub wisps: usize,
    pub placement: Option<Placement>,
    /// The placement is the sphere through the roots (a partial groom: the fit onto the head
    /// shrank it, see `place.rs`).
    pub placed_by_root_sphere: bool,
    /// Mean and largest root distance from the head surface after the fit, metres.
    pub root_distance_mean_m: f32,
    pub root_distance_max_m: f32,
    /// Distance between the interpolated rest pose and the file's strands (both ways: rest
    /// points to the file's polyline and file vertices to the rest polyline), metres.
    pub rest_distance_mean_m: f32,
    pub rest_distance_max_m: f32,
    /// Render strands interpolated among the guides of a sparse groom (0 for a dense one).
    pub strands_added: usize,
    /// Seconds spent clustering (a measurement, for the notes; never asserted).
    pub cluster_s: f64,
    /// Kept as authored: the metres per file unit, and whether they were guessed.
    pub as_authored_unit_m: Option<(f32, bool)>,
}

/// A captured groom ready for the engine.
#[derive(Clone, Debug)]
pub struct Groom {
    pub style: Hairstyle,
    pub guides: GuideSet,
    pub layout: StrandLayout,
    pub report: GroomReport,
}

/// Loads the strand files at `paths` as one groom on `base`'s head.
pub fn load_groom(
    paths: &[&Path],
    base: &Hairstyle,
    opts: &GroomOptions,
) -> Result<Groom, GroomError> {
    let mut files = Vec::with_capacity(paths.len());
    for p in paths {
        files.push((p.display().to_string(), load_strand_file(p)?));
    }
    build_groom(&files, base, opts)
}

/// Builds a groom from parsed strand files (name, strands): see the module doc.
pub fn build_groom(
    files: &[(String, StrandFile)],
    base: &Hairstyle,
    opts: &GroomOptions,
) -> Result<Groom, GroomError> {
    let names = files
        .iter()
        .map(|f| f.0.as_str())
        .collect::<Vec<_>>()
        .join(", ");
    let invalid = |rule: String| GroomError::Invalid {
        files: names.clone(),
        rule,
    };
    let (kept, read) = strands::keep_strands(files, &names)?;
    let count = kept.len();
    let radii = Vec3::from(base.head.radii_m);
    let (on_head, authored_unit) = if opts.as_authored {
        let (on_head, unit, guessed) =
            as_authored::as_authored(&kept, opts.unit_m, opts.authored_on);
        (on_head, Some((unit, guessed)))
    } else {
        let on_head = place::place_on_head(&kept, files, radii, opts.yaw_rad, &names)?;
        (on_head, None)
    };
    let placement = on_head.placement;

    let ppg = base.guides.links as usize + 1;
    let n = base.strands.points as usize;
    let resampled = build::resample_placed(&kept, &placement, ppg, n);
    let longest_m = longest_placed_m(&resampled, &kept, files, placement.scale, authored_unit)
        .map_err(&invalid)?;

    let roots: Vec<Vec3> = resampled.render.chunks(n).map(|p| p[0]).collect();
    let density = density_of(&roots, base);
    let per_wisp = match density {
        Some(_) => cluster::MIN_WISP_STRANDS,
        None => STRANDS_PER_WISP,
    };
    let want = opts
        .wisps
        .unwrap_or_else(|| count.div_ceil(per_wisp).min(MAX_AUTO_WISPS));
    // Roots kept as authored are not on the head: their normal points away from the groom's
    // middle (out of an animal's body, for fur).
    let centre = authored_unit.map(|_| {
        let sum: Vec3 = resampled.guide.chunks(resampled.ppg).map(|g| g[0]).sum();
        sum / count.max(1) as f32
    });
    let (guides, mut layout, wisp_of, cluster_s) =
        cluster_into_wisps(&resampled, want, radii, centre, base.strands.tip_taper);
    let overflow = |v: &Vec3| !v.is_finite();
    let bad_link = |l: &f32| !(l.is_finite() && *l > 0.0);
    if guides.rest.iter().any(overflow)
        || layout.rest_offset.iter().any(overflow)
        || guides.link_length_m.iter().any(bad_link)
    {
        return Err(invalid(format!(
            "the strands' coordinates overflow once scaled onto the head (scale {}): some coordinates are near the largest 32-bit float",
            placement.scale
        )));
    }
    let wisps = layout.wisp_guides.len();
    let shape = style::GroomShape {
        wisps,
        render_strands: density.map_or(count, |d| d.render_strands),
        scalp_share: density.map(|d| d.scalp_share),
        longest_m,
        reach_m: reach_m(&resampled),
    };
    let mut style = style::groom_style(base, files, &shape).map_err(&invalid)?;
    if authored_unit.is_some() {
        // No head under a groom kept as authored: the head ellipsoid, a collider at the
        // origin, shrinks to the smallest the hairstyle allows.
        style.head.radii_m = [crate::hairstyle::MIN_HEAD_RADIUS_M; 3];
    }

    let mut report = GroomReport {
        strands_read: read,
        strands_dropped: read - count,
        wisps,
        placement: Some(placement),
        placed_by_root_sphere: on_head.from_root_sphere,
        root_distance_mean_m: on_head.root_distance_m.iter().sum::<f32>() / count as f32,
        root_distance_max_m: on_head.worst_m,
        cluster_s,
        as_authored_unit_m: authored_unit,
        ..Default::default()
    };
    let placed: Vec<Vec<Vec3>> = kept
        .iter()
        .map(|k| k.points.iter().map(|p| placement.apply(*p)).collect())
        .collect();
    (report.rest_distance_mean_m, report.rest_distance_max_m) =
        rest_distance_m(&guides, &layout, &placed);
    if let Some(d) = density {
        report.strands_added = d.render_strands - count;
        let extra = report.strands_added;
        densify::densify(&resampled, &wisp_of, &guides, &mut layout, extra, base.seed);
    }
    Ok(Groom {
        style,
        guides,
        layout,
        report,
    })
}

/// The longest placed render strand, metres, after checking that every resampled point is
/// finite (coordinates may overflow once scaled by `scale`) and that it is more than 0 and at
/// most 2 m. `authored_unit` is the unit of a groom kept as authored (and whether it was
/// guessed); `None` for a groom fitted to the head. The error is the rule broken.
fn longest_placed_m(
    s: &build::Resampled,
    kept: &[strands::Kept],
    files: &[(String, StrandFile)],
    scale: f32,
    authored_unit: Option<(f32, bool)>,
) -> Result<f32, String> {
    if let Some(i) = s.render.iter().position(|p| !p.is_finite()) {
        let k = kept[i / s.n];
        return Err(format!(
            "{}: strand {}: its coordinates overflow once scaled onto the head (scale {scale})",
            files[k.file].0, k.strand
        ));
    }
    let longest_m = s.render.chunks(s.n).map(arc_length).fold(0.0f32, f32::max);
    if longest_m > 0.0 && longest_m <= 2.0 {
        return Ok(longest_m);
    }
    let in_file = kept
        .iter()
        .map(|k| arc_length(k.points))
        .fold(0.0f32, f32::max);
    Err(match authored_unit {
        Some((unit, guessed)) => format!(
            "kept as authored at {unit:.3e} m per file unit ({}), the longest strand \
             ({in_file:.3e} file units) is {longest_m:.3e} m: it must be more than 0 and at most \
             2 m; give --groom-unit-m the metres one file unit stands for",
            if guessed {
                "guessed from the groom's size"
            } else {
                "--groom-unit-m"
            }
        ),
        None if longest_m > 2.0 => format!(
            "the longest strand is {longest_m:.3} m once fitted to the head (scale {scale:.3e}): \
             at most 2 m"
        ),
        None => format!(
            "the fit onto the head collapsed the groom: scaled by {scale:.3e}, its longest strand \
             ({in_file:.3e} file units) comes out {longest_m:.3e} m long, and hair must be longer \
             than 0: its roots lie in a line or a point, or its coordinates are too large for \
             32-bit precision; --groom-as-authored keeps a groom where it was authored"
        ),
    })
}

/// The farthest the strands `s` reach from the head's centre, metres: a root's distance plus
/// its strand's length, the most of any strand (where the strand can swing to about its root).
fn reach_m(s: &build::Resampled) -> f32 {
    s.render
        .chunks(s.n)
        .map(|p| p[0].length() + arc_length(p))
        .fold(0.0f32, f32::max)
}

/// The strands clustered into about `want` wisps (on their guide resampling, see [`cluster`])
/// and the hair model built on them, with each strand's wisp and the seconds spent
/// clustering. Guide roots get the normal of the head ellipsoid of semi-axes `radii`, or the
/// direction from `centre` when there is one.
fn cluster_into_wisps(
    s: &build::Resampled,
    want: usize,
    radii: Vec3,
    centre: Option<Vec3>,
    tip_taper: f32,
) -> (GuideSet, StrandLayout, Vec<u32>, f64) {
    let features: Vec<cluster::Feature> = s.guide.chunks(s.ppg).map(build::feature_of).collect();
    let clustering = std::time::Instant::now();
    let wisp_of = cluster::cluster(&features, want.max(1));
    let cluster_s = clustering.elapsed().as_secs_f64();
    let normal = |p: Vec3| match centre {
        Some(c) => (p - c).normalize_or(Vec3::Y),
        None => (p / (radii * radii)).normalize_or(Vec3::Y),
    };
    let (guides, layout) = build::build_model(s, &wisp_of, normal, tip_taper);
    (guides, layout, wisp_of, cluster_s)
}
