//! From placed, clustered strands to the engine's hair model: guides (3 strands per wisp,
//! resampled to equal links), barycentric weights, length fractions and rest offsets.
//!
//! Every strand is resampled at points evenly spaced in arc length, once with the guides'
//! `links + 1` points and once with the render strands' points, so a guide's links are equal
//! (the simulation's rigid links) and each render strand is its own file polyline. A render
//! strand is then the Catmull-Rom curve of its wisp's guides blended by its barycentric weights
//! (`c(s) = Σ wᵢ gᵢ(s)`, cut to its length fraction) plus its rest offsets, which carry that
//! curve onto its resampled points: at rest, interpolation reproduces the strands exactly,
//! whatever the number of wisps.

use super::cluster::{FEATURE_DIM, Feature, SHAPE_WEIGHT};
use super::fit::Placement;
use super::polyline::{arc_length, resample_by_arc_length};
use super::strands::Kept;
use crate::hairstyle::{GuideSet, StrandLayout};
use crate::interp::{catmull_rom_resample_to, rest_offsets_of};
use glam::Vec3;
use rayon::prelude::*;

/// The clustering feature of a strand resampled to `pts` (root, middle, tip).
pub fn feature_of(pts: &[Vec3]) -> Feature {
    let root = pts[0];
    let mid = (pts[pts.len() / 2] - root) * SHAPE_WEIGHT;
    let tip = (pts[pts.len() - 1] - root) * SHAPE_WEIGHT;
    let mut f = [0.0; FEATURE_DIM];
    f[..3].copy_from_slice(&root.to_array());
    f[3..6].copy_from_slice(&mid.to_array());
    f[6..].copy_from_slice(&tip.to_array());
    f
}

/// Picks a wisp's 3 guides among its strands (`members`, >= 1; repeated when fewer than 3):
/// the strand whose root is nearest the wisp's mean root, the one farthest from it, and the
/// one farthest from the line through those two, so the guides' roots span the wisp.
pub fn pick_guides(members: &[u32], roots: &[Vec3]) -> [u32; 3] {
    let root = |s: u32| roots[s as usize];
    let mean = members.iter().map(|&s| root(s)).sum::<Vec3>() / members.len() as f32;
    let by = |f: &dyn Fn(u32) -> f32| -> u32 {
        // Largest score, ties to the lowest strand index (deterministic).
        let mut best = (f32::NEG_INFINITY, u32::MAX);
        for &s in members {
            let v = f(s);
            if v > best.0 || (v == best.0 && s < best.1) {
                best = (v, s);
            }
        }
        best.1
    };
    let a = by(&|s| -(root(s) - mean).length_squared());
    let b = by(&|s| {
        if s == a {
            -1.0
        } else {
            (root(s) - root(a)).length_squared()
        }
    });
    let axis = (root(b) - root(a)).normalize_or_zero();
    let c = by(&|s| {
        if s == a || s == b {
            -1.0
        } else {
            let d = root(s) - root(a);
            (d - d.dot(axis) * axis).length_squared()
        }
    });
    [a, b, c]
}

/// Barycentric weights (>= 0, sum 1) of the point of triangle `t` nearest to `p`'s projection
/// on its plane, clamped into the triangle; thirds for a degenerate triangle.
pub fn barycentric_clamped(p: Vec3, t: [Vec3; 3]) -> [f32; 3] {
    let (e0, e1, d) = (t[1] - t[0], t[2] - t[0], p - t[0]);
    let (d00, d01, d11) = (e0.dot(e0), e0.dot(e1), e1.dot(e1));
    let (d20, d21) = (d.dot(e0), d.dot(e1));
    let den = d00 * d11 - d01 * d01;
    let tiny = 1e-12 * (d00 * d11).max(f32::MIN_POSITIVE);
    if den.is_nan() || den <= tiny {
        return [1.0 / 3.0; 3];
    }
    let v = (d11 * d20 - d01 * d21) / den;
    let w = (d00 * d21 - d01 * d20) / den;
    let mut b = [(1.0 - v - w).max(0.0), v.max(0.0), w.max(0.0)];
    let sum: f32 = b.iter().sum();
    if sum.is_nan() || sum <= 0.0 {
        return [1.0 / 3.0; 3];
    }
    b.iter_mut().for_each(|x| *x /= sum);
    b
}

/// Every kept strand placed on the head and resampled twice, strand after strand: for guides
/// (`ppg` points each, links + 1) and for render strands (`n` points each).
pub(super) struct Resampled {
    pub(super) guide: Vec<Vec3>,
    pub(super) ppg: usize,
    pub(super) render: Vec<Vec3>,
    pub(super) n: usize,
}

/// Places each of `kept` with `placement` and resamples it by arc length for guides and for
/// render strands (in parallel, one strand per task).
pub(super) fn resample_placed(
    kept: &[Kept],
    placement: &Placement,
    ppg: usize,
    n: usize,
) -> Resampled {
    let count = kept.len();
    let mut guide = vec![Vec3::ZERO; count * ppg];
    let mut render = vec![Vec3::ZERO; count * n];
    guide
        .par_chunks_mut(ppg)
        .zip(render.par_chunks_mut(n))
        .zip(kept.par_iter())
        .for_each(|((g, r), k)| {
            let placed: Vec<Vec3> = k.points.iter().map(|p| placement.apply(*p)).collect();
            resample_by_arc_length(&placed, g);
            resample_by_arc_length(&placed, r);
        });
    Resampled {
        guide,
        ppg,
        render,
        n,
    }
}

