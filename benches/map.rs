//! Light-oriented map: build (fill + sort + sweep) and filtered lookups, smooth and curly rest
//! poses, in rayon pools of 1 and 2 threads.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use std::hint::black_box;
use wisp::fiber::{Fiber, FiberParams};
use wisp::hairstyle::{Hairstyle, generate};
use wisp::interp::{StrandGeometry, interpolate};
use wisp::map::{CountModel, LightMap, MapBuildInput, MapGeometry};

fn strands(style: &Hairstyle) -> StrandGeometry {
    let (g, layout) = generate(style);
    let mut geo = StrandGeometry::default();
    interpolate(&g, &layout, &style.curl, &g.rest, &mut geo);
    geo
}

fn bench_map(c: &mut Criterion) {
    let fiber = Fiber::new(&FiberParams::default());
    let light = Vec3::new(-0.75, -0.55, -0.35);
    for style in [Hairstyle::default_smooth(), Hairstyle::default_curly()] {
        let geo = strands(&style);
        let geom = MapGeometry::with_resolution(
            MapGeometry::span_m(style.max_length_m(), style.head_size_m()),
            128,
        );
        for threads in [1usize, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool");
            let mut map = LightMap::new(geom, CountModel::Poisson);
            let input = MapBuildInput {
                positions: &geo.positions,
                tangents: &geo.tangents,
                lengths_m: &geo.lengths_m,
                fiber_share: &geo.fiber_share,
                fibers_per_strand: style.strands.fibers_per_strand,
                light: light.into(),
                fiber: &fiber,
            };
            c.bench_function(
                &format!("map_build/{}/threads_{threads}", style.name),
                |b| pool.install(|| b.iter(|| map.build(black_box(&input)))),
            );
            c.bench_function(
                &format!("map_lookup_all_vertices/{}/threads_{threads}", style.name),
                |b| {
                    pool.install(|| {
                        b.iter(|| {
                            use rayon::prelude::*;
                            geo.positions
                                .par_iter()
                                .map(|p| map.light_at(*p).tf.x)
                                .sum::<f32>()
                        })
                    })
                },
            );
        }
    }
}

criterion_group!(benches, bench_map);
criterion_main!(benches);
