//! Each stage of the engine and the whole frame, at 1280×720, for the three scenes of issue
//! 12: `smooth` and `curly` dancing (the state 4 s into the embedded dance), and `dense` (the
//! generated preset of 87,502 one-fibre strands, 1.14 M segments) on a still head (as
//! `--still`: no body); in rayon pools
//! of 1 and 2 threads.
//!
//! - `advance`: animation, simulation and interpolation of one more 1/30 s frame;
//! - `map`: the light map rebuilt from the current hair (its reuse for unchanged input is
//!   defeated, so the build is timed even for the still scene);
//! - `shade`: every vertex's colour; `raster`: the solids and the hair drawn;
//! - `frame`: all of it (for the still scene, with the map rebuilt as if the hair had moved).
//!
//! Run: `cargo bench --bench stages -- --quick` (a filter such as `dense` narrows it).

use criterion::{Criterion, criterion_group, criterion_main};
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

const FRAME_S: f64 = 1.0 / 30.0;
const START_S: f64 = 4.0;

fn stages(c: &mut Criterion) {
    let mut group = c.benchmark_group("stages");
    group.sample_size(10);
    let scenes = [
        (Hairstyle::default_smooth(), false),
        (Hairstyle::default_curly(), false),
        (Hairstyle::dense(), true),
    ];
    for (style, still) in scenes {
        for threads in [1usize, 2] {
            let Ok(pool) = rayon::ThreadPoolBuilder::new().num_threads(threads).build() else {
                eprintln!("cannot build a pool of {threads} threads; skipped");
                continue;
            };
            let config = EngineConfig::sized(1280, 720);
            let motion = if still {
                Motion::still(glam::Affine3A::IDENTITY)
            } else {
                Motion::default_dance()
            };
            let mut engine = pool.install(|| {
                let mut e = Engine::new(style.clone(), motion, config);
                e.run_up_to(START_S);
                e.frame(START_S);
                e
            });
            let id = |stage: &str| format!("{stage}/{}/threads_{threads}", style.name);
            let mut t = START_S;
            group.bench_function(id("advance"), |b| {
                pool.install(|| {
                    b.iter(|| {
                        t += FRAME_S;
                        engine.advance(t)
                    })
                })
            });
            group.bench_function(id("map"), |b| {
                pool.install(|| {
                    b.iter(|| {
                        engine.invalidate_maps();
                        engine.build_map()
                    })
                })
            });
            group.bench_function(id("shade"), |b| pool.install(|| b.iter(|| engine.shade())));
            group.bench_function(id("raster"), |b| {
                pool.install(|| b.iter(|| engine.draw().width))
            });
            group.bench_function(id("frame"), |b| {
                pool.install(|| {
                    b.iter(|| {
                        t += FRAME_S;
                        engine.invalidate_maps();
                        engine.frame(t).width
                    })
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, stages);
criterion_main!(benches);
