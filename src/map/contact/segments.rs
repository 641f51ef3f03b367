//! The render strands as fibre segments in the light frame: each segment where its fibre is
//! present, with what a crossing of it does to the light (ā_f and β̄_f² for the light's
//! inclination θ to it, sin θ = u·ω toward the light at its middle) and its straight piece
//! across and along the light, which `bins.rs` cuts into parts and bins.

use super::{ContactInput, FiberSegment, Segment};
use crate::map::Projection;
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// The render strands' points in the light frame of `proj`, strand after strand (NaN for
/// every point of a strand with a non-finite point).
pub(super) fn light_frame_points(input: &ContactInput, proj: &Projection) -> Vec<Vec3> {
    let ppl = input.points_per_strand.max(1);
    let strands = input.positions.len() / ppl;
    input.positions[..strands * ppl]
        .par_chunks(ppl)
        .flat_map_iter(|pts| {
            let finite = pts.iter().all(|p| p.is_finite());
            pts.iter()
                .map(move |p| if finite { proj.point(*p) } else { Vec3::NAN })
        })
        .collect()
}

/// The fibre segments of light-frame `points` (strand after strand): per segment where the
/// fibre is present (the mean fibre share of its ends at least ½) and which is not along the
/// light, its scattering record and its straight piece (each its own parent), in strand and
/// segment order.
pub(super) fn fiber_segments(
    input: &ContactInput,
    proj: &Projection,
    points: &[Vec3],
) -> (Vec<FiberSegment>, Vec<Segment>) {
    let ppl = input.points_per_strand.max(1);
    let strands = points.len() / ppl;
    let share = input.fiber_share;
    let fiber = input.fiber;
    let pairs: Vec<(FiberSegment, Segment)> = (0..strands)
        .into_par_iter()
        .flat_map_iter(|s| {
            let pts = &points[s * ppl..(s + 1) * ppl];
            let at = move |i: usize| share.get(s * ppl + i).copied().unwrap_or(1.0);
            pts.windows(2).enumerate().filter_map(move |(k, w)| {
                let (a, b) = (w[0], w[1]);
                if !(a.is_finite() && b.is_finite()) || 0.5 * (at(k) + at(k + 1)) < 0.5 {
                    return None;
                }
                let d = Vec2::new(b.y - a.y, b.z - a.z);
                let len = d.length();
                // A fibre exactly along the light has a disc, not a strip, as its shadow; the
                // exact reference skips it too.
                if len * len <= 1e-18 {
                    return None;
                }
                let (wa, wb) = (proj.to_world(a), proj.to_world(b));
                let u = (wb - wa).normalize_or_zero();
                let sin_theta = u.dot(proj.toward_light(0.5 * (wa + wb)));
                let f = fiber.forward_scatter(sin_theta);
                let a_f = f.a_f.clamp(Vec3::ZERO, Vec3::ONE);
                let fiber = FiberSegment {
                    a_f: a_f.into(),
                    beta2: f.beta_f2.max(Vec3::ZERO).into(),
                    strand: s as u32,
                    seg: k as u32,
                };
                let seg = Segment {
                    a: Vec2::new(a.y, a.z),
                    d,
                    inv_len: 1.0 / len,
                    x_a: a.x,
                    dx: b.x - a.x,
                    parent: 0,
                };
                Some((fiber, seg))
            })
        })
        .collect();
    pairs
        .into_par_iter()
        .enumerate()
        .map(|(i, (f, s))| {
            (
                f,
                Segment {
                    parent: i as u32,
                    ..s
                },
            )
        })
        .unzip()
}
