//! Unit tests of the map's sweep and filter on hand-made columns.

use super::*;
use crate::fiber::{Fiber, FiberParams, LightAtPoint};

fn fiber() -> Fiber {
    Fiber::new(&FiberParams::default())
}

/// One sample per point, all fibres perpendicular to the light (which travels along +X).
fn build(points: &[Vec3], len: f32, n: u32, ds: f32) -> LightMap {
    let f = fiber();
    let mut map = LightMap::new(
        MapGeometry {
            n,
            ds_m: ds,
            lateral: 1,
        },
        CountModel::Poisson,
    );
    let tangents = vec![Vec3::Y; points.len()];
    let lengths = vec![len; points.len()];
    map.build(&MapBuildInput {
        positions: points,
        tangents: &tangents,
        lengths_m: &lengths,
        fiber_share: &[],
        fibers_per_strand: 10.0,
        light: Vec3::X.into(),
        fiber: &f,
    });
    map
}

/// Unshadowed light with no hair behind the point either (no back-scatter to expect).
const OPEN: LightAtPoint = LightAtPoint {
    crossings_behind: 0.0,
    ..LightAtPoint::UNSHADOWED
};

#[test]
fn empty_map_is_unshadowed_everywhere() {
    let map = build(&[], 0.01, 16, 0.01);
    assert_eq!(map.stats().filled_cells, 0);
    assert_eq!(map.light_at(Vec3::new(0.3, 0.1, -0.2)), OPEN);
    assert!(map.cell_density(Vec3::ZERO).is_none());
}

#[test]
fn merge_counts_cells_and_sweep_is_monotonic() {
    let ds = 0.01;
    // Three samples in one cell, two in the next along the light, one far behind.
    let pts = [
        Vec3::new(0.001, 0.005, 0.005),
        Vec3::new(0.002, 0.005, 0.005),
        Vec3::new(0.003, 0.005, 0.005),
        Vec3::new(0.012, 0.005, 0.005),
        Vec3::new(0.015, 0.005, 0.005),
        Vec3::new(0.095, 0.005, 0.005),
    ];
    let map = build(&pts, 0.01, 16, ds);
    assert_eq!(map.stats().filled_cells, 3);
    assert_eq!(map.stats().columns, 1);
    let c0 = map.cell_coords(pts[0]).floor();
    let col = map.column_cells(map.column(c0.y as i64, c0.z as i64));
    let live: Vec<&Cell> = col.iter().filter(|c| c.slice != u32::MAX).collect();
    assert_eq!(
        live.iter().map(|c| c.slice).collect::<Vec<_>>(),
        vec![0, 1, 9]
    );
    for w in live.windows(2) {
        assert!(w[1].n_sum >= w[0].n_sum);
        for ch in 0..3 {
            assert!(w[1].loss[ch] >= w[0].loss[ch]);
            assert!(w[1].sigma2[ch] >= w[0].sigma2[ch]);
        }
    }
    // Volume fraction of the first cell: 3 samples x F·ℓ·πr² / ds³.
    let r = FiberParams::default().radius_m;
    let expect = 3.0 * 10.0 * 0.01 * std::f32::consts::PI * r * r / (ds * ds * ds);
    let (vf, centre) = map.cell_density(pts[0]).unwrap();
    assert!((vf / expect - 1.0).abs() < 1e-5, "{vf} vs {expect}");
    let frac = map.cell_coords(centre) - c0;
    assert!(
        (frac - Vec3::splat(0.5)).abs().max_element() < 1e-4,
        "{frac}"
    );
}

#[test]
fn non_finite_samples_are_skipped_and_never_reach_a_lookup() {
    let pts = [
        Vec3::new(f32::NAN, 0.0, 0.0),
        Vec3::splat(f32::INFINITY),
        Vec3::new(0.001, 0.001, 0.001),
    ];
    let map = build(&pts, 0.01, 8, 0.01);
    assert_eq!(map.stats().skipped, 2);
    assert_eq!(map.stats().samples, 1);
    for p in [Vec3::NAN, Vec3::splat(1e30), Vec3::new(0.02, 0.001, 0.001)] {
        let l = map.light_at(p);
        assert!(l.direct_fraction.is_finite() && l.tf.is_finite() && l.sigma_f2.is_finite());
    }
}

#[test]
fn overflow_is_reported_when_hair_exceeds_the_span() {
    let pts = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.5, 0.0)];
    assert!(build(&pts, 0.01, 8, 0.01).stats().overflow);
    let pts = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.05, 0.0)];
    assert!(!build(&pts, 0.01, 8, 0.01).stats().overflow);
}

