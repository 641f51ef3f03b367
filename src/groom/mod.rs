//! Captured grooms: strands from TressFX `.tfx` and cyHair `.hair` files turned into wisp's
//! hair model (guides, render-strand layout), placed on wisp's head.
//!
//! ```text
//! read      input::{tfx, cyhair}           strands in the file's units (several files: one groom)
//! drop      zero-length strands            (counted in the report)
//! place     fit::fit_to_head               scale, 0°/180° turn and offset: roots on the head, hair outside
//! resample  build::resample_by_arc_length  links + 1 guide points, `strands.points` render points
//! cluster   cluster::cluster               k-means on root + shape, grid-accelerated (no O(N²))
//! guides    build::pick_guides             3 strands of each wisp, spanning its roots
//! offsets   interp::rest_offsets_of        each strand's own departure from its wisp's blend
//! ```
//!
//! A captured groom becomes a [`Groom`]: a [`Hairstyle`] (the base style's head, fibre and
//! dynamics, with counts and lengths set from the file, so the budget, the map sizing and the
//! camera work unchanged), the guides and the layout. At rest, interpolation with the rest
//! offsets reproduces every strand's arc-length resampling of the file; [`GroomReport`] says how
//! far that is from the file's polylines.
//!
//! Wisps per strand: [`STRANDS_PER_WISP`] = 25 (Bertails 2005 §5: 134 wisps for 3,350
//! strands), capped at [`MAX_AUTO_WISPS`] wisps so the simulation costs at most about 3× the
//! `smooth` preset's 134 wisps: the rest pose is exact whatever the count (offsets), so more
//! wisps only buy finer motion at a linear simulation cost.

mod build;
pub mod cluster;
pub mod fit;
mod synthetic;

pub use build::{arc_length, resample_by_arc_length};
pub use fit::Placement;
pub use synthetic::synthetic_strands;

use crate::hairstyle::{CurlSpec, GuideSet, Hairstyle, MAX_STRANDS, StrandLayout};
use crate::input::strand_file::load_strand_file;
use crate::input::strands::{StrandFile, StrandFileError};
use crate::interp::{StrandGeometry, interpolate};
use glam::Vec3;
use rayon::prelude::*;
use std::path::Path;

/// Render strands per wisp aimed at (Bertails 2005 §5: 3,350 strands in 134 wisps).
pub const STRANDS_PER_WISP: usize = 25;
/// Most wisps chosen automatically (3× the `smooth` preset's 134, rounded).
pub const MAX_AUTO_WISPS: usize = 400;
/// Largest distance of a root from the head surface after the fit, metres. Real scalps are not
/// ellipsoids (about ±1 cm) and a ponytail's tie sits off the scalp; a groom made for another
/// head shape or in another orientation is off by many centimetres.
pub const ROOT_TOLERANCE_M: f32 = 0.03;
/// Share of roots allowed beyond [`ROOT_TOLERANCE_M`] (ties, hair growing off a bun).
pub const ROOTS_OFF_HEAD_SHARE: f32 = 0.1;

/// How a groom is imported.
#[derive(Clone, Debug, Default)]
pub struct GroomOptions {
    /// Number of wisps (default: strands / [`STRANDS_PER_WISP`], at most [`MAX_AUTO_WISPS`]).
    pub wisps: Option<usize>,
    /// Turn of the groom about +Y in radians before the fit (default: 0 or π, whichever puts
    /// most hair behind the head).
    pub yaw_rad: Option<f32>,
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
    /// Mean and largest root distance from the head surface after the fit, metres.
    pub root_distance_mean_m: f32,
    pub root_distance_max_m: f32,
    /// Distance between the interpolated rest pose and the file's strands (both ways: rest
    /// points to the file's polyline and file vertices to the rest polyline), metres.
    pub rest_distance_mean_m: f32,
    pub rest_distance_max_m: f32,
    /// Seconds spent clustering (a measurement, for the notes; never asserted).
    pub cluster_s: f64,
}

/// A captured groom ready for the engine.
#[derive(Clone, Debug)]
pub struct Groom {
    pub style: Hairstyle,
    pub guides: GuideSet,
    pub layout: StrandLayout,
    pub report: GroomReport,
}

