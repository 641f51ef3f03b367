//! What a [`Simulator`] and its [`SimState`](super::SimState) hold, for the run's memory budget
//! (`crate::budget`), computed before they exist: the sum of their per-particle and per-guide
//! arrays. Keep it in step with `state.rs`, `shape.rs` and `step.rs` when they gain
//! per-particle arrays; `tests/lib/hostile_budget.rs` measures a real engine against the whole
//! budget.

use super::Simulator;
use glam::{Vec3, Vec3A};

impl Simulator {
    /// Bytes held by a simulator and its state for `guides` guides of `points_per_guide`
    /// particles each:
    /// - [`SimState`](super::SimState): `positions`, `velocities`, `prev_positions` (one `Vec3` per particle);
    /// - [`Simulator`]: `rest`, `rest_dir`, `correction` (one `Vec3A` per particle) and one
    ///   `f32` link length per guide.
    pub fn estimated_bytes(guides: u64, points_per_guide: u64) -> u64 {
        let particles = guides.saturating_mul(points_per_guide);
        let per_particle = 3 * size_of::<Vec3>() as u64 + 3 * size_of::<Vec3A>() as u64;
        particles
            .saturating_mul(per_particle)
            .saturating_add(guides.saturating_mul(size_of::<f32>() as u64))
    }
}