/// Guides and layout from the resampled strands `s`, the wisp of each strand in `wisp_of`
/// (0..wisps): each wisp's 3 guides ([`pick_guides`]), then each strand's weights over them,
/// its length fraction and its rest offsets.
pub(super) fn build_model(
    s: &Resampled,
    wisp_of: &[u32],
    root_normal_of: impl Fn(Vec3) -> Vec3,
    tip_taper: f32,
) -> (GuideSet, StrandLayout) {
    let strands = wisp_of.len();
    let roots: Vec<Vec3> = (0..strands).map(|i| s.render[i * s.n]).collect();
    let (start, members) = members_by_wisp(wisp_of);
    let (guides, wisp_guides) = wisp_guides(s, &start, &members, &roots, root_normal_of);
    let fits = strand_fits(s, wisp_of, &wisp_guides, &guides, &roots);
    let layout = StrandLayout {
        wisp_guides,
        strand_wisp: wisp_of.to_vec(),
        strand_weights: fits.weights,
        strand_phase: vec![0.0; strands],
        strand_length: fits.length,
        tip_taper,
        points_per_strand: s.n,
        rest_offset: fits.rest_offset,
    };
    (guides, layout)
}

/// The strands of each wisp in strand order, by counting sort (no per-wisp allocation): wisp
/// w's members are `members[start[w]..start[w + 1]]`.
pub(super) fn members_by_wisp(wisp_of: &[u32]) -> (Vec<usize>, Vec<u32>) {
    let wisps = wisp_of.iter().map(|w| *w as usize + 1).max().unwrap_or(0);
    let mut start = vec![0usize; wisps + 1];
    for &w in wisp_of {
        start[w as usize + 1] += 1;
    }
    for w in 0..wisps {
        start[w + 1] += start[w];
    }
    let mut fill = start.clone();
    let mut members = vec![0u32; wisp_of.len()];
    for (s, &w) in wisp_of.iter().enumerate() {
        members[fill[w as usize]] = s as u32;
        fill[w as usize] += 1;
    }
    (start, members)
}

/// The guides of every wisp (3 of its strands, resampled for guides, with equal links and
/// their roots' scalp normals) and each wisp's guide indices.
fn wisp_guides(
    s: &Resampled,
    start: &[usize],
    members: &[u32],
    roots: &[Vec3],
    root_normal_of: impl Fn(Vec3) -> Vec3,
) -> (GuideSet, Vec<[u32; 3]>) {
    let (wisps, ppg) = (start.len() - 1, s.ppg);
    let mut rest = Vec::with_capacity(wisps * 3 * ppg);
    let mut link_length_m = Vec::with_capacity(wisps * 3);
    let mut root_normal = Vec::with_capacity(wisps * 3);
    let mut wisp_guides = Vec::with_capacity(wisps);
    for w in 0..wisps {
        let picked = pick_guides(&members[start[w]..start[w + 1]], roots);
        let g0 = link_length_m.len() as u32;
        for strand in picked {
            let pts = &s.guide[strand as usize * ppg..(strand as usize + 1) * ppg];
            rest.extend_from_slice(pts);
            link_length_m.push(arc_length(pts) / (ppg - 1) as f32);
            root_normal.push(root_normal_of(pts[0]));
        }
        wisp_guides.push([g0, g0 + 1, g0 + 2]);
    }
    let guides = GuideSet {
        points_per_guide: ppg,
        rest,
        link_length_m,
        root_normal,
        carrier: Vec::new(),
    };
    (guides, wisp_guides)
}

/// Each render strand's place among its wisp's guides.
pub(super) struct StrandFits {
    /// Barycentric weights over the wisp's 3 guides.
    pub(super) weights: Vec<[f32; 3]>,
    /// Length as a fraction of the blended guide's, in (0, 1].
    pub(super) length: Vec<f32>,
    /// `n` rest offsets per strand (see `crate::interp::rest_offsets_of`).
    pub(super) rest_offset: Vec<Vec3>,
}

/// Per strand, independently and in parallel: weights from its root's position in its guides'
/// root triangle ([`barycentric_clamped`]), the length fraction of its resampled points
/// against the blended guides, and the offsets that carry the smoothed blend onto its points.
pub(super) fn strand_fits(
    s: &Resampled,
    wisp_of: &[u32],
    wisp_guides: &[[u32; 3]],
    guides: &GuideSet,
    roots: &[Vec3],
) -> StrandFits {
    let (strands, ppg, n) = (wisp_of.len(), s.ppg, s.n);
    let mut strand_weights = vec![[0.0f32; 3]; strands];
    let mut strand_length = vec![1.0f32; strands];
    let mut rest_offset = vec![Vec3::ZERO; strands * n];
    strand_weights
        .par_iter_mut()
        .zip(strand_length.par_iter_mut())
        .zip(rest_offset.par_chunks_mut(n))
        .enumerate()
        .for_each(|(i, ((weights, length), offsets))| {
            let gi = wisp_guides[wisp_of[i] as usize];
            let g = gi.map(|g| guides.guide(g as usize));
            let w = barycentric_clamped(roots[i], [g[0][0], g[1][0], g[2][0]]);
            let ctrl: Vec<Vec3> = (0..ppg)
                .map(|k| g[0][k] * w[0] + g[1][k] * w[1] + g[2][k] * w[2])
                .collect();
            let target = &s.render[i * n..(i + 1) * n];
            let fraction = (arc_length(target) / arc_length(&ctrl)).min(1.0);
            let fraction = if fraction.is_finite() && fraction > 0.0 {
                fraction
            } else {
                1.0
            };
            let mut centre = vec![Vec3::ZERO; n];
            catmull_rom_resample_to(&ctrl, fraction, &mut centre);
            rest_offsets_of(&centre, g[1][0] - g[0][0], target, offsets);
            *weights = w;
            *length = fraction;
        });
    StrandFits {
        weights: strand_weights,
        length: strand_length,
        rest_offset,
    }
}
