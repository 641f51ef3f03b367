//! Where the exact reference puts each render strand's fibres.
//!
//! Fibre f of a render strand follows the strand's polyline offset by a fixed vector in the
//! strand's normal plane. The normal frame starts from any unit vector perpendicular to the
//! first segment and is carried along the strand by projection (discrete parallel transport,
//! as `interp` carries curls), so a bundle keeps its shape along the strand. The F offsets are
//! a Vogel (golden-angle) spiral filling the disc of radius `bundle_radius_m` evenly, turned
//! by a per-strand angle from a hash of the strand index (and `placement_seed`, 0 unless a
//! measurement asks for another placement of the same bundles). With F = 1 the only fibre is the
//! strand itself (offset 0): the geometry is then exact, not a model.

use super::{ExactInput, Projection};
use crate::disc::vogel;
use glam::{Vec2, Vec3};

/// A per-strand angle in [0, 2π) from a hash of its index and the placement seed (SplitMix64
/// finaliser).
fn strand_angle(s: usize, seed: u64) -> f32 {
    let mut z = (s as u64)
        .wrapping_add(seed.wrapping_mul(0xD1B5_4A32_D192_ED03))
        .wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 40) as f32 / (1u64 << 24) as f32 * std::f32::consts::TAU
}

/// The points of the F fibres of one render strand (light frame), fibre after fibre; NaN
/// points when the strand has a non-finite point.
pub(super) fn place_fibers(
    pts: &[Vec3],
    s: usize,
    input: &ExactInput,
    proj: &Projection,
) -> Vec<Vec3> {
    let f_count = input.fibers_per_strand.max(1) as usize;
    let ppl = pts.len();
    if pts.iter().any(|p| !p.is_finite()) {
        return vec![Vec3::NAN; ppl * f_count];
    }
    let (sn, cs) = strand_angle(s, input.placement_seed).sin_cos();
    let offsets = (0..f_count as u32).map(|f| {
        if f_count == 1 {
            Vec2::ZERO
        } else {
            let v = vogel(f, f_count as u32);
            Vec2::new(cs * v.x - sn * v.y, sn * v.x + cs * v.y) * input.bundle_radius_m
        }
    });
    // Normal frame per point, carried along the strand by projection.
    let tangent =
        |k: usize| (pts[(k + 1).min(ppl - 1)] - pts[k.saturating_sub(1)]).normalize_or(Vec3::Y);
    let mut n1 = tangent(0).any_orthonormal_vector();
    let frames: Vec<(Vec3, Vec3)> = (0..ppl)
        .map(|k| {
            let t = tangent(k);
            n1 = (n1 - t * n1.dot(t)).normalize_or(t.any_orthonormal_vector());
            (n1, t.cross(n1))
        })
        .collect();
    offsets
        .flat_map(|off| {
            frames
                .iter()
                .zip(pts)
                .map(move |((n1, n2), p)| proj.point(*p + *n1 * off.x + *n2 * off.y))
        })
        .collect()
}
