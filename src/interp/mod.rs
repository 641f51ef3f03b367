//! Render strands from guides (Bertails 2005 §3.1 and §4.1).
//!
//! Each render strand is a barycentric blend of its wisp's three guides, particle by particle;
//! the blended control polygon is smoothed with a uniform Catmull-Rom spline into the
//! `points_per_strand` points that are both filled into the map and drawn (Bertails §3.1: "each
//! hair strand is sampled using a Catmull-Rom spline into nSmooth points"); curls are a helix
//! added around that centre line in a frame transported along the strand.
//!
//! The curl frame starts from the vector between two guide roots of the wisp (which turns
//! with the head, so curls do not spin when the head turns) and is carried along the strand by
//! projection onto each new normal plane: a discrete parallel transport that costs two dot
//! products per point and never flips.
//!
//! An imported groom adds each strand's own rest offset from its wisp's blend ([`offset`]),
//! in a frame carried by the guides, before any curl.
//!
//! Given the frame's colliders, render points that the blend puts inside the head or body are
//! moved to their surface ([`solids`]).
//!
//! Output buffers are reused between frames; strands are independent, so the work is split
//! over rayon in fixed chunks and the result does not depend on the thread count.

pub mod solids;

use crate::hairstyle::{CurlSpec, GuideSet, StrandLayout};
use crate::sim::Colliders;
use glam::Vec3;
use rayon::prelude::*;
use solids::SolidsView;

mod offset;
pub use offset::{apply_rest_offsets, rest_offsets_of};
mod subdivide;
pub use subdivide::{subdivide_in_place, subdivided_points};

/// Maximum particles per guide (matches `hairstyle::MAX_GUIDE_LINKS + 1`), so control points
/// fit in a stack buffer.
const MAX_GUIDE_POINTS: usize = crate::hairstyle::MAX_GUIDE_LINKS as usize + 1;

/// Points and unit tangents of all render strands, strand-major.
#[derive(Clone, Debug, Default)]
pub struct StrandGeometry {
    pub points_per_strand: usize,
    /// Each segment of the groom's polyline is cut into this many pieces
    /// ([`subdivide_in_place`]; 0 or 1: none): only every piece-th point can turn.
    pub segment_pieces: usize,
    /// World positions, metres.
    pub positions: Vec<Vec3>,
    /// Unit tangents from root to tip.
    pub tangents: Vec<Vec3>,
    /// Length of hair each point stands for (half of each adjacent segment), metres, times the
    /// share of the strand's fibres present there (`fibre_share`): the length of *fibre*, in
    /// units of the strand's F fibres, that the map fills.
    pub lengths_m: Vec<f32>,
    /// Share of the strand's fibres present at each point, in [0, 1]: 1 along the strand, falling
    /// linearly to 0 over its tip taper (fibres end one by one toward the tip).
    pub fiber_share: Vec<f32>,
}

impl StrandGeometry {
    pub fn strand_count(&self) -> usize {
        self.positions
            .len()
            .checked_div(self.points_per_strand)
            .unwrap_or(0)
    }
}

/// Interpolates all render strands from guide particles `guide_pos` (world, indexed like
/// `GuideSet::rest`) into `out`, reusing its allocations.
pub fn interpolate(
    guides: &GuideSet,
    layout: &StrandLayout,
    curl: &CurlSpec,
    guide_pos: &[Vec3],
    out: &mut StrandGeometry,
) {
    interpolate_among(guides, layout, curl, guide_pos, None, 1, out);
}

