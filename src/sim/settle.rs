//! Settling in coarse steps: the hair's fall onto the head before the first frame, taken in
//! steps longer than the simulation's, then its last [`SETTLE_TAIL_S`] in the simulation's own
//! step.
//!
//! Why: the settle (2 s with the head held at the first pose) is most of a groom's set-up: 960
//! steps of 1/480 s, 4 s on 2 cores for the 1,200 guides of a 10,000-strand groom. What it
//! is for is the resting state it ends in, not the path there. Every parameter is a rate per
//! unit time, so a coarse step falls the same way and ends near the same rest; the rest of the
//! coarse step differs from the fine one's by the discretisation (the follow-the-leader
//! correction leaves a step-dependent velocity in hanging hair, `guide_step.rs`), which the
//! fine tail removes before the first frame.
//!
//! Measured (BENCHMARKS.md, "Groom set-up"): a synthetic 10,000-strand groom on the dance's
//! first pose, 1/60 s steps then 0.25 s of 1/480 s, ends 0.07 mm (mean over guide particles)
//! from the 1/480 s settle, which itself is 0.9 mm from a 1/960 s settle; a few guides that
//! fall onto the shoulder can come to rest on its other side under any change of step (up to
//! 0.15 m, as between 1/480 s and 1/240 s).
//!
//! The coarse step is shortened so that a whole number of steps ends exactly at the tail, so
//! the fine steps after it fall on the instants the simulation would have taken anyway.

use super::Colliders;
use super::state::SimState;
use super::step::{Simulator, StepStats};

/// The end of the settle taken in the simulation's own step, seconds.
pub const SETTLE_TAIL_S: f64 = 0.25;

/// A settle in coarse steps under way: when the coarse steps end and the step to go back to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoarseSettle {
    /// When the coarse steps end, seconds (the tail before the settle's end).
    switch_s: f64,
    /// The simulation's own step, seconds.
    fine_step_s: f32,
}

impl CoarseSettle {
    /// Sets `sim` to coarse steps of at most `coarse_step_s` for the settle from `state`'s time
    /// to `end_s` (the first frame), but its last `tail_s` (the engine's: [`SETTLE_TAIL_S`]).
    /// `None` (and `sim` unchanged) when the coarse step is not longer than the simulator's or
    /// the settle is no longer than the tail.
    pub fn start(
        sim: &mut Simulator,
        state: &SimState,
        end_s: f64,
        coarse_step_s: f32,
        tail_s: f64,
    ) -> Option<CoarseSettle> {
        let fine_step_s = sim.params().step_s;
        let switch_s = end_s - tail_s;
        let span_s = switch_s - state.time_s;
        if !(coarse_step_s > fine_step_s && span_s > 0.0 && span_s.is_finite()) {
            return None;
        }
        let steps = (span_s / f64::from(coarse_step_s)).ceil().max(1.0);
        sim.set_step_s((span_s / steps) as f32);
        Some(CoarseSettle {
            switch_s,
            fine_step_s,
        })
    }

    /// Advances `state` toward `t_end_s` in coarse steps, up to the switch; on reaching it,
    /// puts `sim` back to its own step with the state's clock restarted there, and returns
    /// true (the settle is done with: advance on with `sim` alone).
    pub fn advance<C>(
        &self,
        sim: &mut Simulator,
        state: &mut SimState,
        t_end_s: f64,
        colliders_at: C,
    ) -> (StepStats, bool)
    where
        C: FnMut(f64, &mut Colliders),
    {
        let stats = sim.advance(state, t_end_s.min(self.switch_s), colliders_at);
        let done = t_end_s >= self.switch_s;
        if done {
            let coarse_step_s = sim.params().step_s;
            sim.set_step_s(self.fine_step_s);
            let ratio = f64::from(sim.params().step_s) / f64::from(coarse_step_s);
            state.restart_clock(self.switch_s, ratio);
        }
        (stats, done)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hairstyle::{Hairstyle, generate};
    use glam::{Affine3A, Vec3};

    /// A 2 s settle in steps of at most 1/60 s then 0.25 s of 1/480 s: 105 coarse steps
    /// ((2 − 0.25) · 60) and 120 fine ones (0.25 · 480), ending at 0 with the
    /// simulator back at its own step, and the same bits whatever the slices of time asked.
    #[test]
    fn a_coarse_settle_ends_on_the_fine_step_at_the_first_frame() {
        let style = Hairstyle::default_smooth();
        let (guides, _) = generate(&style);
        let fine = 1.0 / 480.0;
        let mut stepped = style.clone();
        stepped.dynamics.step_s = fine;
        let head = Colliders::head_only(Affine3A::IDENTITY, Vec3::from(style.head.radii_m));
        let run = |slice_s: f64| {
            let mut sim = Simulator::from_hairstyle(&stepped, &guides);
            let mut state = SimState::at_rest(&guides, &head, -2.0);
            let settle = CoarseSettle::start(&mut sim, &state, 0.0, 1.0 / 60.0, SETTLE_TAIL_S)
                .expect("a coarse step longer than 1/480 s");
            let (mut t, mut steps, mut settling) = (-2.0f64, 0, true);
            while t < 0.0 {
                t = (t + slice_s).min(0.0);
                let stats = if settling {
                    let (stats, done) =
                        settle.advance(&mut sim, &mut state, t, |_, c| *c = head.clone());
                    settling = !done;
                    stats
                } else {
                    sim.advance(&mut state, t, |_, c| *c = head.clone())
                };
                steps += stats.steps;
            }
            assert_eq!(sim.params().step_s, fine);
            // The step clock's own rounding: 120 steps of 1/480 s rounded to f32.
            assert!(state.time_s.abs() < 1e-6, "ends at {}", state.time_s);
            (steps, state.positions)
        };
        let (steps, positions) = run(0.2);
        assert_eq!(steps, 105 + 120);
        let (steps_b, positions_b) = run(0.05);
        assert_eq!(steps_b, steps);
        assert!(positions == positions_b, "slicing changed the settled bits");
    }

    /// No coarse settle when the coarse step is not longer than the simulator's, or the
    /// settle no longer than the tail.
    #[test]
    fn no_coarse_settle_without_a_longer_step_or_time_before_the_tail() {
        let style = Hairstyle::default_smooth();
        let (guides, _) = generate(&style);
        let mut sim = Simulator::from_hairstyle(&style, &guides);
        let head = Colliders::head_only(Affine3A::IDENTITY, Vec3::from(style.head.radii_m));
        let early = SimState::at_rest(&guides, &head, -2.0);
        let late = SimState::at_rest(&guides, &head, -0.2);
        let own = sim.params().step_s;
        assert!(CoarseSettle::start(&mut sim, &early, 0.0, own, SETTLE_TAIL_S).is_none());
        assert!(CoarseSettle::start(&mut sim, &late, 0.0, 1.0 / 60.0, SETTLE_TAIL_S).is_none());
        assert_eq!(sim.params().step_s, own);
    }
}
