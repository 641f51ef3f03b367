//! The window's motion clock: how far the motion moves from one frame to the next.
//!
//! Moving it by the wall time each frame took keeps real time but lets one slow frame (a
//! rebuild, the system) hand the next frame a burst of simulation steps, which makes that frame
//! slow too. Instead each frame moves the motion by the same whole number of simulation steps,
//! the steps in the frame interval the window sustains: a mean of the recent frames' wall
//! intervals, which a single slow frame barely moves. The window keeps real time on average,
//! each frame does the same simulation work, and a window slower than
//! [`MAX_FRAME_INTERVAL_S`] plays the motion slower instead of jumping.

/// Weight of the newest frame's interval in the running mean.
const NEWEST_WEIGHT: f64 = 0.05;

/// Longest frame interval the clock follows, seconds: a slower window plays slow motion.
pub(super) const MAX_FRAME_INTERVAL_S: f64 = 0.1;

/// The running mean of the frame interval and the step the motion moves in.
#[derive(Clone, Debug)]
pub(super) struct MotionClock {
    /// Mean wall seconds between frames.
    interval_s: f64,
    /// The window's shortest interval between frames (it waits out the rest).
    shortest_s: f64,
    /// Seconds of one simulation step.
    step_s: f64,
}

impl MotionClock {
    /// A clock for a window that shows a frame every `shortest_s` at most often, expecting
    /// that rate, and moves in steps of `step_s` (each taken as positive and finite, else a
    /// 60th and a 480th of a second).
    pub fn new(shortest_s: f64, step_s: f64) -> Self {
        let positive = |x: f64, or: f64| if x.is_finite() && x > 0.0 { x } else { or };
        let shortest_s = positive(shortest_s, 1.0 / 60.0).min(MAX_FRAME_INTERVAL_S);
        Self {
            interval_s: shortest_s,
            shortest_s,
            step_s: positive(step_s, 1.0 / 480.0),
        }
    }

    /// Records a frame that took `wall_s` (clamped to the window's shortest interval and
    /// [`MAX_FRAME_INTERVAL_S`]) and returns how far the motion moves for the next frame:
    /// a whole number of steps, at least one.
    pub fn tick(&mut self, wall_s: f64) -> f64 {
        let wall_s = if wall_s.is_finite() { wall_s } else { 0.0 };
        let measured = wall_s.clamp(self.shortest_s, MAX_FRAME_INTERVAL_S);
        self.interval_s += NEWEST_WEIGHT * (measured - self.interval_s);
        self.steps_per_frame() as f64 * self.step_s
    }

    /// Simulation steps each frame moves the motion by.
    pub fn steps_per_frame(&self) -> u32 {
        (self.interval_s / self.step_s).round().max(1.0) as u32
    }
}

#[cfg(test)]
mod tests;