/// [`interpolate`], keeping render points out of `colliders` when given (see [`solids`]), with
/// each segment of the groom's polyline cut into `pieces` straight pieces (1: as the groom
/// says; see [`subdivide_in_place`]).
pub fn interpolate_among(
    guides: &GuideSet,
    layout: &StrandLayout,
    curl: &CurlSpec,
    guide_pos: &[Vec3],
    colliders: Option<&Colliders>,
    pieces: usize,
    out: &mut StrandGeometry,
) {
    let view = colliders.map(SolidsView::new);
    let coarse = layout.points_per_strand;
    let pieces = pieces.max(1);
    let n = subdivided_points(coarse, pieces);
    let total = layout.count() * n;
    out.points_per_strand = n;
    out.segment_pieces = pieces;
    out.positions.resize(total, Vec3::ZERO);
    out.tangents.resize(total, Vec3::ZERO);
    out.lengths_m.resize(total, 0.0);
    out.fiber_share.resize(total, 1.0);
    let ppg = guides.points_per_guide;
    debug_assert!(ppg <= MAX_GUIDE_POINTS);
    out.positions
        .par_chunks_mut(n)
        .zip(out.tangents.par_chunks_mut(n))
        .zip(out.lengths_m.par_chunks_mut(n))
        .zip(out.fiber_share.par_chunks_mut(n))
        .enumerate()
        .for_each(|(s, (((pos, tan), len), share))| {
            let wisp = layout.wisp_guides[layout.strand_wisp[s] as usize];
            let w = layout.strand_weights[s];
            let g = wisp.map(|g| &guide_pos[g as usize * ppg..(g as usize + 1) * ppg]);
            let mut ctrl = [Vec3::ZERO; MAX_GUIDE_POINTS];
            for i in 0..ppg {
                ctrl[i] = g[0][i] * w[0] + g[1][i] * w[1] + g[2][i] * w[2];
            }
            let length = layout.strand_length.get(s).copied().unwrap_or(1.0);
            // The groom's points first, in the front of the strand's buffer.
            let groom = &mut pos[..coarse];
            catmull_rom_resample_to(&ctrl[..ppg], length, groom);
            let reference = g[1][0] - g[0][0];
            if let Some(offsets) = layout.rest_offset.get(s * coarse..(s + 1) * coarse) {
                apply_rest_offsets(groom, reference, offsets);
            }
            if curl.radius_m > 0.0 {
                add_curl(groom, reference, curl, layout.strand_phase[s]);
            }
            if let Some(v) = &view {
                v.push_out(groom, &mut len[..coarse]);
            }
            subdivide_in_place(pos, coarse, pieces);
            tangents_and_lengths(pos, tan, len);
            tip_taper(layout.tip_taper, pos, share, len);
        });
}

/// Samples the uniform Catmull-Rom spline through `ctrl` (>= 2 points) at `out.len()` evenly
/// spaced parameters from the first to the last control point; end tangents use reflected
/// phantom points, so the curve passes through both ends.
pub fn catmull_rom_resample(ctrl: &[Vec3], out: &mut [Vec3]) {
    catmull_rom_resample_to(ctrl, 1.0, out);
}

/// [`catmull_rom_resample`] over the first `fraction` ∈ (0, 1] of the spline's parameter
/// range: a strand that stops short of its guides' tips, still sampled at `out.len()` points.
/// The guides' links are of equal length, so the parameter is proportional to arc length up to
/// the spline's bending.
pub fn catmull_rom_resample_to(ctrl: &[Vec3], fraction: f32, out: &mut [Vec3]) {
    let m = ctrl.len();
    let n = out.len();
    if n == 0 {
        return;
    }
    if m < 2 || n == 1 {
        out.fill(ctrl.first().copied().unwrap_or(Vec3::ZERO));
        return;
    }
    let at = |i: isize| -> Vec3 {
        if i < 0 {
            2.0 * ctrl[0] - ctrl[1]
        } else if i as usize >= m {
            2.0 * ctrl[m - 1] - ctrl[m - 2]
        } else {
            ctrl[i as usize]
        }
    };
    let fraction = if fraction.is_finite() {
        fraction.clamp(1e-3, 1.0)
    } else {
        1.0
    };
    let scale = (m - 1) as f32 * fraction / (n - 1) as f32;
    for (k, o) in out.iter_mut().enumerate() {
        let u = k as f32 * scale;
        let seg = (u as usize).min(m - 2);
        let t = u - seg as f32;
        let i = seg as isize;
        let (p0, p1, p2, p3) = (at(i - 1), at(i), at(i + 1), at(i + 2));
        // Uniform Catmull-Rom in Hermite form with tangents (p2 - p0)/2 and (p3 - p1)/2.
        let t2 = t * t;
        let t3 = t2 * t;
        *o = 0.5
            * ((2.0 * p1)
                + (p2 - p0) * t
                + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2
                + (3.0 * p1 - p0 - 3.0 * p2 + p3) * t3);
    }
}

