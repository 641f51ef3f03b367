//! Contact shadows (`map::contact`): the exact light a one-fibre vertex receives from the fibres
//! in a window in front of it. Checked against geometry (a fibre passing over the vertex's
//! point or beside it, the window's ends, the own-strand exclusion) and against the exact
//! reference's ray from the same point (`map::exact`, `Footprint::FibresLitSide` with one ray
//! for one fibre), which it must equal when the window holds everything.

use crate::common::*;
use glam::Vec3;
use proptest::prelude::*;
use wisp::accuracy::exact::{ExactInput, ExactReference, Footprint};
use wisp::hairstyle::SplitMix64;
use wisp::map::MapLight;
use wisp::map::contact::{ContactInput, ContactShadows};

/// Contact shadows of `positions` (strands of `ppl` points) for light travelling along `light`.
fn contact(
    positions: &[Vec3],
    ppl: usize,
    light: impl Into<MapLight>,
    window_m: f32,
    fiber: &wisp::fiber::Fiber,
) -> ContactShadows {
    let proj = light.into().projection(positions);
    ContactShadows::build(
        &ContactInput {
            positions,
            points_per_strand: ppl,
            fiber_share: &[],
            window_m,
            fiber,
        },
        &proj,
        0.002,
    )
}

/// A receiving strand along world Z at depth x = 0.01 (light along +X: behind the occluder),
/// 5 points 4 mm apart, and an occluder strand along Y at depth `x_occ` crossing the receiver's
/// middle point's piece at z = `z_occ`.
fn crossing(x_occ: f32, z_occ: f32) -> Vec<Vec3> {
    let mut p: Vec<Vec3> = (0..5)
        .map(|i| Vec3::new(0.01, 0.0, (i as f32 - 2.0) * 0.004))
        .collect();
    p.extend((0..5).map(|i| Vec3::new(x_occ, (i as f32 - 2.0) * 0.004 + 0.001, z_occ)));
    p
}

#[test]
fn a_crossing_fiber_shadows_the_vertex_it_passes_over() {
    let fiber = default_fiber();
    let r = fiber.params().radius_m;
    let a_f = fiber.forward_scatter(0.0).a_f;
    let beta = fiber.forward_scatter(0.0).beta_f2;
    // The occluder (radius r) lies 5 mm in front of vertex 2 (at z = 0), inside a 10 mm
    // window. Passing within r of the vertex's point, it covers it: one crossing, the light
    // its ā_f, no direct light.
    let c = contact(&crossing(0.005, 0.3 * r), 5, Vec3::X, 0.01, &fiber);
    let l = c.near_light(2, 1.0, 0.0);
    println!("covered: {l:?}");
    assert_eq!(l.direct_fraction, 0.0);
    assert!((l.tf - a_f).abs().max_element() < 1e-6, "{} vs {a_f}", l.tf);
    assert!((l.sigma_f2 - beta).abs().max_element() < 1e-7);
    assert!((l.crossings - 1.0).abs() < 1e-6);
    // 1.5 r beside the point it misses it, though it crosses the vertex's piece.
    let c = contact(&crossing(0.005, 1.5 * r), 5, Vec3::X, 0.01, &fiber);
    assert_eq!(
        c.near_light(2, 1.0, 0.0),
        wisp::map::contact::NearLight::CLEAR
    );
    // Over vertex 3's point (z = 4 mm) it shadows vertex 3, not vertex 2.
    let c = contact(&crossing(0.005, 0.004), 5, Vec3::X, 0.01, &fiber);
    assert_eq!(c.near_light(2, 1.0, 0.0).direct_fraction, 1.0);
    assert_eq!(c.near_light(3, 1.0, 0.0).direct_fraction, 0.0);
    // Outside the window (15 mm in front of a 10 mm window) or behind the vertex: no shadow.
    for x in [-0.005, 0.02] {
        let c = contact(&crossing(x, 0.0), 5, Vec3::X, 0.01, &fiber);
        assert_eq!(
            c.near_light(2, 1.0, 0.0),
            wisp::map::contact::NearLight::CLEAR,
            "{x}"
        );
    }
}

