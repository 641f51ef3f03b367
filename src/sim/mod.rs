//! Rigid-link guide simulation (Bertails, Ménier & Cani 2005 §4.1; Müller, Kim & Chentanez
//! 2012 for the follow-the-leader links).
//!
//! What: every guide strand is a chain of inextensible links whose root segment is carried by
//! the moving head; the rest of the chain feels gravity, air damping, bending stiffness toward
//! its rest shape, collisions with the head ellipsoid and body spheres, and self-collision:
//! repulsion down the gradient of the hair's excess density and hair-hair friction, from a
//! density grid the simulator builds from the guides at every step (Bertails §4.1).
//!
//! How: [`Simulator::advance`] runs fixed steps of [`SimParams::step_s`] (default 1/480 s) up
//! to the requested time, whatever the output frame rate (a slow display never makes the
//! physics coarser, the TressFX failure mode where hair lags and clips when simulation is capped
//! at 60 Hz). Each step is position based: predict with forces, sweep root to tip placing each
//! particle at exactly one link length from its predecessor (follow the leader), resolve
//! collisions, then derive velocities with Müller's correction. See `step.rs` for the step
//! loop, `guide_step.rs` for one guide's stages and their equations, `shape.rs` for the rest
//! shape and the hair each particle stands for, `bend.rs` for the bending constants and
//! damping, `collide.rs` for collisions and their order, `density.rs` for self-collision
//! (§4.1), `settle.rs` for settling in coarse steps before the first frame.
//!
//! Every parameter is a rate or a frequency per unit time, converted to per-step factors with
//! exact solutions over the step (`bend.rs`, `density.rs`), so the model is the same at any
//! step and a smaller step only reduces the discretisation error (ACCURACY.md §4, measured
//! with `examples/sim_steps.rs`).
//!
//! Why: rigid links by construction (no iteration count to tune, lengths exact to rounding),
//! unconditionally stable position projections, and guides independent within a step, so they
//! run in parallel and give the same bits for any thread count.
//!
//! [`SimParams`] is read from hairstyle JSON (`"dynamics": {...}`, defined with the
//! hairstyle, which this stage reads); missing fields take defaults.
//! [`dance`] holds an analytic dance motion used by tests and benches.

mod bend;
mod budget;
pub mod capsule;
pub mod collide;
pub mod dance;
pub mod density;
mod guide_step;
pub mod settle;
mod shape;
pub mod state;
pub mod step;

pub use bend::bending_frequency_rad_s;
pub use capsule::CapsuleCollider;
pub use collide::{COLLISION_MARGIN_M, Colliders, SphereCollider};
pub use density::MAX_NODES as DENSITY_GRID_MAX_NODES;
pub use settle::{CoarseSettle, SETTLE_TAIL_S};
pub use state::SimState;
pub use step::{Simulator, StepStats};

pub use crate::hairstyle::dynamics::SimParams;

/// The step at which the per-step parameters `bending_stiffness` and `ftl_correction` are
/// defined, seconds (1/240 s, the step they were tuned at). Other steps convert them to the
/// same behaviour per unit time (`bend.rs`, `guide_step.rs`).
pub const REFERENCE_STEP_S: f32 = 1.0 / 240.0;

/// How long a guide must stay within `rest_tolerance_m` before it is held still, seconds.
pub const REST_WINDOW_S: f64 = 0.5;
