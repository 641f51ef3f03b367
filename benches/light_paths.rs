//! The `final` level's shading on the smooth dance at 1280×720 (the state 4 s in), with its
//! light paths, against `preview`'s dual scattering on the same frame: the two numbers the
//! level table in BENCHMARKS.md compares, in rayon pools of 1 and 2 threads.
//!
//! Run: `cargo bench --bench light_paths -- --quick`.

use criterion::{Criterion, criterion_group, criterion_main};
use wisp::engine::{Engine, EngineConfig, Quality};
use wisp::fiber::ShadingMode;
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

const START_S: f64 = 4.0;

fn light_paths(c: &mut Criterion) {
    let mut group = c.benchmark_group("shade_final");
    group.sample_size(10);
    for threads in [1usize, 2] {
        let Ok(pool) = rayon::ThreadPoolBuilder::new().num_threads(threads).build() else {
            eprintln!("cannot build a pool of {threads} threads; skipped");
            continue;
        };
        for (name, mode) in [
            ("light_paths", ShadingMode::Volume),
            ("dual", ShadingMode::DualScattering),
        ] {
            let mut config = EngineConfig::sized(1280, 720);
            config.apply_quality(Quality::Final);
            config.shading.mode = mode;
            let mut engine = pool.install(|| {
                let mut e =
                    Engine::new(Hairstyle::default_smooth(), Motion::default_dance(), config);
                e.run_up_to(START_S);
                e.frame(START_S);
                e
            });
            group.bench_function(format!("{name}/threads_{threads}"), |b| {
                pool.install(|| b.iter(|| engine.shade()))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, light_paths);
criterion_main!(benches);