#[test]
fn the_light_is_read_on_the_fibers_lit_side() {
    // Light along +X, square to the receiver: its lit side is r toward the light (x − r). An
    // occluder passing over the point half a radius in front of the axis (render strands may
    // interpenetrate) shadows the axis but lies behind the lit surface: clear. One touching the
    // lit side (axis 2r in front) covers the surface where they touch; one r beside the light
    // ray through the axis misses the lit side's point by the same 1 r (so its own 1.5 r
    // grazing test above holds on the surface too).
    let fiber = default_fiber();
    let r = fiber.params().radius_m;
    let c = contact(&crossing(0.01 - 0.5 * r, 0.0), 5, Vec3::X, 0.01, &fiber);
    assert_eq!(
        c.near_light(2, 1.0, 0.0),
        wisp::map::contact::NearLight::CLEAR
    );
    let c = contact(&crossing(0.01 - 2.0 * r, 0.0), 5, Vec3::X, 0.01, &fiber);
    assert_eq!(c.near_light(2, 1.0, 0.0).direct_fraction, 0.0);
    // Light along the receiver (+Z after a turn of the occluder out of its way) has no lit
    // side across the fibre: the point stays on the axis, so the occluder half a radius in
    // front along the light still covers it.
    let mut p: Vec<Vec3> = (0..5)
        .map(|i| Vec3::new(0.0, 0.0, (i as f32 - 2.0) * 0.004))
        .collect();
    p.extend((0..5).map(|i| Vec3::new((i as f32 - 2.0) * 0.004 + 0.001, 0.0, -0.5 * r)));
    let c = contact(&p, 5, Vec3::Z, 0.01, &fiber);
    assert_eq!(c.near_light(2, 1.0, 0.0).direct_fraction, 0.0);
}

#[test]
fn a_strand_does_not_shadow_itself_nearby_but_does_when_it_curls_back() {
    let fiber = default_fiber();
    // A strand along Z at x = 0.01, then turning toward the light and back across its own
    // first point's piece 6 mm in front: points 0..3 along Z, 4.. a hairpin in front.
    let mut p: Vec<Vec3> = (0..4)
        .map(|i| Vec3::new(0.01, 0.0, i as f32 * 0.004))
        .collect();
    p.push(Vec3::new(0.004, 0.0, 0.012));
    p.push(Vec3::new(0.004, 0.0, 0.0005));
    p.push(Vec3::new(0.004, 0.0, -0.010));
    let c = contact(&p, p.len(), Vec3::X, 0.02, &fiber);
    // Point 1's neighbours (segments 0..=2) are its own; segment 5 passes right in front of
    // point 0 and 1 along their own line (the same y): it shadows them.
    let l0 = c.near_light(0, 1.0, 0.0);
    assert!(l0.direct_fraction < 1.0, "{l0:?}");
    // Point 3 is not crossed by the hairpin's later segments (they lie beside its piece), and
    // its neighbouring segments are excluded: clear.
    let l3 = c.near_light(3, 1.0, 0.0);
    assert_eq!(l3.direct_fraction, 1.0, "{l3:?}");
}

/// A random tangle of short one-fibre strands in a 6 mm box.
fn tangle(seed: u64, strands: usize, ppl: usize) -> Vec<Vec3> {
    let mut rng = SplitMix64::new(seed);
    let mut u = || rng.unit() * 2.0 - 1.0;
    let mut pts = Vec::new();
    for _ in 0..strands {
        let mut p = Vec3::new(u(), u(), u()) * 0.003;
        let mut d = Vec3::new(u(), u(), u()).normalize_or(Vec3::Z) * 0.0015;
        for _ in 0..ppl {
            pts.push(p);
            d = (d + Vec3::new(u(), u(), u()) * 0.0006).normalize_or(Vec3::Z) * 0.0015;
            p += d;
        }
    }
    pts
}

/// The exact reference of `positions` with one fibre per strand (the strand itself).
fn one_fiber_reference<'a>(
    positions: &'a [Vec3],
    ppl: usize,
    light: impl Into<MapLight>,
    fiber: &'a wisp::fiber::Fiber,
) -> ExactReference<'a> {
    ExactReference::build(
        &ExactInput {
            positions,
            points_per_strand: ppl,
            fibers_per_strand: 1,
            bundle_radius_m: 0.0,
            placement_seed: 0,
            fiber_share: &[],
            light: light.into(),
            fiber,
        },
        0.0005,
    )
}

#[test]
fn with_everything_in_the_window_it_is_the_exact_reference() {
    // With one fibre per strand and one ray, the reference's lit-side ray starts where contact
    // shadows read the light (the vertex's point moved by r to the fibre's lit side): the same
    // fibres cross the same ray, so the two agree to rounding.
    let fiber = default_fiber();
    let light = Vec3::new(0.4, -1.0, 0.3);
    let ppl = 8;
    let pos = tangle(7, 300, ppl);
    let c = contact(&pos, ppl, light, 1.0, &fiber);
    let reference = one_fiber_reference(&pos, ppl, light, &fiber);
    let (mut worst, mut shadowed) = (0.0f32, 0);
    for v in (0..pos.len()).step_by(3) {
        let near = c.near_light(v, 1.0, 0.0);
        let truth = reference.light_at_vertex(v, &Footprint::FibersLitSide { rays: 1 });
        assert!(near.tf.is_finite() && near.sigma_f2.is_finite());
        worst = worst.max((near.tf - truth.tf).abs().max_element());
        worst = worst.max((near.direct_fraction - truth.direct_fraction).abs());
        shadowed += (truth.direct_fraction < 0.99) as usize;
    }
    println!("worst |Δ| {worst}, {shadowed} vertices shadowed");
    assert!(shadowed > 50, "the tangle must shadow: {shadowed}");
    assert!(worst < 1e-4, "contact shadows vs exact reference: {worst}");
}