#[test]
fn every_column_is_monotonic_exactly() {
    // Bertails §3.2: along a column, light only decreases. The sweep adds non-negative terms
    // (the cells hold running sums; the lookup takes exp(−sum), which is monotonic), so the
    // sums never decrease, exactly, without tolerance, in every column.
    use crate::hairstyle::{Hairstyle, generate};
    use crate::interp::{StrandGeometry, interpolate};
    let style = Hairstyle::default_curly();
    let (g, layout) = generate(&style);
    let mut geo = StrandGeometry::default();
    interpolate(&g, &layout, &style.curl, &g.rest, &mut geo);
    let f = fiber();
    let mut map = LightMap::new(
        MapGeometry {
            n: 128,
            ds_m: 0.007,
            lateral: 1,
        },
        CountModel::Poisson,
    );
    map.build(&MapBuildInput {
        positions: &geo.positions,
        tangents: &geo.tangents,
        lengths_m: &geo.lengths_m,
        fiber_share: &geo.fiber_share,
        fibers_per_strand: style.strands.fibers_per_strand,
        light: Vec3::new(-0.5, -0.7, 0.5).into(),
        fiber: &f,
    });
    let cols = (map.geom.n * map.geom.n) as usize;
    let mut checked = 0;
    for c in 0..cols {
        let live: Vec<&Cell> = map
            .column_cells(c)
            .iter()
            .filter(|c| c.slice != u32::MAX)
            .collect();
        for w in live.windows(2) {
            assert!(w[0].slice < w[1].slice);
            assert!(w[1].n_sum >= w[0].n_sum);
            for ch in 0..3 {
                assert!(w[1].loss[ch] >= w[0].loss[ch]);
                assert!(w[1].sigma2[ch] >= w[0].sigma2[ch]);
            }
            checked += 1;
        }
        for cell in &live {
            // Losses n(1 − ā_f) never exceed crossings n, so T_f = exp(−loss) ≥ exp(−n).
            assert!(cell.n_sum >= 0.0);
            assert!(cell.loss.iter().all(|l| (0.0..=cell.n_sum).contains(l)));
            // The depth shares are a cumulative distribution.
            assert!(cell.depth_cdf.windows(2).all(|w| w[0] <= w[1]));
        }
    }
    assert!(
        checked > 10_000,
        "only {checked} cell pairs: the scene is too sparse to prove much"
    );
}

#[test]
fn a_point_inside_a_cell_receives_only_the_crossings_in_front_of_it() {
    // Two samples in one cell of 10 mm along the light (+X): one near the light-side face, one
    // near the far face. A point between them is shadowed by the first only; a point behind
    // both by both; a point before both by none. A uniform spread through the cell would give
    // the middle point half of both instead.
    let ds = 0.01;
    let pts = [
        Vec3::new(0.002, 0.005, 0.005),
        Vec3::new(0.008, 0.005, 0.005),
    ];
    let map = build(&pts, 0.01, 16, ds);
    let one = map.light_at(Vec3::new(0.0095, 0.005, 0.005)); // behind both (same cell)
    let mid = map.light_at(Vec3::new(0.005, 0.005, 0.005));
    let front = map.light_at(Vec3::new(0.0005, 0.005, 0.005));
    // Expected crossings per sample: F·ℓ·2r·sinψ/ds² with F = 10, ℓ = 1 cm, ψ = 90°.
    let r = FiberParams::default().radius_m;
    let n = 10.0 * 0.01 * 2.0 * r / (ds * ds);
    let exp = |k: f32| (-k * n).exp();
    assert!((front.direct_fraction - 1.0).abs() < 1e-6, "{front:?}");
    // Sub-slices are 1.25 mm: the samples lie in sub-slices 1 and 6, the points in 0, 4 and 7,
    // so each point is exactly before or past each sample (up to the shares' 1/255 steps:
    // 0.5 is stored as 128/255, 0.4% of the cell's 2n crossings).
    assert!(
        (mid.direct_fraction - exp(1.0)).abs() < 1e-3,
        "{} vs {}",
        mid.direct_fraction,
        exp(1.0)
    );
    assert!(
        (one.direct_fraction - exp(2.0)).abs() < 1e-4,
        "{} vs {}",
        one.direct_fraction,
        exp(2.0)
    );
}

