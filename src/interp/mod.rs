//! Render strands from guides (Bertails 2005 §3.1 and §4.1).
//!
//! Each render strand is a barycentric blend of its wisp's three guides, particle by particle;
//! the blended control polygon is smoothed with a uniform Catmull-Rom spline into the
//! `points_per_strand` points that are both filled into the map and drawn (Bertails §3.1: "each
//! hair strand is sampled using a Catmull-Rom spline into nSmooth points", `catmull_rom.rs`);
//! curls are a helix added around that centre line in a frame transported along the strand
//! (`curl.rs`).
//!
//! Each point then gets a unit tangent by central differences and the length of hair it stands
//! for, ℓ_i = (|p_i − p_{i−1}| + |p_{i+1} − p_i|)/2, times the share of the strand's fibres
//! present there: fibres end one by one over the tip taper τ, so the share is
//! clamp((1 − u)/τ, 0, 1) at arc-length fraction u.
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

mod catmull_rom;
pub use catmull_rom::{catmull_rom_resample, catmull_rom_resample_to};
mod curl;
use curl::add_curl;
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
