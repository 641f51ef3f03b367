//! The cell convention and the filter agree (Bertails 2005 §3.2-3.3): a flat slab of hair
//! perpendicular to the light reads exactly 1 in front of it, the analytic attenuation at every
//! face behind it and, inside a cell, the attenuation of the hair in front of the point only;
//! and the light never grows along the light direction.

use crate::common::*;
use glam::Vec3;
use wisp::hairstyle::Hairstyle;
use wisp::map::{LightFrame, MapGeometry};

const DS: f32 = 1.0 / 128.0;
const FIBERS: f32 = 20.0;
const LEN: f32 = 0.002;
/// Samples per cell: a 2x2x2 lattice.
const PER_CELL: f32 = 8.0;

#[test]
fn slab_reads_one_in_front_and_the_analytic_attenuation_behind() {
    let light = Vec3::new(0.3, -1.0, 0.2);
    let frame = LightFrame::new(light);
    let fiber = default_fiber();
    let map = build_map(
        &slab(&frame, 10..14, DS, LEN),
        &fiber,
        MapGeometry {
            n: 128,
            ds_m: DS,
            lateral: 1,
        },
        light,
        FIBERS,
    );
    // Expected crossings per cell: 8 samples x F·ℓ·2r / ds² (fibres perpendicular to L).
    let r = fiber.params().radius_m;
    let n_cell = PER_CELL * FIBERS * LEN * 2.0 * r / (DS * DS);
    let fs = fiber.forward_scatter(0.0);
    let expect = |cells: f32| {
        let n = cells * n_cell;
        (
            (-n).exp(),
            (-(Vec3::ONE - fs.a_f) * n).exp(),
            fs.beta_f2 * n,
        )
    };
    let at = |x_cells: f32| map.light_at(frame.to_world(Vec3::new(x_cells, 0.3, -0.6) * DS));
    // In front, and exactly at the entry face: no attenuation at all.
    for x in [2.0, 9.0, 9.99, 10.0] {
        let l = at(x);
        assert_eq!(
            (l.direct_fraction, l.tf, l.sigma_f2),
            (1.0, Vec3::ONE, Vec3::ZERO),
            "x = {x} cells"
        );
    }
    // At each face inside and behind: the analytic values after the cells crossed.
    for (x, cells) in [
        (11.0, 1.0),
        (12.0, 2.0),
        (14.0, 4.0),
        (20.0, 4.0),
        (60.0, 4.0),
    ] {
        let l = at(x);
        let (d, tf, s2) = expect(cells);
        assert!(
            (l.direct_fraction - d).abs() < 1e-5 * d.max(1e-3),
            "x {x}: direct {} vs {d}",
            l.direct_fraction
        );
        assert!(
            (l.tf - tf).abs().max_element() < 1e-5,
            "x {x}: Tf {} vs {tf}",
            l.tf
        );
        assert!(
            (l.sigma_f2 - s2).abs().max_element() < 1e-5 * s2.max_element().max(1e-6),
            "x {x}"
        );
    }
    // Inside a cell, a point receives only the crossings in front of it: the slab's samples
    // lie in two planes at 1/4 and 3/4 of each cell, so a point at 1/10 of cell 12 has crossed
    // two cells, at 1/2 two and a half, at 9/10 three (a filter linear through the cell, as
    // Bertails §3.3, would give 2.1, 2.5 and 2.9). The cell stores its shares in 1/255.
    for (x, cells) in [(12.1, 2.0), (12.5, 2.5), (12.9, 3.0)] {
        let l = at(x);
        let (d, tf, _) = expect(cells);
        let tol = n_cell / 255.0; // one quantisation step of a cell's crossings
        assert!(
            (l.direct_fraction / d).ln().abs() < tol,
            "x {x}: direct {} vs {d}",
            l.direct_fraction
        );
        assert!(
            ((l.tf / tf).abs().max_element().ln()).abs() < tol,
            "x {x}: Tf {} vs {tf}",
            l.tf
        );
    }
    // The slab is thick enough to matter.
    assert!(
        expect(4.0).0 < 0.5,
        "direct fraction behind the slab {}",
        expect(4.0).0
    );
}

#[test]
fn light_never_increases_along_the_light_in_any_column() {
    let style = Hairstyle::default_curly();
    let geo = rest_strands(&style);
    let fiber = default_fiber();
    let light = Vec3::new(-0.5, -0.7, 0.5);
    let frame = LightFrame::new(light);
    let geom = MapGeometry::with_resolution(
        MapGeometry::span_m(style.max_length_m(), style.head_size_m()),
        96,
    );
    let map = build_map(&geo, &fiber, geom, light, style.strands.fibers_per_strand);
    // Rays along the light through a lattice of lateral positions covering the hair, stepping
    // a seventh of a cell (so every cell and both filter regimes are visited).
    let lo = geo
        .positions
        .iter()
        .fold(Vec3::splat(f32::MAX), |a, p| a.min(frame.to_map(*p)));
    let hi = geo
        .positions
        .iter()
        .fold(Vec3::splat(f32::MIN), |a, p| a.max(frame.to_map(*p)));
    let mut rays = 0;
    let mut darkened = 0;
    for a in 0..40 {
        for b in 0..40 {
            let y = lo.y + (hi.y - lo.y) * (a as f32 + 0.5) / 40.0;
            let z = lo.z + (hi.z - lo.z) * (b as f32 + 0.5) / 40.0;
            let mut prev = map.light_at(frame.to_world(Vec3::new(lo.x - geom.ds_m, y, z)));
            // Tolerance 1e-5: the 8-term blend of equal face values rounds by a few ulps, and
            // each point's lateral map coordinates go through world coordinates in f32, which
            // moves the lateral filter weights by ~1e-5 cells between steps (seen as drops of σ²
            // up to 4e-5 relative next to columns with much larger σ²; on the smooth preset
            // with fanned tips, whose lone tips make steeper lateral steps, up to 7e-4 relative
            // at σ² 2.5e-3, ray (4,14)); hence 2e-3 relative for σ². The exact, per-column
            // statement is `map::tests::every_column_is_monotonic`.
            let steps = ((hi.x - lo.x) / geom.ds_m * 7.0) as usize + 14;
            for s in 0..steps {
                let x = lo.x - geom.ds_m + s as f32 * geom.ds_m / 7.0;
                let l = map.light_at(frame.to_world(Vec3::new(x, y, z)));
                assert!(
                    l.direct_fraction <= prev.direct_fraction + 1e-5,
                    "ray ({a},{b}) step {s} of {steps}: {} after {}, x {x}",
                    l.direct_fraction,
                    prev.direct_fraction
                );
                assert!(
                    l.tf.cmple(prev.tf + Vec3::splat(1e-5)).all(),
                    "Tf grew at ray ({a},{b}) step {s}"
                );
                assert!(
                    l.sigma_f2
                        .cmpge(prev.sigma_f2 * (1.0 - 2e-3) - Vec3::splat(1e-6))
                        .all(),
                    "σ² fell at ray ({a},{b}) step {s}: {} after {}",
                    l.sigma_f2,
                    prev.sigma_f2
                );
                prev = l;
            }
            rays += 1;
            darkened += (prev.tf.x < 0.9) as usize;
        }
    }
    assert_eq!(rays, 1600);
    assert!(
        darkened > 100,
        "only {darkened} rays were shadowed: the test would prove nothing"
    );
}
