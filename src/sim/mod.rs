//! Rigid-link guide simulation (Bertails, Ménier & Cani 2005 §4.1; Müller, Kim & Chentanez
//! 2012 for the follow-the-leader links).
//!
//! What: every guide strand is a chain of inextensible links whose root segment is carried by
//! the moving head; the rest of the chain feels gravity, air damping, bending stiffness toward
//! its rest shape, collisions with the head ellipsoid and body spheres, and repulsion out of
//! over-dense cells of the density map (self-collision, Bertails §4.1).
//!
//! How: [`Simulator::advance`] runs fixed steps of [`SimParams::step_s`] (default 1/240 s) up
//! to the requested time, whatever the output frame rate (a slow display never makes the
//! physics coarser, the TressFX failure mode where hair lags and clips when simulation is capped
//! at 60 Hz). Each step is position based: predict with forces, sweep root to tip placing each
//! particle at exactly one link length from its predecessor (follow the leader), resolve
//! collisions, then derive velocities with Müller's correction. See `step.rs` for the
//! equations, `bend.rs` for the bending constants and damping, `collide.rs` for collisions and
//! their order, `density.rs` for §4.1.
//!
//! Why: rigid links by construction (no iteration count to tune, lengths exact to rounding),
//! unconditionally stable position projections, and guides independent within a step, so they
//! run in parallel and give the same bits for any thread count.
//!
//! `SimParams` is read from hairstyle JSON (`"dynamics": {...}`); missing fields take defaults.
//! [`dance`] holds an analytic dance motion used by tests and benches.

mod bend;
mod budget;
pub mod capsule;
pub mod collide;
pub mod dance;
pub mod density;
pub mod state;
pub mod step;

pub use bend::BENDING_REFERENCE_STEP_S;
pub use capsule::CapsuleCollider;
pub use collide::{COLLISION_MARGIN_M, Colliders, SphereCollider};
pub use density::{DensityField, NoDensity};
pub use state::SimState;
pub use step::{Simulator, StepStats};

use serde::{Deserialize, Serialize};

/// Dynamics parameters of a hairstyle (`"dynamics"` in JSON). Units in the names.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SimParams {
    /// Fixed simulation step in seconds (default 1/240), independent of the output frame rate.
    pub step_s: f32,
    /// Gravity magnitude in m/s² along world −Y (default 9.81).
    pub gravity_m_s2: f32,
    /// Air damping rate in 1/s: velocity decays as exp(−rate·t) (default 1.5).
    pub damping_per_s: f32,
    /// Bending stiffness toward the rest shape, in [0, 1] (0 limp, 1 rigid; default 0.3): the
    /// fraction of a link's deviation from its rest bend removed per 1/240 s (`step.rs`).
    pub bending_stiffness: f32,
    /// Hair volume fraction above which a map cell repels hair (Bertails §4.1; default 0.25).
    pub density_threshold: f32,
    /// Repulsion strength in m/s² per unit of excess volume fraction (default 20).
    pub repulsion_m_s2: f32,
    /// Damping ratio ζ of the bending spring, >= 0 (default 1, critical): each link's angular
    /// velocity relative to its parent link is damped at the rate 2ζω, with ω = √k / step the
    /// bending spring's angular frequency (see `step.rs`). Without it the one-sided bending pull
    /// makes a chain of lightly damped oscillators that amplify motion toward the tip.
    pub bending_damping_ratio: f32,
    /// Follow-the-leader velocity correction factor (the s_damping of Müller, Kim & Chentanez
    /// 2012's dynamic FTL), in [0, 1] (0: plain FTL; 1: full reaction on the parent; default
    /// 0.5, see `step.rs` for the measured trade-off).
    pub ftl_correction: f32,
    /// Largest gap of simulated time one `advance` call catches up, seconds in (0, 10]
    /// (default 0.25): beyond it the hair is carried rigidly with the head.
    pub max_catch_up_s: f32,
}

impl Default for SimParams {
    fn default() -> Self {
        Self {
            step_s: 1.0 / 240.0,
            gravity_m_s2: 9.81,
            damping_per_s: 1.5,
            bending_stiffness: 0.3,
            density_threshold: 0.25,
            repulsion_m_s2: 20.0,
            bending_damping_ratio: 1.0,
            ftl_correction: 0.5,
            max_catch_up_s: 0.25,
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
            ("repulsion_m_s2", self.repulsion_m_s2),
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
            repulsion_m_s2: pick(self.repulsion_m_s2, d.repulsion_m_s2, 0.0, f32::MAX),
            bending_damping_ratio: pick(
                self.bending_damping_ratio,
                d.bending_damping_ratio,
                0.0,
                10.0,
            ),
            ftl_correction: pick(self.ftl_correction, d.ftl_correction, 0.0, 1.0),
            max_catch_up_s: pick(self.max_catch_up_s, d.max_catch_up_s, 1e-3, 10.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_fields_are_validated_and_default_when_absent() {
        assert!(SimParams::default().validate().is_ok());
        let p: SimParams = serde_json::from_str(r#"{ "damping_per_s": 2.0 }"#).expect("parses");
        assert_eq!(p.ftl_correction, SimParams::default().ftl_correction);
        assert_eq!(p.max_catch_up_s, 0.25);
        for (bad, field) in [
            (
                SimParams {
                    ftl_correction: 1.5,
                    ..SimParams::default()
                },
                "ftl_correction",
            ),
            (
                SimParams {
                    max_catch_up_s: 0.0,
                    ..SimParams::default()
                },
                "max_catch_up_s",
            ),
            (
                SimParams {
                    bending_damping_ratio: f32::NAN,
                    ..SimParams::default()
                },
                "bending_damping_ratio",
            ),
        ] {
            let err = bad.validate().expect_err("must be rejected");
            assert!(err.starts_with(field), "{err}");
            assert!(bad.sanitized().validate().is_ok());
        }
    }
}
