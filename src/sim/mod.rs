//! Rigid-link guide simulation (Bertails 2005 §4.1). CONTRACT placeholder: the simulation work
//! (issue #4) fills this module; `SimParams` is read from hairstyle JSON (`"dynamics": {...}`).

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
    /// Bending stiffness toward the rest shape, in [0, 1] (0 limp, 1 rigid; default 0.3).
    pub bending_stiffness: f32,
    /// Hair volume fraction above which a map cell repels hair (Bertails §4.1; default 0.25).
    pub density_threshold: f32,
    /// Repulsion strength in m/s² per unit of excess volume fraction (default 20).
    pub repulsion_m_s2: f32,
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
        Ok(())
    }
}