/// Why a groom could not be imported.
#[derive(Debug, thiserror::Error)]
pub enum GroomError {
    #[error(transparent)]
    File(#[from] StrandFileError),
    #[error("{files}: {rule}")]
    Invalid { files: String, rule: String },
    #[error(
        "{file}: strand {strand}: its root is {distance_mm:.0} mm from the head surface after fitting the groom to the head (scale {scale:.4}, turn {yaw_deg:.0}°), and {share:.0}% of all roots are over {tolerance_mm:.0} mm: the groom's roots do not lie on a head (is it Y-up?)"
    )]
    RootsOffHead {
        file: String,
        strand: usize,
        distance_mm: f32,
        tolerance_mm: f32,
        share: f32,
        scale: f32,
        yaw_deg: f32,
    },
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
    // Keep strands with at least 2 points and a length above a millionth of the longest
    // (shorter ones are points at any scale: they vanish or underflow once placed); remember
    // their origin. A length that overflows means coordinates near the float limit.
    let mut longest_file = 0.0f32;
    for (name, file) in files {
        for (s, pts) in file.strands().enumerate() {
            let len = arc_length(pts);
            if !len.is_finite() {
                return Err(GroomError::Invalid {
                    files: name.clone(),
                    rule: format!(
                        "strand {s}: its length overflows (coordinates near the largest 32-bit float)"
                    ),
                });
            }
            longest_file = longest_file.max(len);
        }
    }
    let mut kept: Vec<(usize, usize, &[Vec3])> = Vec::new();
    let mut read = 0usize;
    for (f, (_, file)) in files.iter().enumerate() {
        for (s, pts) in file.strands().enumerate() {
            read += 1;
            if pts.len() >= 2 && arc_length(pts) > 1e-6 * longest_file {
                kept.push((f, s, pts));
            }
        }
    }
    let count = kept.len();
    if count < 3 {
        return Err(invalid(format!(
            "{count} strands of nonzero length ({read} read): a groom needs at least 3 (one wisp of 3 guides)"
        )));
    }
    if count as u64 > MAX_STRANDS {
        return Err(invalid(format!("{count} strands: at most {MAX_STRANDS}")));
    }

    // Place the groom on the head.
    let radii = Vec3::from(base.head.radii_m);
    let roots: Vec<Vec3> = kept.iter().map(|k| k.2[0]).collect();
    let yaw = opts.yaw_rad.unwrap_or_else(|| {
        let (sum, n) = kept.iter().fold((Vec3::ZERO, 0usize), |(s, n), k| {
            (s + k.2.iter().copied().sum::<Vec3>(), n + k.2.len())
        });
        fit::guess_yaw_rad(&roots, sum / n as f32)
    });
    // Samples along the strands for the fit's "hair outside the head" term: every vertex past
    // the root's link, at most about 50,000 in all (a strided subset of the strands).
    let stride = (kept.iter().map(|k| k.2.len()).sum::<usize>() / 50_000).max(1);
    let hair: Vec<Vec3> = kept
        .iter()
        .step_by(stride)
        .flat_map(|k| k.2.iter().skip(2).copied())
        .collect();
    let placement = fit::fit_to_head(&roots, &hair, yaw, radii).ok_or_else(|| {
        invalid("the roots cannot be fitted onto the head (all roots in one point?)".into())
    })?;
    let dist: Vec<f32> = roots
        .iter()
        .map(|r| fit::surface_distance_m(placement.apply(*r), radii))
        .collect();
    let off = dist.iter().filter(|d| **d > ROOT_TOLERANCE_M).count();
    let share = off as f32 / count as f32;
    let (worst, worst_d) = dist
        .iter()
        .enumerate()
        .fold((0, 0.0f32), |b, (i, d)| if *d > b.1 { (i, *d) } else { b });
    if share > ROOTS_OFF_HEAD_SHARE {
        let (f, s, _) = kept[worst];
        return Err(GroomError::RootsOffHead {
            file: files[f].0.clone(),
            strand: s,
            distance_mm: worst_d * 1000.0,
            tolerance_mm: ROOT_TOLERANCE_M * 1000.0,
            share: share * 100.0,
            scale: placement.scale,
            yaw_deg: placement.yaw_rad.to_degrees(),
        });
    }

    // Resample every strand, placed, for guides and for render strands.
    let ppg = base.guides.links as usize + 1;
    let n = base.strands.points as usize;
    let mut guide_pts = vec![Vec3::ZERO; count * ppg];
    let mut render_pts = vec![Vec3::ZERO; count * n];
    guide_pts
        .par_chunks_mut(ppg)
        .zip(render_pts.par_chunks_mut(n))
        .zip(kept.par_iter())
        .for_each(|((g, r), k)| {
            let placed: Vec<Vec3> = k.2.iter().map(|p| placement.apply(*p)).collect();
            build::resample_by_arc_length(&placed, g);
            build::resample_by_arc_length(&placed, r);
        });
    if let Some(i) = render_pts.iter().position(|p| !p.is_finite()) {
        let (f, s, _) = kept[i / n];
        return Err(invalid(format!(
            "{}: strand {s}: its coordinates overflow once scaled onto the head (scale {})",
            files[f].0, placement.scale
        )));
    }
    let longest_m = render_pts.chunks(n).map(arc_length).fold(0.0f32, f32::max);
    if !(longest_m > 0.0 && longest_m <= 2.0) {
        return Err(invalid(format!(
            "the longest strand is {longest_m:.2} m once fitted to the head: at most 2 m"
        )));
    }

    // Wisps.
    let want = opts
        .wisps
        .unwrap_or_else(|| count.div_ceil(STRANDS_PER_WISP).min(MAX_AUTO_WISPS));
    let features: Vec<cluster::Feature> = guide_pts.chunks(ppg).map(build::feature_of).collect();
    let clustering = std::time::Instant::now();
    let wisp_of = cluster::cluster(&features, want.max(1));
    let cluster_s = clustering.elapsed().as_secs_f64();
    let normal = |p: Vec3| (p / (radii * radii)).normalize_or(Vec3::Y);
    let (guides, layout) = build::build_model(
        &guide_pts,
        ppg,
        &render_pts,
        n,
        &wisp_of,
        normal,
        base.strands.tip_taper,
    );
    let wisps = layout.wisp_guides.len();
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

    // The style: base head, fibre and dynamics; counts and lengths of the groom.
    let mut style = base.clone();
    style.name = files
        .iter()
        .map(|(name, _)| {
            Path::new(name)
                .file_stem()
                .map_or(name.clone(), |s| s.to_string_lossy().into_owned())
        })
        .collect::<Vec<_>>()
        .join("+");
    let base_strands = base.wisps.count as f32 * base.wisps.strands_per_wisp as f32;
    style.wisps.count = wisps as u32;
    style.wisps.strands_per_wisp = count.div_ceil(wisps) as u32;
    style.guides.length_m = longest_m;
    style.guides.length_jitter = 0.0;
    style.guides.wave_amplitude_m = 0.0;
    style.curl = CurlSpec::default();
    // The same number of real fibres as the base style: a captured strand stands for fewer
    // fibres when the file has more strands.
    style.strands.fibers_per_strand = base.strands.fibers_per_strand * base_strands / count as f32;
    style
        .validate()
        .map_err(|(field, rule)| invalid(format!("the imported style's `{field}` {rule}")))?;

    let mut report = GroomReport {
        strands_read: read,
        strands_dropped: read - count,
        wisps,
        placement: Some(placement),
        root_distance_mean_m: dist.iter().sum::<f32>() / count as f32,
        root_distance_max_m: worst_d,
        cluster_s,
        ..Default::default()
    };
    let placed: Vec<Vec<Vec3>> = kept
        .iter()
        .map(|k| k.2.iter().map(|p| placement.apply(*p)).collect())
        .collect();
    (report.rest_distance_mean_m, report.rest_distance_max_m) =
        rest_distance_m(&guides, &layout, &placed);
    Ok(Groom {
        style,
        guides,
        layout,
        report,
    })
}

