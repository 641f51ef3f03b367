//! Sparse grooms densified: a groom with fewer strands than a head of hair renders (a capture
//! subsampled to 100 strands) has its strands taken as guides and render strands interpolated
//! among them, as wisp grows its own hair (Bertails 2005 §4.1: wisps of 3 guides, render
//! strands blended from them).
//!
//! How many render strands a head needs is the base style's count (`wisps.count ×
//! strands_per_wisp`, 3,350 for the presets) times the share of its scalp the groom's roots
//! cover ([`scalp_share`]). A groom of at least 3 strands and fewer than that is sparse: it is
//! clustered into wisps of about 3 strands (`MIN_WISP_STRANDS`), whose 3 guides are 3 file
//! strands spanning the wisp; its file strands stay render strands (each reproduced at rest by
//! its offsets, as in a dense groom) and [`densify`] adds the rest, spread over the wisps in
//! proportion to their strands. Each added strand has barycentric weights drawn uniformly in
//! its wisp's guide triangle (as `hairstyle::generate` draws them), and its rest shape is the
//! same blend of its guides' file polylines, point by point along their arc length, fitted as a
//! file strand is (length fraction and rest offsets against the blended guides): its root lies
//! in the triangle of its guides' roots, and it keeps the file's detail finer than the guides'
//! links. The style then gives each render strand `F_base · N_base · share / N` fibres
//! (`style::groom_style`): the hair's total stays the base style's for the scalp it covers.

use super::build::{Resampled, members_by_wisp, pick_guides, strand_fits};
use crate::hairstyle::{GuideSet, Hairstyle, SplitMix64, StrandLayout, guide_roots};
use glam::Vec3;

/// A base style's guide root counts as covered by a groom when one of the groom's roots lies
/// within this many wisp spacings (`sqrt(scalp area / wisps)`, 18 mm for the presets) of it:
/// 1.5 spacings reach past the middle between two neighbouring wisps, so a groom whose roots
/// are spread over the whole scalp at the wisps' own spacing covers all of it.
pub const SHARE_RADIUS_SPACINGS: f32 = 1.5;

/// How a sparse groom is densified.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Density {
    /// Render strands wanted: the base style's count times `scalp_share`, rounded.
    pub render_strands: usize,
    /// Share of the base style's scalp the groom's roots cover, in (0, 1].
    pub scalp_share: f32,
}

/// The share of `base`'s scalp that `roots` (placed, head frame) cover: the fraction of
/// `base`'s guide roots ([`guide_roots`]) with a groom root within [`SHARE_RADIUS_SPACINGS`]
/// wisp spacings. Costs guide roots × `roots.len()` distances.
pub fn scalp_share(roots: &[Vec3], base: &Hairstyle) -> f32 {
    let lattice = guide_roots(base);
    if lattice.is_empty() {
        return 0.0;
    }
    let spacing = (base.scalp_area_m2() / base.wisps.count.max(1) as f32).sqrt();
    let within2 = (SHARE_RADIUS_SPACINGS * spacing).powi(2);
    let covered = lattice
        .iter()
        .filter(|g| roots.iter().any(|r| r.distance_squared(**g) <= within2))
        .count();
    covered as f32 / lattice.len() as f32
}

/// The densification of a groom whose strands have `roots` on `base`'s head, or `None` when it
/// is dense enough as it is (see the module doc): at least 3 strands and fewer than the base
/// style's render strands times its scalp share.
pub fn density_of(roots: &[Vec3], base: &Hairstyle) -> Option<Density> {
    let count = roots.len();
    let base_strands = base.wisps.count as usize * base.wisps.strands_per_wisp as usize;
    if count < 3 || count >= base_strands {
        return None;
    }
    let scalp_share = scalp_share(roots, base);
    let render_strands = (base_strands as f32 * scalp_share).round() as usize;
    (count < render_strands).then_some(Density {
        render_strands,
        scalp_share,
    })
}

/// Appends `extra` render strands to `layout` (built from the strands `s`, each in the wisp
/// `wisp_of` says, with `guides`): each wisp gets a share of them in proportion to its
/// strands, with weights drawn uniformly in its guide triangle from `seed` (see the module
/// doc).
pub(super) fn densify(
    s: &Resampled,
    wisp_of: &[u32],
    guides: &GuideSet,
    layout: &mut StrandLayout,
    extra: usize,
    seed: u64,
) {
    let n = s.n;
    let count = wisp_of.len();
    let roots: Vec<Vec3> = (0..count).map(|i| s.render[i * n]).collect();
    let (start, members) = members_by_wisp(wisp_of);
    let mut rng = SplitMix64::new(seed ^ 0xDE45_1F1E_D0A1_2B7C);
    let mut added = Resampled {
        guide: Vec::new(),
        ppg: s.ppg,
        render: Vec::with_capacity(extra * n),
        n,
    };
    let mut added_wisp = Vec::with_capacity(extra);
    let mut added_roots = Vec::with_capacity(extra);
    for w in 0..start.len() - 1 {
        // Cumulative rounding: the wisps' shares add up to exactly `extra`.
        let share = |k: usize| k * extra / count;
        let here = share(start[w + 1]) - share(start[w]);
        let picked = pick_guides(&members[start[w]..start[w + 1]], &roots);
        let file = picked.map(|g| &s.render[g as usize * n..(g as usize + 1) * n]);
        for _ in 0..here {
            // Uniform point in a triangle: (1 - √r1, √r1 (1 - r2), √r1 r2).
            let s1 = rng.unit().sqrt();
            let r2 = rng.unit();
            let wt = [1.0 - s1, s1 * (1.0 - r2), s1 * r2];
            let from = added.render.len();
            added.render.extend(
                (0..n).map(|k| file[0][k] * wt[0] + file[1][k] * wt[1] + file[2][k] * wt[2]),
            );
            added_roots.push(added.render[from]);
            added_wisp.push(w as u32);
        }
    }
    let fits = strand_fits(
        &added,
        &added_wisp,
        &layout.wisp_guides,
        guides,
        &added_roots,
    );
    layout.strand_wisp.extend_from_slice(&added_wisp);
    layout.strand_weights.extend_from_slice(&fits.weights);
    layout.strand_phase.resize(layout.strand_wisp.len(), 0.0);
    layout.strand_length.extend_from_slice(&fits.length);
    layout.rest_offset.extend_from_slice(&fits.rest_offset);
}
