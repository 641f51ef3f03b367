//! The whole frame (animation, simulation, interpolation, map, shading, raster) of the
//! embedded dance at 800x800, smooth and curly, in rayon pools of 1 and 2 threads.

use criterion::{Criterion, criterion_group, criterion_main};
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

fn bench_frame(c: &mut Criterion) {
    let mut group = c.benchmark_group("frame");
    group.sample_size(10);
    for style in [Hairstyle::default_smooth(), Hairstyle::default_curly()] {
        for threads in [1usize, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool");
            let name = format!("{}/threads_{threads}", style.name);
            let mut engine = pool.install(|| {
                Engine::new(
                    style.clone(),
                    Motion::default_dance(),
                    EngineConfig::default(),
                )
            });
            let mut t = 0.0;
            group.bench_function(&name, |b| {
                pool.install(|| {
                    b.iter(|| {
                        t += 1.0 / 30.0;
                        engine.frame(t).width
                    })
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench_frame);
criterion_main!(benches);
