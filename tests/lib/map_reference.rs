//! How expected crossing counts become transmittance (DESIGN.md "Sweep"), measured against
//! ray shooting through explicit fibres.
//!
//! Fibres of radius r and length ℓ, perpendicular to the light, are scattered uniformly in a
//! slab. A ray along the light crosses a fibre when its lateral distance to the fibre's axis
//! is below r. Each ray's transmittance is ∏ ā_f over its crossings = ā_f^N; the reference is
//! the average over rays (what a map cell, averaging its column, should report). The map is
//! built from the same fibres (one sample each, F = 1) and read behind the slab.

use crate::common::*;
use glam::{Vec2, Vec3};
use wisp::hairstyle::SplitMix64;
use wisp::interp::StrandGeometry;
use wisp::map::{CountModel, LightFrame, LightMap, MapBuildInput, MapGeometry};

struct Fiber {
    centre: Vec2,
    dir: Vec2,
}

fn seg_dist(p: Vec2, f: &Fiber, half: f32) -> f32 {
    let t = (p - f.centre).dot(f.dir).clamp(-half, half);
    (p - (f.centre + f.dir * t)).length()
}

#[test]
fn poisson_average_matches_ray_shooting_and_mean_count_does_not() {
    let fiber = default_fiber();
    let r = fiber.params().radius_m;
    let ds = 0.002f32;
    let len = 0.001f32;
    let lateral_cells = 16.0;
    let width = lateral_cells * ds; // 32 mm
    // Mean crossings of a ray: N_f·ℓ·2r / width² = 3.
    let target_n = 3.0f32;
    let count = (target_n * width * width / (len * 2.0 * r)) as usize;
    let light = Vec3::NEG_X;
    let frame = LightFrame::new(light);
    let mut rng = SplitMix64::new(42);
    let mut fibers = Vec::with_capacity(count);
    let mut geo = StrandGeometry {
        points_per_strand: 1,
        ..Default::default()
    };
    for _ in 0..count {
        let x = (4.0 + 4.0 * rng.unit()) * ds; // slices 4..8
        let c = Vec2::new(rng.unit(), rng.unit()) * width;
        let a = std::f32::consts::TAU * rng.unit();
        let dir = Vec2::new(a.cos(), a.sin());
        geo.positions.push(frame.to_world(Vec3::new(x, c.x, c.y)));
        geo.tangents.push(frame.y * dir.x + frame.z * dir.y);
        geo.lengths_m.push(len);
        fibers.push(Fiber { centre: c, dir });
    }
    let a_f = fiber.forward_scatter(0.0).a_f;
    let build = |model| {
        let mut map = LightMap::new(
            MapGeometry {
                n: 64,
                ds_m: ds,
                lateral: 1,
            },
            model,
        );
        map.build(&MapBuildInput {
            positions: &geo.positions,
            tangents: &geo.tangents,
            lengths_m: &geo.lengths_m,
            fiber_share: &geo.fiber_share,
            fibers_per_strand: 1.0,
            light: light.into(),
            fiber: &fiber,
        });
        map
    };
    let (poisson, mean_count) = (build(CountModel::Poisson), build(CountModel::MeanCount));

    // Rays through the central 8x8 cells (away from the slab's lateral edges).
    let rays = 60;
    let (mut reference, mut direct_ref) = (Vec3::ZERO, 0.0f64);
    let (mut map_p, mut map_m, mut direct_map) = (Vec3::ZERO, Vec3::ZERO, 0.0f64);
    let mut crossings = 0usize;
    for a in 0..rays {
        for b in 0..rays {
            let p = Vec2::new(
                4.0 * ds + 8.0 * ds * (a as f32 + 0.5) / rays as f32,
                4.0 * ds + 8.0 * ds * (b as f32 + 0.5) / rays as f32,
            );
            let hits = fibers
                .iter()
                .filter(|f| seg_dist(p, f, 0.5 * len) < r)
                .count();
            crossings += hits;
            reference += a_f.powf(hits as f32);
            direct_ref += (hits == 0) as u8 as f64;
            let behind = frame.to_world(Vec3::new(12.0 * ds, p.x, p.y));
            let lp = poisson.light_at(behind);
            map_p += lp.tf;
            direct_map += lp.direct_fraction as f64;
            map_m += mean_count.light_at(behind).tf;
        }
    }
    let k = (rays * rays) as f32;
    let (reference, map_p, map_m) = (reference / k, map_p / k, map_m / k);
    let (direct_ref, direct_map) = (direct_ref / k as f64, direct_map / k as f64);
    let mean_hits = crossings as f32 / k;
    println!(
        "mean crossings {mean_hits:.3}; Tf reference {reference}, Poisson map {map_p}, mean-count map {map_m}; direct {direct_ref:.4} vs {direct_map:.4}"
    );
    assert!(
        (mean_hits - target_n).abs() < 0.3,
        "the scene is not what it claims: {mean_hits}"
    );
    // Monte Carlo error of the reference: rays are correlated within a cell, so allow 0.03
    // (about 3 standard errors of a 3,600-ray mean of values in [0, 1] with this spread).
    assert!(
        (map_p - reference).abs().max_element() < 0.03,
        "Poisson {map_p} vs rays {reference}"
    );
    assert!(
        (direct_map - direct_ref).abs() < 0.03,
        "direct {direct_map} vs rays {direct_ref}"
    );
    // The mean-count reading is systematically darker (Jensen: E[a^N] >= a^E[N]).
    assert!(
        ((map_m - reference).abs().max_element()) > 2.0 * (map_p - reference).abs().max_element()
    );
    assert!(map_m.cmplt(reference).all());
}