/// Adds a helix of `curl.radius_m` around the centre line `pos` (in place). The radius ramps up
/// over the first 2 cm so roots stay on the scalp.
fn add_curl(pos: &mut [Vec3], reference: Vec3, curl: &CurlSpec, phase: f32) {
    const RAMP_M: f32 = 0.02;
    let n = pos.len();
    if n < 2 {
        return;
    }
    let mut prev = pos[0];
    let mut t = (pos[1] - pos[0]).normalize_or(Vec3::NEG_Y);
    let mut b1 = (reference - reference.dot(t) * t).normalize_or(t.any_orthonormal_vector());
    let mut s = 0.0f32;
    let k = std::f32::consts::TAU / curl.period_m;
    for i in 0..n {
        let centre = pos[i];
        if i > 0 {
            s += (centre - prev).length();
            let next = if i + 1 < n { pos[i + 1] } else { centre };
            let t_new = (next - prev).normalize_or(t);
            // Discrete parallel transport: project the old normal onto the new normal plane.
            b1 = (b1 - b1.dot(t_new) * t_new).normalize_or(t_new.any_orthonormal_vector());
            t = t_new;
        }
        prev = centre;
        let b2 = t.cross(b1);
        let r = curl.radius_m * (s / RAMP_M).min(1.0);
        let a = k * s + phase;
        pos[i] = centre + r * (a.cos() * b1 + a.sin() * b2);
    }
}

/// The share of a strand's fibres present at each point: fibres end one by one over the last
/// `taper` of the strand's arc length (their lengths spread evenly there), so the share falls
/// linearly from 1 to 0 over it, reaching 0 at the tip. Scales each point's fibre length `len`.
fn tip_taper(taper: f32, pos: &[Vec3], share: &mut [f32], len: &mut [f32]) {
    let n = share.len().min(pos.len());
    if taper.is_nan() || taper <= 0.0 || n < 2 {
        share.fill(1.0);
        return;
    }
    let total: f32 = pos.windows(2).map(|w| (w[1] - w[0]).length()).sum();
    let mut arc = 0.0f32;
    for i in 0..n {
        if i > 0 {
            arc += (pos[i] - pos[i - 1]).length();
        }
        let u = if total > 0.0 { arc / total } else { 0.0 };
        share[i] = ((1.0 - u) / taper).clamp(0.0, 1.0);
        len[i] *= share[i];
    }
}

/// Unit tangents by central differences, and the hair length each point stands for.
fn tangents_and_lengths(pos: &[Vec3], tan: &mut [Vec3], len: &mut [f32]) {
    let n = pos.len();
    if n < 2 {
        tan.fill(Vec3::NEG_Y);
        len.fill(0.0);
        return;
    }
    for i in 0..n {
        let a = pos[i.saturating_sub(1)];
        let b = pos[(i + 1).min(n - 1)];
        tan[i] = (b - a).normalize_or(if i > 0 { tan[i - 1] } else { Vec3::NEG_Y });
        let before = if i > 0 {
            (pos[i] - pos[i - 1]).length()
        } else {
            0.0
        };
        let after = if i + 1 < n {
            (pos[i + 1] - pos[i]).length()
        } else {
            0.0
        };
        len[i] = 0.5 * (before + after);
    }
}

#[cfg(test)]
mod tests;
