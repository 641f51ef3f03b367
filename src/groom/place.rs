//! Placing the kept strands on the head and refusing a groom whose roots are not on it.
//!
//! The placement is fitted by [`fit::fit_to_head`] on the roots and on samples along the
//! strands (every vertex past the root's link, a strided subset of at most about 50,000 in
//! all, enough for the 4 unknowns and linear in the groom). The turn about +Y is given, or
//! guessed so that most hair hangs behind the head ([`fit::guess_yaw_rad`]). Each root's
//! distance to the head surface is then measured; when more than [`ROOTS_OFF_HEAD_SHARE`]
//! of them are over [`ROOT_TOLERANCE_M`], the groom is refused, naming its worst strand: it
//! belongs to another head shape or orientation, or is not Y-up.
//!
//! A partial groom whose roots form a strip or a line (a mohawk, bangs) leaves the fit's scale
//! free: it can shrink the groom onto a point of the head, or fit the hairline's small circle
//! as if it went round the head. Such a groom is placed by the sphere through its own roots
//! ([`super::root_sphere`]), and so is any groom the fit leaves with its longest strand under
//! [`MIN_LONGEST_STRAND_M`].

use glam::{DVec3, Quat, Vec3};

use super::error::GroomError;
use super::fit::{self, Placement};
use super::polyline::arc_length;
use super::root_sphere::{is_strip, sphere_through};
use super::strands::Kept;
use crate::input::strands::StrandFile;

/// Largest distance of a root from the head surface after the fit, metres. Real scalps are not
/// ellipsoids (about ±1 cm) and a ponytail's tie sits off the scalp; a groom made for another
/// head shape or in another orientation is off by many centimetres.
pub const ROOT_TOLERANCE_M: f32 = 0.03;
/// Share of roots allowed beyond [`ROOT_TOLERANCE_M`] (ties, hair growing off a bun).
pub const ROOTS_OFF_HEAD_SHARE: f32 = 0.1;
/// A fit whose longest strand comes out shorter than this has shrunk the groom onto a point
/// of the head (no groom wisp simulates has hair under 2 cm long).
pub const MIN_LONGEST_STRAND_M: f32 = 0.02;

/// The groom's placement and how far its roots are from the head surface.
pub(super) struct OnHead {
    pub(super) placement: Placement,
    /// Distance of each kept strand's root from the head surface, metres.
    pub(super) root_distance_m: Vec<f32>,
    /// The largest of them.
    pub(super) worst_m: f32,
    /// Placed by the sphere through the roots: the fit onto the head shrank the groom.
    pub(super) from_root_sphere: bool,
}

/// Places the `kept` strands of `files` on the head ellipsoid of semi-axes `radii`, turned by
/// `yaw_rad` (guessed when `None`); see the module doc. `names` names all files in messages.
pub(super) fn place_on_head(
    kept: &[Kept],
    files: &[(String, StrandFile)],
    radii: Vec3,
    yaw_rad: Option<f32>,
    names: &str,
) -> Result<OnHead, GroomError> {
    let count = kept.len();
    let roots: Vec<Vec3> = kept.iter().map(|k| k.points[0]).collect();
    let yaw = yaw_rad.unwrap_or_else(|| {
        let (sum, n) = kept.iter().fold((Vec3::ZERO, 0usize), |(s, n), k| {
            (
                s + k.points.iter().copied().sum::<Vec3>(),
                n + k.points.len(),
            )
        });
        fit::guess_yaw_rad(&roots, sum / n as f32)
    });
    // Samples along the strands for the fit's "hair outside the head" term.
    let stride = (kept.iter().map(|k| k.points.len()).sum::<usize>() / 50_000).max(1);
    let hair: Vec<Vec3> = kept
        .iter()
        .step_by(stride)
        .flat_map(|k| k.points.iter().skip(2).copied())
        .collect();
    let fitted = fit::fit_to_head(&roots, &hair, yaw, radii);
    let longest_file = kept
        .iter()
        .map(|k| arc_length(k.points))
        .fold(0.0f32, f32::max);
    // A strip of roots, or a fit that shrank the groom to a point: the sphere of the roots'
    // own head (module doc).
    let collapsed = |p: &Placement| p.scale * longest_file < MIN_LONGEST_STRAND_M;
    let by_sphere = from_root_sphere(&roots, yaw, radii);
    let not_on_a_head = || GroomError::NotOnAHead {
        files: names.to_string(),
        min_mm: MIN_LONGEST_STRAND_M * 1000.0,
    };
    let (placement, from_root_sphere) =
        choose(fitted, by_sphere, &collapsed).ok_or_else(not_on_a_head)?;
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
        let k = kept[worst];
        return Err(GroomError::RootsOffHead {
            file: files[k.file].0.clone(),
            strand: k.strand,
            distance_mm: worst_d * 1000.0,
            tolerance_mm: ROOT_TOLERANCE_M * 1000.0,
            share: share * 100.0,
            scale: placement.scale,
            yaw_deg: placement.yaw_rad.to_degrees(),
        });
    }
    if collapsed(&placement) {
        // Every root on the head, but only with the groom shrunk to a point.
        return Err(not_on_a_head());
    }
    Ok(OnHead {
        placement,
        root_distance_m: dist,
        worst_m: worst_d,
        from_root_sphere,
    })
}

/// The placement used, and whether it is the roots' sphere: a strip's sphere, else a fit that
/// did not collapse, else any sphere that did not, else the collapsed fit (whose roots' distances
/// then say whether the groom is off the head or only shrunk).
fn choose(
    fitted: Option<Placement>,
    by_sphere: Option<(Placement, bool)>,
    collapsed: &impl Fn(&Placement) -> bool,
) -> Option<(Placement, bool)> {
    match (fitted, by_sphere) {
        (_, Some((p, true))) if !collapsed(&p) => Some((p, true)),
        (Some(p), _) if !collapsed(&p) => Some((p, false)),
        (_, Some((p, _))) if !collapsed(&p) => Some((p, true)),
        (Some(p), _) => Some((p, false)),
        (None, s) => s.map(|(p, _)| (p, true)),
    }
}

/// The placement that puts the sphere through the turned `roots` (their own head,
/// [`sphere_through`]) onto wisp's head: its centre at the head centre, its radius scaled to
/// the mean of the semi-axes `radii`; with whether the roots form a strip on it ([`is_strip`]).
fn from_root_sphere(roots: &[Vec3], yaw_rad: f32, radii: Vec3) -> Option<(Placement, bool)> {
    let turn = Quat::from_rotation_y(yaw_rad);
    let turned: Vec<DVec3> = roots.iter().map(|p| (turn * *p).as_dvec3()).collect();
    let (centre, radius) = sphere_through(&turned)?;
    let strip = is_strip(&turned, centre);
    let scale = f64::from((radii.x + radii.y + radii.z) / 3.0) / radius;
    let placement = Placement {
        scale: scale as f32,
        yaw_rad,
        offset_m: (-scale * centre).as_vec3(),
        upright: glam::Quat::IDENTITY,
    };
    (placement.scale.is_finite() && placement.scale > 0.0 && placement.offset_m.is_finite())
        .then_some((placement, strip))
}
