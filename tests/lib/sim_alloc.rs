//! The simulator allocates nothing per step once constructed (issue #4 design rule): the
//! binary's counting allocator (`alloc.rs`) watches `advance` after a warm-up call. It counts
//! only on the threads of this test's own pool, so the tests running beside it do not count.

use crate::alloc::{ALLOCATIONS, ARMED, watch_this_thread};
use glam::Vec3;
use std::sync::atomic::Ordering;
use wisp::hairstyle::{Hairstyle, generate};
use wisp::sim::dance::AnalyticDance;
use wisp::sim::{Colliders, SimState, Simulator};

#[test]
fn advance_does_not_allocate_after_warm_up() {
    let style = Hairstyle::default_smooth();
    let (guides, _) = generate(&style);
    let dance = AnalyticDance::new(Vec3::from(style.head.radii_m));
    let motion = |t: f64, c: &mut Colliders| dance.colliders_at(t, c);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .start_handler(|_| watch_this_thread())
        .build()
        .expect("thread pool");
    // Self-collision on, as the presets ship: its density grid must not allocate either.
    let mut sim = Simulator::from_hairstyle(&style, &guides);
    assert!(sim.self_collision());
    let mut state = SimState::at_rest(&guides, &dance.colliders(0.0), 0.0);
    pool.install(|| {
        // Warm-up: the collider scratch grows its sphere vector once, rayon starts its workers.
        sim.advance(&mut state, 0.1, motion);
        ARMED.store(true, Ordering::SeqCst);
        let mut steps = 0;
        for f in 4..=30 {
            steps += sim.advance(&mut state, f64::from(f) / 30.0, motion).steps;
        }
        ARMED.store(false, Ordering::SeqCst);
        assert!(steps > 200);
    });
    let n = ALLOCATIONS.load(Ordering::SeqCst);
    assert_eq!(n, 0, "{n} allocations during 0.9 s of simulation");
}
