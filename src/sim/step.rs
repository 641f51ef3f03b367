//! The simulator: fixed steps of every guide, parallel over guides, on a step clock.
//!
//! One step of `step_s` (default 1/480 s) builds the density grid of the positions and
//! velocities the step starts from (self-collision on: `density.rs`), in the head frame of
//! the step, then runs the step of every guide (`guide_step.rs`: root segment, forces, the
//! root-to-tip sweep of bending, follow-the-leader links and collisions, velocities, bending
//! damping, rest). [`Simulator::advance`] runs the steps up to the requested time: step n is at
//! `origin + n · step_s` (`state.rs`), so how the caller slices time does not change which
//! instants are simulated. A gap longer than `max_catch_up_s` (a hiccup, a seek) carries the
//! hair rigidly with the head over all but its last `max_catch_up_s`, so one slow frame cannot
//! make the next one slower.
//!
//! What remains step-dependent is the discretisation itself: measured on the dance
//! (`examples/sim_steps.rs`), the guide-tip error falls with an observed order of 0.4 to 0.7
//! at steps coarser than 1/480 s and 1 to 1.4 below; the default 1/480 s is 0.38 frames of
//! motion from converged on the smooth preset and 0.29 on the curly one (ACCURACY.md §4).
//!
//! Parallelism and determinism: guides are independent within a step (self-collision only goes
//! through the density grid, built on one thread before the guides and only read by them), so
//! guides are processed in parallel with rayon on disjoint chunks. The arithmetic on a guide
//! does not depend on the thread that runs it, and the only cross-guide reductions are a `max`
//! of f32 and integer counts, which are order-independent: positions are bit-identical for any
//! thread count.
//!
//! Allocation: none per step; the scratch for the corrections `d` and the density grid live in
//! the simulator (the grid's storage is reserved for the reachable cube at construction), and
//! the collider closure writes into a `Colliders` kept by the simulator (clearing and refilling
//! its sphere vector reuses its capacity).

use super::SimParams;
use super::collide::{Colliders, CollisionScene};
use super::density::DensityGrid;
use super::guide_step::{Consts, Guide, GuideStats, StepInputs, step_guide};
use super::shape::Shape;
pub use super::shape::hair_section_per_guide_m2;
use super::state::SimState;
use crate::hairstyle::{GuideSet, Hairstyle};
use glam::{Affine3A, Quat, Vec3, Vec3A};
use rayon::prelude::*;

/// What happened during one [`Simulator::advance`] call.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepStats {
    /// Fixed steps taken.
    pub steps: u32,
    /// Particle-steps that received self-collision repulsion (summed over steps).
    pub repelled_particles: u32,
    /// Steps whose self-collision was skipped because the hair spread over more than
    /// [`super::DENSITY_GRID_MAX_NODES`] grid nodes (0 in normal use).
    pub self_collision_skipped_steps: u32,
    /// Largest penetration of a free particle (index ≥ 2) into the true head ellipsoid or a
    /// sphere after any step, metres (conservative bound for the ellipsoid).
    pub max_penetration_m: f32,
    /// Guides reset to their rest shape because a value became non-finite (0 in normal use).
    pub reset_guides: u32,
    /// Guides held exactly still at the last step (`guide_step.rs`, stage 6).
    pub resting_guides: u32,
    /// Simulated time skipped by the catch-up cap, seconds (the hair was carried rigidly with
    /// the head over it).
    pub dropped_s: f64,
}

impl StepStats {
    /// The figures of this advance followed by `later`: counts and skipped time summed, the
    /// largest penetration, and the resting guides at the end.
    pub fn then(self, later: StepStats) -> StepStats {
        StepStats {
            steps: self.steps + later.steps,
            repelled_particles: self
                .repelled_particles
                .saturating_add(later.repelled_particles),
            self_collision_skipped_steps: self.self_collision_skipped_steps
                + later.self_collision_skipped_steps,
            max_penetration_m: self.max_penetration_m.max(later.max_penetration_m),
            reset_guides: self.reset_guides.saturating_add(later.reset_guides),
            resting_guides: if later.steps > 0 {
                later.resting_guides
            } else {
                self.resting_guides
            },
            dropped_s: self.dropped_s + later.dropped_s,
        }
    }
}

