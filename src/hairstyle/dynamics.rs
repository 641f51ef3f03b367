//! The dynamics a hairstyle asks of the simulation (`"dynamics": {...}` in hairstyle JSON):
//! rates and frequencies per unit time, read and validated with the hairstyle, and taken by
//! `crate::sim` (which defines what each one does: `bend.rs`, `density.rs`, `step.rs`).

use serde::{Deserialize, Serialize};

/// Dynamics parameters of a hairstyle (`"dynamics"` in JSON). Units in the names.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SimParams {
    /// Fixed simulation step in seconds (default 1/480), independent of the output frame rate.
    /// Chosen from the speed-against-error table (`examples/sim_steps.rs`): the coarsest step
    /// whose guide-tip error over the dance is under half a frame of motion for both presets.
    pub step_s: f32,
    /// Gravity magnitude in m/s² along world −Y (default 9.81).
    pub gravity_m_s2: f32,
    /// Air damping rate in 1/s: velocity decays as exp(−rate·t) (default 1.5).
    pub damping_per_s: f32,
    /// Bending stiffness toward the rest shape, in [0, 1] (0 limp, 1 rigid; default 0.3). It
    /// sets the bending oscillator's angular frequency ω = −ln(1 − √s) / (1/240 s), whose
    /// critically damped pull removes the fraction s of a link's deviation from its rest bend
    /// over 1/240 s; the same ω is used at any step (`bend.rs`).
    pub bending_stiffness: f32,
    /// Hair volume fraction (of the simulator's density grid, smoothed over about one link
    /// length) above which hair repels hair (Bertails §4.1), >= 0 (default 0.04; `density.rs`).
    pub density_threshold: f32,
    /// Self-collision repulsion K in m²/s², >= 0 (0: off; default 60): hair accelerates down the
    /// gradient of the excess volume fraction, a = −K ∇(φ − threshold)₊ (`density.rs`).
    pub repulsion_m2_s2: f32,
    /// Hair-hair friction in 1/s, >= 0 (0: off; default 20): where the hair is at the
    /// threshold density or denser, a particle's velocity relative to the hair around it
    /// decays at this rate (less in sparser hair; `density.rs`).
    pub hair_friction_per_s: f32,
    /// Damping ratio ζ of the bending oscillator, in [0, 10] (default 1, critical): each link's
    /// angular velocity relative to its parent link is damped at the rate 2ζω (`bend.rs`).
    /// Without it the one-sided bending pull makes a chain of lightly damped oscillators that
    /// amplify motion toward the tip.
    pub bending_damping_ratio: f32,
    /// Follow-the-leader velocity correction factor (the s_damping of Müller, Kim & Chentanez
    /// 2012's dynamic FTL), in [0, 1] (0: plain FTL; 1: full reaction on the parent; default
    /// 0.5), defined per 1/240 s: a step of dt uses 1 − (1 − s)^(dt / (1/240 s)), because the
    /// correction acts as a per-step damping (see `step.rs` for the measurement).
    pub ftl_correction: f32,
    /// Largest gap of simulated time one `advance` call catches up, seconds in (0, 10]
    /// (default 0.25): beyond it the hair is carried rigidly with the head.
    pub max_catch_up_s: f32,
    /// Rest tolerance in metres, in [0, 1e-3] (default 2e-5; 0: off). A guide whose roots have
    /// not moved and whose particles have all stayed within this distance of where they were
    /// for `crate::sim::REST_WINDOW_S` is held exactly still until its roots move or a particle would
    /// leave that distance (`step.rs`): what is left then is f32 rounding, a flicker of a few
    /// µm that would change a few pixels of every frame.
    pub rest_tolerance_m: f32,
}

impl Default for SimParams {
    fn default() -> Self {
        Self {
            step_s: 1.0 / 480.0,
            gravity_m_s2: 9.81,
            damping_per_s: 1.5,
            bending_stiffness: 0.3,
            density_threshold: 0.04,
            repulsion_m2_s2: 60.0,
            hair_friction_per_s: 20.0,
            bending_damping_ratio: 1.0,
            ftl_correction: 0.5,
            max_catch_up_s: 0.25,
            rest_tolerance_m: 2.0e-5,
        }
    }
}