/// Mean and largest distance between the rest-pose render strands (interpolated from the rest
/// guides with the rest offsets) and the placed file strands `files_m` (head frame, metres):
/// every rest point to the file's polyline and every file vertex to the rest polyline.
pub fn rest_distance_m(
    guides: &GuideSet,
    layout: &StrandLayout,
    files_m: &[Vec<Vec3>],
) -> (f32, f32) {
    let mut geo = StrandGeometry::default();
    interpolate(guides, layout, &CurlSpec::default(), &guides.rest, &mut geo);
    let n = layout.points_per_strand;
    let (sum, max, count) = files_m
        .par_iter()
        .enumerate()
        .map(|(s, file)| {
            let rest = &geo.positions[s * n..(s + 1) * n];
            let mut sum = 0.0f64;
            let mut max = 0.0f32;
            for (a, b) in [(rest, file.as_slice()), (file.as_slice(), rest)] {
                for p in a {
                    let d = point_polyline_m(*p, b);
                    sum += d as f64;
                    max = max.max(d);
                }
            }
            (sum, max, rest.len() + file.len())
        })
        .reduce(
            || (0.0, 0.0, 0),
            |a, b| (a.0 + b.0, a.1.max(b.1), a.2 + b.2),
        );
    ((sum / count.max(1) as f64) as f32, max)
}

/// Distance from `p` to the polyline `line`.
fn point_polyline_m(p: Vec3, line: &[Vec3]) -> f32 {
    if line.len() < 2 {
        return line.first().map_or(f32::INFINITY, |q| (p - *q).length());
    }
    line.windows(2)
        .map(|w| {
            let e = w[1] - w[0];
            let t = if e.length_squared() > 0.0 {
                ((p - w[0]).dot(e) / e.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (p - (w[0] + t * e)).length()
        })
        .fold(f32::INFINITY, f32::min)
}