/// Advances guide strands in fixed steps (see the module doc).
pub struct Simulator {
    params: SimParams,
    consts: Consts,
    shape: Shape,
    /// Scratch: follow-the-leader correction `d` of each particle in the current step.
    correction: Vec<Vec3A>,
    /// Scratch written by the collider closure.
    colliders: Colliders,
    /// The colliders of the step before, to tell a still scene (`guide_step.rs`, stage 3d).
    prev_colliders: Colliders,
    /// Head semi-axes given to `new`, used when the closure leaves invalid ones.
    head_radii_m: Vec3,
    /// The self-collision density grid, rebuilt every step when self-collision is on.
    grid: DensityGrid,
    /// Whether the parameters and the hair cross-section give self-collision any strength.
    self_collision_possible: bool,
    /// Self-collision on (the default when possible) or off.
    self_collision: bool,
    /// Scratch: the rotation of each carrier in `colliders.carriers`, for the step.
    carrier_rot: Vec<Quat>,
}

impl Simulator {
    /// The simulator of a hairstyle's guides (its dynamics, head and hair cross-section).
    pub fn from_hairstyle(style: &Hairstyle, guides: &GuideSet) -> Simulator {
        Simulator::new(
            &style.dynamics,
            guides,
            Vec3::from(style.head.radii_m),
            hair_section_per_guide_m2(style, guides),
        )
    }

    /// Prepares the rest-shape data of `guides`. `params` should have passed
    /// [`SimParams::validate`]; out-of-range values are clamped into range here rather than
    /// producing a simulator that loops forever or returns NaN. `head_radii_m` initialises the
    /// head ellipsoid the collider closure sees (it may change it). `hair_section_m2` is the
    /// cross-section of real hair each guide stands for ([`hair_section_per_guide_m2`]), which
    /// self-collision turns into volume; 0 turns self-collision off.
    pub fn new(
        params: &SimParams,
        guides: &GuideSet,
        head_radii_m: Vec3,
        hair_section_m2: f32,
    ) -> Simulator {
        let params = params.sanitized();
        let section = if hair_section_m2.is_finite() && hair_section_m2 > 0.0 {
            hair_section_m2
        } else {
            0.0
        };
        let consts = Consts::new(&params);
        let shape = Shape::new(guides, section, consts.bend_damp);
        let reach_m = shape.reach_m();
        let cell_m = shape.density_cell_m(reach_m);
        let self_collision =
            section > 0.0 && (params.repulsion_m2_s2 > 0.0 || params.hair_friction_per_s > 0.0);
        Simulator {
            params,
            consts,
            correction: vec![Vec3A::ZERO; shape.rest.len()],
            shape,
            colliders: Colliders::head_only(Affine3A::IDENTITY, head_radii_m),
            prev_colliders: Colliders::head_only(Affine3A::IDENTITY, head_radii_m),
            head_radii_m,
            grid: DensityGrid::new(cell_m, if self_collision { reach_m } else { 0.0 }),
            self_collision_possible: self_collision,
            self_collision,
            carrier_rot: Vec::new(),
        }
    }

    /// Turns self-collision on or off (it is on after `new` when the parameters and the hair
    /// cross-section give it any strength; turning it on otherwise does nothing).
    pub fn set_self_collision(&mut self, on: bool) {
        self.self_collision = on && self.self_collision_possible;
    }

    /// Whether self-collision is on.
    pub fn self_collision(&self) -> bool {
        self.self_collision
    }

    /// Node spacing of the self-collision density grid, metres (the mean link length).
    pub fn density_cell_m(&self) -> f32 {
        self.grid.cell_m()
    }

    /// Nodes of the density grid of the last step (0 when self-collision is off).
    pub fn density_grid_nodes(&self) -> usize {
        if self.self_collision {
            self.grid.node_count()
        } else {
            0
        }
    }

    /// Changes the step to `step_s` (sanitised as in [`Simulator::new`]) and the per-step
    /// constants that follow from it (`bend.rs`, `guide_step.rs`). A state's step clock counts
    /// steps of the old step: restart it ([`SimState::restart_clock`]) before advancing it.
    pub fn set_step_s(&mut self, step_s: f32) {
        let mut params = self.params.clone();
        params.step_s = step_s;
        self.params = params.sanitized();
        self.consts = Consts::new(&self.params);
        self.shape.damping_weights =
            super::bend::damping_weights(self.consts.bend_damp, self.shape.points_per_guide);
    }

