//! One output frame (1/30 s, i.e. 1/30 s ÷ `dynamics.step_s` fixed steps) of the guide
//! simulation under the analytic dance, for the smooth and curly presets, with self-collision
//! on (as the presets ship) and off, in rayon pools of 1 and 2 threads.
//!
//! The state is warmed up for 1 s of dance first so that the measured frames see hair in
//! motion and in contact, not the rest pose. Each iteration advances the same state by one
//! more frame (time keeps increasing, so the dance keeps moving). The difference between the
//! `on` and `off` ids is the cost of self-collision (density grid splat + per-particle
//! queries). Run: `cargo bench --bench sim` (or `-- --quick`).

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::Vec3;
use std::hint::black_box;
use wisp::hairstyle::{Hairstyle, generate};
use wisp::sim::dance::AnalyticDance;
use wisp::sim::{Colliders, SimState, Simulator};

const FRAME_S: f64 = 1.0 / 30.0;

fn frame(c: &mut Criterion) {
    let mut group = c.benchmark_group("sim_frame");
    for style in [Hairstyle::default_smooth(), Hairstyle::default_curly()] {
        let (guides, _) = generate(&style);
        let dance = AnalyticDance::new(Vec3::from(style.head.radii_m));
        let motion = |t: f64, c: &mut Colliders| dance.colliders_at(t, c);
        for self_collision in [true, false] {
            for threads in [1usize, 2] {
                let Ok(pool) = rayon::ThreadPoolBuilder::new().num_threads(threads).build() else {
                    eprintln!("cannot build a pool of {threads} threads; skipped");
                    continue;
                };
                let mut sim = Simulator::from_hairstyle(&style, &guides);
                sim.set_self_collision(self_collision);
                let mut state = SimState::at_rest(&guides, &dance.colliders(0.0), 0.0);
                let mut t = 0.0;
                pool.install(|| {
                    while t < 1.0 {
                        t += FRAME_S;
                        sim.advance(&mut state, t, motion);
                    }
                });
                let sc = if self_collision { "on" } else { "off" };
                let id = BenchmarkId::new(format!("{}-sc-{sc}", style.name), format!("{threads}t"));
                group.bench_function(id, |b| {
                    pool.install(|| {
                        b.iter(|| {
                            t += FRAME_S;
                            black_box(sim.advance(&mut state, t, motion))
                        })
                    })
                });
            }
        }
    }
    group.finish();
}

criterion_group!(benches, frame);
criterion_main!(benches);
