//! The exact reference as the measurements use it: the hairstyle's render strands as F real
//! fibres per strand within half the strand spacing (`exact`), under the key light, and its
//! mean over several placements of each bundle's fibres.
//!
//! Where a render strand's F fibres lie inside its bundle is not known from the render strands,
//! so a reference of one placement carries that placement's accident. The ensemble averages
//! the reference over P placements (seeds 0, 1, …, P − 1):
//!
//!   T̄_f = (1/P) Σ_p T_f,p,  and likewise the direct fraction, σ̄f² and the crossings behind,
//!
//! all of them fractions or means of the same rays, summed in seed order.

use crate::accuracy::exact::{ExactInput, ExactReference, Footprint};
use crate::engine::Engine;
use crate::fiber::{Fiber, LightAtPoint};
use crate::hairstyle::Hairstyle;
use crate::interp::StrandGeometry;
use crate::map::MapLight;

/// Placements the references of `wisp accuracy` and `wisp bench` average for bundles of
/// several fibres ([`ensemble_light`]): against 8, another placement reads within 0.008 of
/// them in every true-T_f bin at 30,000 vertices (against one placement, −0.03 to −0.045 in
/// smooth's lit bin; ACCURACY.md §1).
pub const DEFAULT_PLACEMENTS: u32 = 8;

/// The rays a reference of `placements` placements shoots at each vertex on the fibres it
/// stands for (`Footprint::Fibers`), as `wisp bench`'s references take them: 32 on each
/// placement of several (2 on each of a bundle's 30 fibres, a quarter piece either side of the
/// vertex), about the cost of 2.5 references of 128 (building a placement's fibres, not its
/// rays, is most of a reference's time); 128 on the one placement of one-fibre strands.
pub fn default_rays(placements: u32) -> u32 {
    if placements > 1 { 32 } else { 128 }
}

/// The exact-geometry variant of a hairstyle: K render strands of one fibre for every render
/// strand of F fibres.
pub fn single_fiber_variant(style: &Hairstyle, k: u32) -> Hairstyle {
    let mut s = style.clone();
    s.wisps.strands_per_wisp = s.wisps.strands_per_wisp.saturating_mul(k);
    s.strands.fibers_per_strand = 1.0;
    s.name = format!("{} (x{k} strands, 1 fibre each)", style.name);
    s
}

/// The placements a reference of `requested` placements averages for `style`: one when each
/// render strand is a single fibre (nothing to place: every seed gives the same bytes,
/// `tests/lib/map_exact.rs`), else `requested` (at least one).
pub fn placements_used(style: &Hairstyle, requested: u32) -> u32 {
    if style.strands.fibers_per_strand.round() <= 1.0 {
        1
    } else {
        requested.max(1)
    }
}

/// The exact reference's light at `vertices`, averaged over `placements` placements of each
/// bundle's fibres (`ExactInput::placement_seed` 0, the documented one, then 1, 2, …): the
/// light a render strand of F fibres receives when where its fibres lie inside the bundle is
/// not known, which is all the render strands say (ACCURACY.md §1, "One placement or the
/// ensemble"). Every field is the plain mean: T_f and the direct fraction are fractions of the
/// same rays, σ̄f² and the crossings behind are means over rays already. Seeds are summed in
/// order, so the result does not depend on the thread count.
pub fn ensemble_light(
    style: &Hairstyle,
    strands: &StrandGeometry,
    fiber: &Fiber,
    light: MapLight,
    vertices: &[usize],
    footprint: &Footprint,
    placements: u32,
) -> Vec<LightAtPoint> {
    let placed = |seed: u64| {
        exact_reference_placed(style, strands, fiber, light, seed)
            .light_at_vertices(vertices, footprint)
    };
    let mut sum = placed(0);
    for seed in 1..placements.max(1) as u64 {
        for (a, b) in sum.iter_mut().zip(placed(seed)) {
            a.direct_fraction += b.direct_fraction;
            a.tf += b.tf;
            a.sigma_f2 += b.sigma_f2;
            a.crossings_behind += b.crossings_behind;
        }
    }
    if placements > 1 {
        let k = placements as f32;
        for a in &mut sum {
            a.direct_fraction /= k;
            a.tf /= k;
            a.sigma_f2 /= k;
            a.crossings_behind /= k;
        }
    }
    sum
}

/// The key light (the first: its map is the one measured) in the map's terms.
pub fn key_light(engine: &Engine) -> MapLight {
    let key = engine.scene.lights[0];
    MapLight::of(&key, glam::Vec3::from(engine.pose().head.translation))
}

/// The exact reference for render strands `strands` of hairstyle `style` under `light`: F
/// fibres per render strand (the hairstyle's count rounded) within half the strand spacing,
/// binned across the light at half the strand spacing.
pub fn exact_reference<'a>(
    style: &Hairstyle,
    strands: &'a StrandGeometry,
    fiber: &'a Fiber,
    light: MapLight,
) -> ExactReference<'a> {
    exact_reference_placed(style, strands, fiber, light, 0)
}

/// [`exact_reference`] with the bundles' fibres placed by `placement_seed`
/// (`ExactInput::placement_seed`; 0 is the documented placement).
pub fn exact_reference_placed<'a>(
    style: &Hairstyle,
    strands: &'a StrandGeometry,
    fiber: &'a Fiber,
    light: MapLight,
    placement_seed: u64,
) -> ExactReference<'a> {
    ExactReference::build(
        &ExactInput {
            positions: &strands.positions,
            points_per_strand: strands.points_per_strand,
            fibers_per_strand: style.strands.fibers_per_strand.round().max(1.0) as u32,
            bundle_radius_m: 0.5 * style.strand_spacing_m(),
            placement_seed,
            fiber_share: &strands.fiber_share,
            light,
            fiber,
        },
        0.5 * style.strand_spacing_m(),
    )
}