    /// The (sanitised) parameters in use.
    pub fn params(&self) -> &SimParams {
        &self.params
    }

    /// Particles the simulator expects in a [`SimState`].
    pub fn particle_count(&self) -> usize {
        self.shape.rest.len()
    }

    /// The colliders of the last step (as written by the closure).
    pub fn colliders(&self) -> &Colliders {
        &self.colliders
    }

    /// Advances `state` to the step instant nearest `t_end_s`, in fixed steps of
    /// `params.step_s`. Step n is at `origin + n · step_s` (see [`SimState`]), so the result
    /// does not depend on how the caller slices time; `state.time_s` ends within half a step
    /// of `t_end_s` (the remainder is carried to the next call). `colliders_at(t, &mut c)` is
    /// called once per step with the step's end time and must set the head transform and the
    /// spheres at `t` (the roots and root normals follow `c.head`). A gap larger than
    /// `params.max_catch_up_s` (a hiccup, a seek) is not simulated in full: the hair is carried
    /// rigidly with the head to `t_end_s − max_catch_up_s` and only the last
    /// `max_catch_up_s` is simulated, so one slow frame cannot make the next one slower.
    /// A state from a different guide set, an empty guide set, a non-finite `t_end_s` or one
    /// in the past does nothing.
    pub fn advance<C>(
        &mut self,
        state: &mut SimState,
        t_end_s: f64,
        mut colliders_at: C,
    ) -> StepStats
    where
        C: FnMut(f64, &mut Colliders),
    {
        let mut stats = StepStats::default();
        let n = self.particle_count();
        if n == 0
            || !t_end_s.is_finite()
            || state.positions.len() != n
            || state.velocities.len() != n
            || state.prev_positions.len() != n
            || state.anchor.len() != n
            || state.still_steps.len() != n / self.shape.points_per_guide.max(1)
        {
            return stats;
        }
        let dt = f64::from(self.consts.dt);
        let cap = f64::from(self.params.max_catch_up_s);
        if t_end_s - state.time_s > cap {
            let restart_s = t_end_s - cap;
            copy_colliders(&self.colliders, &mut self.prev_colliders);
            colliders_at(restart_s, &mut self.colliders);
            self.sanitize_colliders(state.head);
            carry_rigidly(
                state,
                &self.colliders,
                &self.prev_colliders.carriers,
                &self.shape.carrier,
            );
            stats.dropped_s = restart_s - state.time_s;
            state.origin_s = restart_s;
            state.steps = 0;
            state.time_s = restart_s;
        }
        // Steps to reach the instant nearest t_end_s (robust to the f32 rounding of step_s).
        let target_steps = ((t_end_s - state.origin_s) / dt).round();
        while (state.steps as f64) < target_steps {
            let t = state.origin_s + (state.steps + 1) as f64 * dt;
            copy_colliders(&self.colliders, &mut self.prev_colliders);
            colliders_at(t, &mut self.colliders);
            self.sanitize_colliders(state.head);
            let still_scene = state.steps > 0 && self.colliders == self.prev_colliders;
            let s = self.step(state, still_scene);
            stats.steps += 1;
            stats.repelled_particles = stats.repelled_particles.saturating_add(s.repelled);
            stats.self_collision_skipped_steps += s.grid_skipped;
            stats.max_penetration_m = stats.max_penetration_m.max(s.max_penetration_m);
            stats.reset_guides = stats.reset_guides.saturating_add(s.reset);
            stats.resting_guides = s.resting;
            state.steps += 1;
            state.time_s = t;
            state.head = self.colliders.head;
            state.last_step_s = self.consts.dt;
        }
        stats
    }

    /// Keeps the previous head transform if the closure produced a non-finite one (a
    /// non-finite carrier takes the head's), and the head semi-axes given to `new` if it
    /// produced invalid ones (if those are invalid too, the ellipsoid test simply finds
    /// nothing inside).
    fn sanitize_colliders(&mut self, previous_head: Affine3A) {
        if !self.colliders.head.is_finite() {
            self.colliders.head = previous_head;
        }
        let head = self.colliders.head;
        for c in &mut self.colliders.carriers {
            if !c.is_finite() {
                *c = head;
            }
        }
        let r = self.colliders.head_radii_m;
        if !(r.is_finite() && r.min_element() > 0.0) {
            self.colliders.head_radii_m = self.head_radii_m;
        }
    }

