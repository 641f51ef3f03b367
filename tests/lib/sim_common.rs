//! Helpers shared by the `sim_*` integration tests: building a simulator from a preset and
//! measuring link lengths and penetration independently of the simulator's own statistics.
//! Every run takes its motion as a collider closure, so the analytic dance can be swapped for a
//! loaded glTF clip without touching the tests' assertions.

use wisp::hairstyle::{GuideSet, Hairstyle, generate};
use wisp::sim::{Colliders, SimState, Simulator};

/// A preset's guides, a simulator for them (self-collision on, as in the presets), and a state
/// at rest at t = 0 under `colliders0`.
pub fn setup(style: &Hairstyle, colliders0: &Colliders) -> (GuideSet, Simulator, SimState) {
    let (guides, _) = generate(style);
    let sim = Simulator::from_hairstyle(style, &guides);
    let state = SimState::at_rest(&guides, colliders0, 0.0);
    (guides, sim, state)
}

/// Largest relative link-length error |len/L − 1| over all links.
pub fn max_length_error(state: &SimState, guides: &GuideSet) -> f32 {
    let ppg = guides.points_per_guide;
    let mut worst = 0.0f32;
    for (g, l) in guides.link_length_m.iter().enumerate() {
        let pts = &state.positions[g * ppg..(g + 1) * ppg];
        for w in pts.windows(2) {
            worst = worst.max(((w[1] - w[0]).length() / l - 1.0).abs());
        }
    }
    worst
}

/// Largest penetration (metres, conservative for the ellipsoid) of a free particle (index ≥ 2
/// in its guide; 0 and 1 are the kinematic root segment) into the colliders.
pub fn max_penetration_m(state: &SimState, ppg: usize, colliders: &Colliders) -> f32 {
    state
        .positions
        .iter()
        .enumerate()
        .filter(|(k, _)| k % ppg >= 2)
        .map(|(_, p)| colliders.penetration_m(*p))
        .fold(0.0, f32::max)
}

/// True when every position is finite.
pub fn all_finite(state: &SimState) -> bool {
    state.positions.iter().all(|p| p.is_finite())
}