impl SimParams {
    /// Checks every field; the error names the field (relative to `dynamics.`) and the rule.
    pub fn validate(&self) -> Result<(), String> {
        if !(self.step_s.is_finite() && self.step_s > 1e-5 && self.step_s <= 0.05) {
            return Err(format!(
                "step_s must be in (1e-5, 0.05] seconds (got {})",
                self.step_s
            ));
        }
        for (name, v) in [
            ("gravity_m_s2", self.gravity_m_s2),
            ("damping_per_s", self.damping_per_s),
            ("density_threshold", self.density_threshold),
            ("repulsion_m2_s2", self.repulsion_m2_s2),
            ("hair_friction_per_s", self.hair_friction_per_s),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(format!("{name} must be finite and >= 0 (got {v})"));
            }
        }
        if !(self.bending_stiffness.is_finite() && (0.0..=1.0).contains(&self.bending_stiffness)) {
            return Err(format!(
                "bending_stiffness must be in [0, 1] (got {})",
                self.bending_stiffness
            ));
        }
        if !(self.bending_damping_ratio.is_finite()
            && (0.0..=10.0).contains(&self.bending_damping_ratio))
        {
            return Err(format!(
                "bending_damping_ratio must be in [0, 10] (got {})",
                self.bending_damping_ratio
            ));
        }
        if !(self.ftl_correction.is_finite() && (0.0..=1.0).contains(&self.ftl_correction)) {
            return Err(format!(
                "ftl_correction must be in [0, 1] (got {})",
                self.ftl_correction
            ));
        }
        if !(self.max_catch_up_s.is_finite()
            && self.max_catch_up_s > 0.0
            && self.max_catch_up_s <= 10.0)
        {
            return Err(format!(
                "max_catch_up_s must be in (0, 10] seconds (got {})",
                self.max_catch_up_s
            ));
        }
        if !(self.rest_tolerance_m.is_finite() && (0.0..=1e-3).contains(&self.rest_tolerance_m)) {
            return Err(format!(
                "rest_tolerance_m must be in [0, 1e-3] metres (got {})",
                self.rest_tolerance_m
            ));
        }
        Ok(())
    }

    /// A copy with every field forced into its valid range (non-finite values take the
    /// default), for constructors that must not fail.
    pub fn sanitized(&self) -> SimParams {
        let d = SimParams::default();
        let pick = |v: f32, def: f32, lo: f32, hi: f32| {
            if v.is_finite() { v.clamp(lo, hi) } else { def }
        };
        SimParams {
            step_s: pick(self.step_s, d.step_s, 1e-5, 0.05),
            gravity_m_s2: pick(self.gravity_m_s2, d.gravity_m_s2, 0.0, f32::MAX),
            damping_per_s: pick(self.damping_per_s, d.damping_per_s, 0.0, f32::MAX),
            bending_stiffness: pick(self.bending_stiffness, d.bending_stiffness, 0.0, 1.0),
            density_threshold: pick(self.density_threshold, d.density_threshold, 0.0, f32::MAX),
            repulsion_m2_s2: pick(self.repulsion_m2_s2, d.repulsion_m2_s2, 0.0, f32::MAX),
            hair_friction_per_s: pick(
                self.hair_friction_per_s,
                d.hair_friction_per_s,
                0.0,
                f32::MAX,
            ),
            bending_damping_ratio: pick(
                self.bending_damping_ratio,
                d.bending_damping_ratio,
                0.0,
                10.0,
            ),
            ftl_correction: pick(self.ftl_correction, d.ftl_correction, 0.0, 1.0),
            max_catch_up_s: pick(self.max_catch_up_s, d.max_catch_up_s, 1e-3, 10.0),
            rest_tolerance_m: pick(self.rest_tolerance_m, d.rest_tolerance_m, 0.0, 1e-3),
        }
    }
}

#[cfg(test)]
mod tests;
