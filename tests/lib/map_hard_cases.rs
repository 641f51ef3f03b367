//! The map where it breaks: all hair in one cell, degenerate samples, fibres along the light,
//! zero and huge absorption, light along an axis. No NaN or infinity may come out.

use glam::Vec3;
use wisp::fiber::{Fiber, FiberParams, LightAtPoint};
use wisp::map::{CountModel, LightMap, MapBuildInput, MapGeometry};

fn build(
    fiber: &Fiber,
    pos: &[Vec3],
    tan: &[Vec3],
    len: &[f32],
    light: Vec3,
    fibers: f32,
) -> LightMap {
    let mut map = LightMap::new(
        MapGeometry {
            n: 64,
            ds_m: 0.01,
            lateral: 1,
        },
        CountModel::Poisson,
    );
    map.build(&MapBuildInput {
        positions: pos,
        tangents: tan,
        lengths_m: len,
        fiber_share: &[],
        fibers_per_strand: fibers,
        light: light.into(),
        fiber,
    });
    map
}

fn valid(l: &LightAtPoint) -> bool {
    (0.0..=1.0).contains(&l.direct_fraction)
        && l.tf.cmpge(Vec3::ZERO).all()
        && l.tf.cmple(Vec3::ONE).all()
        && l.sigma_f2.is_finite()
        && l.sigma_f2.cmpge(Vec3::ZERO).all()
}

fn probes() -> Vec<Vec3> {
    let mut v = Vec::new();
    for i in -3..=3 {
        for j in -3..=3 {
            v.push(Vec3::new(
                i as f32 * 0.013,
                j as f32 * 0.011,
                0.004 * i as f32,
            ));
        }
    }
    v
}

#[test]
fn two_hundred_million_fibers_in_one_cell_give_black_not_nan() {
    let fiber = Fiber::new(&FiberParams::default());
    let n = 200_000;
    let pos = vec![Vec3::new(0.001, 0.002, 0.003); n];
    let tan = vec![Vec3::Z; n];
    let len = vec![0.005; n];
    let light = Vec3::new(0.0, -1.0, 0.1).normalize();
    let map = build(&fiber, &pos, &tan, &len, light, 1000.0);
    // One position, shared by the four columns around it (the bilinear splat).
    assert!(
        (1..=4).contains(&map.stats().filled_cells),
        "{}",
        map.stats().filled_cells
    );
    // Straight behind the cell's centre, where the lateral filter reads that column alone.
    let (_, centre) = map.cell_density(pos[0]).expect("the cell is filled");
    let behind = map.light_at(centre + light * 0.05);
    assert!(valid(&behind));
    assert!(behind.direct_fraction < 1e-5, "{}", behind.direct_fraction);
    assert!(behind.tf.max_element() < 1e-6, "{}", behind.tf);
    assert!(map.stats().peak_volume_fraction.is_finite());
    for p in probes() {
        assert!(valid(&map.light_at(p)));
    }
}

#[test]
fn degenerate_samples_and_fibers_along_the_light() {
    let fiber = Fiber::new(&FiberParams::default());
    let light = Vec3::new(0.0, -1.0, 0.0);
    let pos = vec![
        Vec3::ZERO,
        Vec3::new(0.0, 0.01, 0.0),
        Vec3::new(0.02, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 0.02),
    ];
    // Zero length, zero tangent, tangent exactly along the light, tangent against it.
    let tan = vec![Vec3::X, Vec3::ZERO, Vec3::NEG_Y, Vec3::Y];
    let len = vec![0.0, 0.01, 0.01, 0.01];
    let map = build(&fiber, &pos, &tan, &len, light, 30.0);
    for p in probes() {
        let l = map.light_at(p);
        assert!(valid(&l), "{l:?}");
    }
    // A fibre along the light has no cross-section to it: nothing is shadowed behind it.
    let behind = map.light_at(Vec3::new(0.02, -0.05, 0.0));
    assert!(
        (behind.tf - Vec3::ONE).abs().max_element() < 1e-6,
        "{}",
        behind.tf
    );
}

#[test]
fn zero_and_huge_absorption() {
    let pos: Vec<Vec3> = (0..400)
        .map(|i| Vec3::new((i % 20) as f32 * 0.001, 0.0, (i / 20) as f32 * 0.001))
        .collect();
    let tan = vec![Vec3::X; pos.len()];
    let len = vec![0.002; pos.len()];
    let behind = Vec3::new(0.01, -0.05, 0.01);
    let mut results = Vec::new();
    for sigma in [0.0f32, 100.0] {
        let fiber = Fiber::new(&FiberParams {
            sigma_a: [sigma; 3],
            ..FiberParams::default()
        });
        let map = build(&fiber, &pos, &tan, &len, Vec3::NEG_Y, 50.0);
        let l = map.light_at(behind);
        assert!(valid(&l), "sigma_a {sigma}: {l:?}");
        results.push(l);
    }
    // Clear fibres scatter forward most of the light; opaque ones pass only the no-crossing
    // rays, so T_f falls to the direct fraction.
    assert!(results[0].tf.min_element() > results[1].tf.max_element());
    assert!(
        (results[1].tf - Vec3::splat(results[1].direct_fraction))
            .abs()
            .max_element()
            < 0.02,
        "{:?}",
        results[1]
    );
}