    /// One fixed step of every guide, in parallel; `still_scene` when no collider moved
    /// since the step before.
    fn step(&mut self, state: &mut SimState, still_scene: bool) -> GuideStats {
        let ppg = self.shape.points_per_guide;
        // The density grid of the positions and velocities the step starts from, in the head
        // frame of the step (the same transform for the splat and the queries).
        let grid_skipped = if self.self_collision {
            let ok = self.grid.build(
                self.colliders.head,
                &state.positions,
                &state.velocities,
                ppg,
                &self.shape.particle_volume_m3,
                self.consts.density_threshold,
            );
            u32::from(!ok)
        } else {
            0
        };
        let scene = CollisionScene::new(&self.colliders);
        let head = self.colliders.head;
        self.carrier_rot.clear();
        self.carrier_rot.extend(
            self.colliders
                .carriers
                .iter()
                .map(|c| Quat::from_mat3a(&c.matrix3).normalize()),
        );
        let inputs = StepInputs {
            shape: &self.shape,
            consts: &self.consts,
            head,
            head_rot: Quat::from_mat3a(&head.matrix3).normalize(),
            carriers: &self.colliders.carriers,
            carrier_rot: &self.carrier_rot,
            scene: &scene,
            still_scene,
            grid: (self.self_collision && self.grid.is_active()).then_some(&self.grid),
        };
        let stats = state
            .positions
            .par_chunks_mut(ppg)
            .zip(state.prev_positions.par_chunks_mut(ppg))
            .zip(state.velocities.par_chunks_mut(ppg))
            .zip(self.correction.par_chunks_mut(ppg))
            .zip(state.anchor.par_chunks_mut(ppg))
            .zip(state.still_steps.par_iter_mut())
            .enumerate()
            .with_min_len(8)
            .map(|(g, (((((pos, prev), vel), corr), anchor), still))| {
                let guide = Guide {
                    pos,
                    prev,
                    vel,
                    corr,
                    anchor,
                    still,
                };
                step_guide(g, guide, &inputs)
            })
            .reduce(GuideStats::default, GuideStats::merge);
        GuideStats {
            grid_skipped,
            ..stats
        }
    }
}

/// Copies `from` into `to`, reusing `to`'s allocations (a derived `clone_from` would not).
fn copy_colliders(from: &Colliders, to: &mut Colliders) {
    to.head = from.head;
    to.head_radii_m = from.head_radii_m;
    to.spheres.clone_from(&from.spheres);
    to.capsules.clone_from(&from.capsules);
    to.carriers.clone_from(&from.carriers);
}

/// Moves the whole state rigidly from its head pose to `new.head` (used when a time gap is
/// skipped): positions, previous positions and velocities. A guide carried by a bone
/// (`carrier_of`) moves with its carrier, from `old_carriers` (the carriers of the state's
/// time) to `new.carriers`; when the old ones are not known (a simulator that has not stepped
/// this state), with the head.
fn carry_rigidly(
    state: &mut SimState,
    new: &Colliders,
    old_carriers: &[Affine3A],
    carrier_of: &[u32],
) {
    let head_delta = new.head * state.head.inverse();
    let carried = old_carriers.len() == new.carriers.len() && !carrier_of.is_empty();
    let deltas: Vec<Affine3A> = if carried {
        new.carriers
            .iter()
            .zip(old_carriers)
            .map(|(n, o)| *n * o.inverse())
            .collect()
    } else {
        Vec::new()
    };
    let guides = state.still_steps.len();
    let ppg = state.positions.len() / guides.max(1);
    for g in 0..guides {
        let delta = carrier_of
            .get(g)
            .and_then(|&c| deltas.get(c as usize))
            .copied()
            .unwrap_or(head_delta);
        let span = g * ppg..(g + 1) * ppg;
        for p in state.positions[span.clone()]
            .iter_mut()
            .chain(state.prev_positions[span.clone()].iter_mut())
        {
            *p = delta.transform_point3(*p);
        }
        for v in &mut state.velocities[span] {
            *v = delta.transform_vector3(*v);
        }
    }
    state.anchor.copy_from_slice(&state.positions);
    state.still_steps.iter_mut().for_each(|s| *s = 0);
    state.head = new.head;
}
