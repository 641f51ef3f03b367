//! One output frame (1/30 s = 8 fixed steps of 1/240 s) of the guide simulation under the
//! analytic dance, for the smooth and curly presets, in rayon pools of 1 and 2 threads.
//!
//! The state is warmed up for 1 s of dance first so that the measured frames see hair in
//! motion and in contact, not the rest pose. Each iteration advances the same state by one
//! more frame (time keeps increasing, so the dance keeps moving); ns per particle-step =
//! frame time / (8 · particles). Run: `cargo bench --bench sim` (or `-- --quick`).

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::Vec3;
use std::hint::black_box;
use wisp::hairstyle::{Hairstyle, generate};
use wisp::sim::dance::AnalyticDance;
use wisp::sim::{Colliders, NoDensity, SimState, Simulator};

const FRAME_S: f64 = 1.0 / 30.0;

fn frame(c: &mut Criterion) {
    let mut group = c.benchmark_group("sim_frame");
    for style in [Hairstyle::default_smooth(), Hairstyle::default_curly()] {
        let (guides, _) = generate(&style);
        let dance = AnalyticDance::new(Vec3::from(style.head.radii_m));
        let motion = |t: f64, c: &mut Colliders| dance.colliders_at(t, c);
        for threads in [1usize, 2] {
            let Ok(pool) = rayon::ThreadPoolBuilder::new().num_threads(threads).build() else {
                eprintln!("cannot build a pool of {threads} threads; skipped");
                continue;
            };
            let mut sim = Simulator::new(&style.dynamics, &guides, Vec3::from(style.head.radii_m));
            let mut state = SimState::at_rest(&guides, &dance.colliders(0.0), 0.0);
            let mut t = 0.0;
            pool.install(|| {
                while t < 1.0 {
                    t += FRAME_S;
                    sim.advance(&mut state, t, motion, &NoDensity);
                }
            });
            let id = BenchmarkId::new(style.name.clone(), format!("{threads}t"));
            group.bench_function(id, |b| {
                pool.install(|| {
                    b.iter(|| {
                        t += FRAME_S;
                        black_box(sim.advance(&mut state, t, motion, &NoDensity))
                    })
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, frame);
criterion_main!(benches);