/// A tapered tip: a sample with a share s of its strand's fibres stands for its whole piece of
/// strand with s times the crossings, so it shadows the same cells as a full sample, each with
/// s times the optical depth. A fill that took `lengths_m` (= piece × s) as the piece's extent
/// would pack a tip's crossings into s of its length: behind the piece's ends it would cast no
/// shadow, and the cells at its middle would be 1/s too dark.
#[test]
fn a_tapered_sample_spreads_its_crossings_along_its_whole_piece() {
    let ds = 0.01;
    let piece_m = 0.04;
    let share = 0.25;
    let f = fiber();
    let build_one = |lengths_m: f32, fiber_share: &[f32]| {
        let mut map = LightMap::new(
            MapGeometry {
                n: 16,
                ds_m: ds,
                lateral: 1,
            },
            CountModel::Poisson,
        );
        map.build(&MapBuildInput {
            // The piece runs across the light (+X) along Y, over four columns.
            positions: &[Vec3::new(0.005, 0.04, 0.005)],
            tangents: &[Vec3::Y],
            lengths_m: &[lengths_m],
            fiber_share,
            fibers_per_strand: 10.0,
            light: Vec3::X.into(),
            fiber: &f,
        });
        map
    };
    let full = build_one(piece_m, &[]);
    let tip = build_one(piece_m * share, &[share]);
    // Behind the piece (next slice), at the column centres it spans.
    for y in [0.025, 0.035, 0.045, 0.055] {
        let p = Vec3::new(0.015, y, 0.005);
        let (a, b) = (full.light_at(p).tf, tip.light_at(p).tf);
        for c in 0..3 {
            let (la, lb) = (a[c].ln(), b[c].ln());
            assert!(la < -0.005, "y {y}: the full piece shadows here ({})", a[c]);
            assert!(
                (lb / la - share).abs() < 0.01,
                "y {y}, channel {c}: optical depth {lb} against {la} × {share}"
            );
        }
    }
}

/// An empty map (no hair) with a sphere of radius 2 cm at the origin in its solids' grid; light
/// along +X.
fn map_with_a_sphere() -> (LightMap, crate::map::OccluderGrid) {
    let hair = build(&[Vec3::new(0.3, 0.3, 0.3)], 0.01, 64, 0.01);
    let mut solids = crate::map::OccluderGrid::default();
    let sphere = crate::map::Solid {
        unit_sphere_to_world: glam::Affine3A::from_scale(Vec3::splat(0.02)),
    };
    solids.build_for(&hair, 0.25, &[sphere], crate::map::OccluderMesh::EMPTY);
    (hair, solids)
}

#[test]
fn occluders_shadow_what_lies_behind_them() {
    let (hair, solids) = map_with_a_sphere();
    let map = crate::map::Shadow {
        hair: &hair,
        solids: &solids,
        skin: None,
        earlier: None,
    };
    assert!(map.light_at(Vec3::new(0.05, 0.0, 0.0)).direct_fraction < 1e-6);
    assert_eq!(map.light_at(Vec3::new(0.05, 0.0, 0.0)).tf, Vec3::ZERO);
    assert_eq!(map.light_at(Vec3::new(-0.05, 0.0, 0.0)), OPEN);
    assert_eq!(map.light_at(Vec3::new(0.05, 0.03, 0.0)), OPEN);
    // The lit surface itself, moved off by the surface offset as skin shading does, is lit.
    let n = Vec3::new(-1.0, 0.3, 0.0).normalize();
    let p = n * 0.02 + n * map.surface_offset_m();
    assert!(map.light_at(p).direct_fraction > 0.999);
}

/// Shadows built for an earlier frame (`BuiltEarlier`) read a render-strand point where it
/// was then and any other hair point carried back with the head; surface points where they
/// are. Light along +X, a sphere of 2 cm at the origin shadows x > 0.
#[test]
fn shadows_built_earlier_read_the_hair_where_it_was() {
    use crate::map::BuiltEarlier;
    let (hair, solids) = map_with_a_sphere();
    let (shadowed, open) = (Vec3::new(0.05, 0.0, 0.0), Vec3::new(-0.05, 0.0, 0.0));
    // Since the build the head moved 0.1 m along +X: a point now at `shadowed` + 0.1 was at
    // `shadowed`; vertex 0 was at `shadowed` and is now in the open.
    let positions = [shadowed];
    let map = crate::map::Shadow {
        hair: &hair,
        solids: &solids,
        skin: None,
        earlier: Some(BuiltEarlier {
            positions: &positions,
            head_back: glam::Affine3A::from_translation(Vec3::new(-0.1, 0.0, 0.0)),
        }),
    };
    let (x, y) = (Vec3::X, Vec3::Y);
    assert!(
        map.light_at_vertex_seen(0, open, -x, y, 4e-5)
            .direct_fraction
            < 1e-6
    );
    assert!(map.light_at(shadowed + 0.1 * x).direct_fraction < 1e-6);
    assert_eq!(map.light_at(shadowed), OPEN, "carried back to x = -0.05");
    // A vertex index past the recorded ones is carried back with the head.
    assert!(
        map.light_at_vertex_seen(7, shadowed + 0.1 * x, -x, y, 4e-5)
            .direct_fraction
            < 1e-6
    );
    // Surfaces are read where they are.
    assert!(map.solid_visibility(shadowed) < 1e-6);
    assert!(map.solid_visibility(open) > 0.999);
}