#[test]
fn under_a_point_light_it_is_the_exact_reference_too() {
    // A point light 5 cm from the tangle, off its axis: the lit side is taken toward the light
    // itself and narrowed with the projection's lateral scale, in both.
    let fiber = default_fiber();
    let light = MapLight::Point {
        position_m: Vec3::new(-0.03, 0.04, 0.01),
        aim_m: Vec3::new(0.001, 0.0, -0.001),
    };
    let ppl = 8;
    let pos = tangle(11, 300, ppl);
    let c = contact(&pos, ppl, light, 1.0, &fiber);
    let reference = one_fiber_reference(&pos, ppl, light, &fiber);
    let (mut worst, mut shadowed, mut moved) = (0.0f32, 0, 0);
    for v in (0..pos.len()).step_by(3) {
        let near = c.near_light(v, 1.0, 0.0);
        let truth = reference.light_at_vertex(v, &Footprint::FibersLitSide { rays: 1 });
        let axis = reference.light_at_vertex(v, &Footprint::Fibers { rays: 1 });
        worst = worst.max((near.tf - truth.tf).abs().max_element());
        worst = worst.max((near.direct_fraction - truth.direct_fraction).abs());
        shadowed += (truth.direct_fraction < 0.99) as usize;
        moved += (axis.direct_fraction != truth.direct_fraction) as usize;
    }
    println!("worst |Δ| {worst}, {shadowed} shadowed, {moved} differ from the axis ray");
    assert!(shadowed > 50, "the tangle must shadow: {shadowed}");
    assert!(
        moved > 0,
        "the lit side must differ from the axis somewhere"
    );
    assert!(worst < 1e-4, "contact shadows vs exact reference: {worst}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// A longer window takes more fibres: the light never grows, it stays in [0, 1] and
    /// finite, and the direct fraction is at most T_f.
    #[test]
    fn light_falls_as_the_window_grows(seed in 0u64..1_000_000, lx in -1.0f32..1.0, lz in -1.0f32..1.0) {
        let fiber = default_fiber();
        let light = Vec3::new(lx, -1.0, lz);
        let pos = tangle(seed, 60, 6);
        let windows = [0.001f32, 0.003, 0.01];
        let maps: Vec<_> = windows.iter().map(|w| contact(&pos, 6, light, *w, &fiber)).collect();
        for v in 0..pos.len() {
            let l: Vec<_> = maps.iter().map(|m| m.near_light(v, 1.0, 0.0)).collect();
            for x in &l {
                prop_assert!(x.tf.is_finite() && x.tf.min_element() >= 0.0 && x.tf.max_element() <= 1.0);
                prop_assert!(x.direct_fraction <= x.tf.min_element() + 1e-6);
            }
            for w in l.windows(2) {
                prop_assert!(w[1].direct_fraction <= w[0].direct_fraction + 1e-6);
                prop_assert!(w[1].tf.cmple(w[0].tf + Vec3::splat(1e-6)).all());
            }
        }
    }
}

#[test]
fn degenerate_strands_read_clear_or_finite() {
    let fiber = default_fiber();
    // A strand with coincident points, one along the light, one with a NaN point.
    let pos = vec![
        Vec3::ZERO,
        Vec3::ZERO,
        Vec3::ZERO,
        Vec3::new(-0.01, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.01, 0.0, 0.0),
        Vec3::new(0.0, f32::NAN, 0.0),
        Vec3::new(0.0, 0.0, 0.001),
        Vec3::new(0.0, 0.0, 0.002),
    ];
    let c = contact(&pos, 3, Vec3::X, 0.05, &fiber);
    for v in 0..pos.len() + 3 {
        let l = c.near_light(v, 1.0, 0.0);
        assert!(l.tf.is_finite() && l.direct_fraction.is_finite() && l.sigma_f2.is_finite());
    }
    assert_eq!(
        c.near_light(7, 1.0, 0.0),
        wisp::map::contact::NearLight::CLEAR
    );
}
