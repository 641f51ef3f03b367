//! A level of detail for render strands: fewer strands, each standing for more fibres.
//!
//! A render strand drawn narrower than a pixel costs as much to interpolate, fill, shade and
//! draw as a wide one. Keeping a fraction `f` of each wisp's strands and giving each kept strand
//! the fibres of the strands it replaces (`fibers_per_strand / f`, so the hair's total fibres
//! are the same) conserves what the map and the image add up: the optical density a wisp puts
//! into the map (it sums fibres), and the coverage its lines leave on the image (a strand's line
//! is as wide as its fibres side by side, so `f` as many lines `1/f` as wide). What it loses is
//! the strands' own placement inside the wisp: where a kept strand lies, the strands it stands
//! for are taken to lie, which the image error of a level measures (BENCHMARKS.md).
//!
//! The kept strands are the first of each wisp's strands in layout order, so a thinned layout's
//! strands are a subset of the full one's at any fraction: a level of detail draws some of the
//! hair the full level draws, not other hair.

use super::model::StrandLayout;
use super::spec::Hairstyle;

/// How many of a wisp's `n` render strands a level of detail of `fraction` keeps:
/// `ceil(fraction × n)`, at least one of a non-empty wisp. `fraction` is clamped to (0, 1]; a
/// non-finite one keeps them all. The engine's memory estimate counts strands with this too.
pub fn kept_strands(n: u32, fraction: f32) -> u32 {
    if !fraction.is_finite() || fraction >= 1.0 {
        return n;
    }
    ((n as f32 * fraction.max(0.0)).ceil() as u32).clamp(1.min(n), n)
}

/// `style` and `layout` with the first [`kept_strands`] of each wisp's render strands kept and
/// `strands.fibers_per_strand` raised so that the total fibres stay the same;
/// `strands_per_wisp` becomes the kept count of a full wisp (what the strand spacing
/// follows). At a fraction of 1 the inputs come back unchanged.
pub fn thin_strands(
    style: Hairstyle,
    layout: StrandLayout,
    fraction: f32,
) -> (Hairstyle, StrandLayout) {
    if !fraction.is_finite() || fraction >= 1.0 || layout.count() == 0 {
        return (style, layout);
    }
    let wisps = layout.wisp_guides.len();
    let mut per_wisp = vec![0u32; wisps];
    for &w in &layout.strand_wisp {
        per_wisp[w as usize] += 1;
    }
    let mut seen = vec![0u32; wisps];
    let keep: Vec<bool> = layout
        .strand_wisp
        .iter()
        .map(|&w| {
            let w = w as usize;
            seen[w] += 1;
            seen[w] <= kept_strands(per_wisp[w], fraction)
        })
        .collect();
    let thinned = keep_strands(&layout, &keep);
    let mut style = style;
    let ratio = layout.count() as f64 / thinned.count().max(1) as f64;
    style.strands.fibers_per_strand = (style.strands.fibers_per_strand as f64 * ratio) as f32;
    style.wisps.strands_per_wisp = kept_strands(style.wisps.strands_per_wisp, fraction);
    (style, thinned)
}

/// The layout of the strands whose `keep` entry is true, in their order.
fn keep_strands(layout: &StrandLayout, keep: &[bool]) -> StrandLayout {
    let pick = |i: &usize| keep[*i];
    let indices: Vec<usize> = (0..layout.count()).filter(pick).collect();
    let ppg = layout.points_per_strand;
    let rest_offset = if layout.rest_offset.is_empty() {
        Vec::new()
    } else {
        indices
            .iter()
            .flat_map(|&i| layout.rest_offset[i * ppg..(i + 1) * ppg].iter().copied())
            .collect()
    };
    StrandLayout {
        wisp_guides: layout.wisp_guides.clone(),
        strand_wisp: indices.iter().map(|&i| layout.strand_wisp[i]).collect(),
        strand_weights: indices.iter().map(|&i| layout.strand_weights[i]).collect(),
        strand_phase: indices.iter().map(|&i| layout.strand_phase[i]).collect(),
        strand_length: indices.iter().map(|&i| layout.strand_length[i]).collect(),
        tip_taper: layout.tip_taper,
        points_per_strand: ppg,
        rest_offset,
    }
}

#[cfg(test)]
mod tests;
