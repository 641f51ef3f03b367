//! The rigid-link integrator: fixed steps, follow-the-leader links, bending toward the rest
//! shape, collisions, self-collision, parallel over guides.
//!
//! One step of `step_s` (default 1/480 s), for all guides (stage 0) and then for each guide,
//! particles `0..n` root to tip:
//!
//! 0. **Density grid** (self-collision on): every particle's hair volume and velocity at the
//!    start of the step are splatted into the simulator's density grid (`density.rs`).
//! 1. **Kinematic root segment.** Particles 0 and 1 are the rest positions carried by the head
//!    transform: the root sits on the scalp and the first link keeps its rest direction relative
//!    to the head, which leaves the scalp near the scalp normal (the rest generator starts every
//!    guide along the normal). A follicle does not pivot, so a rigid first link is the physical
//!    reading, and it removes the need for a stiff (and step-limiting) root constraint.
//! 2. **Forces, symplectic Euler.** For free particles (i ≥ 2): hair-hair friction
//!    `v ← v̄ + (v − v̄) e^{−c dt}` toward the local mean velocity v̄, then
//!    `v ← v · exp(−damping_per_s · dt) + dt · (g + a_rep)`, `p* = x + dt · v`, with
//!    `g = (0, −gravity_m_s2, 0)` and `a_rep = −K ∇ẽ(x)` the Bertails §4.1 repulsion
//!    (`density.rs`), all read at `x` from the grid of this step. The decay factors are exact
//!    solutions of `dv/dt = −c v` over the step, so they do not depend on `dt`.
//! 3. **Root-to-tip sweep** (Gauss–Seidel, each particle sees its predecessor's final position):
//!    - a) *Bending.* `Q` is a rotation carrying rest directions (head frame) to the current
//!      frame of the previous link, parallel-transported down the strand: `Q₁ = R_head`, and
//!      after link i is placed with direction `dᵢ`, `Qᵢ = arc(Qᵢ₋₁ rᵢ → dᵢ) · Qᵢ₋₁` (the
//!      minimal rotation). The target of link i is `tᵢ = Qᵢ₋₁ rᵢ`: the rest bend between
//!      links i−1 and i, including its plane, so waves and curls keep their shape and their
//!      orientation about the strand. The particle is pulled toward it,
//!      `p* ← p* + k (pᵢ₋₁ + L tᵢ − p*)`, with `k` from `bend.rs`: the pull of a bending
//!      oscillator of fixed frequency ω advanced exactly over `dt`, so the same at any step
//!      (0: limp, 1: rigid rest shape).
//!    - b) *Follow the leader* (Müller, Kim & Chentanez 2012, "Fast Simulation of Inextensible
//!      Hair and Fur", dynamic FTL; the paper is not in `shared/papers`, so no equation
//!      numbers are cited): `pᵢ = pᵢ₋₁ + L · (p* − pᵢ₋₁)/|p* − pᵢ₋₁|`, so every link has
//!      length L exactly (to rounding), with no iteration. The correction `dᵢ = pᵢ − p*` is
//!      kept for step 4. A degenerate direction falls back to `tᵢ`.
//!    - c) *Collisions* (`collide.rs`): out of the head ellipsoid and the spheres, keeping the
//!      particle on the sphere of radius L around `pᵢ₋₁`; the length projection is always last.
//! 4. **Velocities** (DFTL velocity update): `vᵢ = (pᵢ − xᵢ)/dt − s · dᵢ₊₁/dt` with
//!    `s = ftl_correction` (default 0.5; `d` past the tip is 0). Plain FTL moves a particle
//!    without moving its predecessor, as if each particle were infinitely heavier than the
//!    next; adding back the child's correction approximates the reaction on the parent. Measured
//!    here: with `s = 0` a limp guide set (`bending_stiffness` 0) never settles under a still
//!    head (kinetic energy still 1e4 m²/s² after 10 s), with `s` = 0.5 or 0.9 it settles within
//!    8 s; on the stiff presets `s` changes dance kinetic energy by about 1%. But `s > 0` keeps
//!    a velocity `−s·dᵢ₊₁/dt` in every hanging particle at rest (undone each step by the
//!    projection), whose rounding noise raised the rest kinetic-energy floor from 3e-7 (s = 0)
//!    to 4e-6 (0.5) and 3e-4 m²/s² (0.9) and made settled particles wander 0.3 mm (0.9). 0.5 is
//!    the compromise. `s` is defined per 1/240 s: a step of `dt` uses
//!    `1 − (1 − s)^(dt / (1/240 s))`, because the correction acts as a damping per step:
//!    measured, s = 0.5 against s = 0 moved the dance's guide tips by 0.94 mm RMS at 1/240 s
//!    but 4.3 mm at 1/1920 s; with the scaling, 1.35 / 0.94 / 0.82 / 0.64 mm at 1/60, 1/240,
//!    1/960 and 1/1920 s.
//! 5. **Bending damping.** Each link's angular velocity relative to its parent link decays at
//!    the damping rate of the same exactly advanced oscillator as `k` (ratio
//!    `ζ = bending_damping_ratio`, default 1), solved exactly over the step for the whole chain
//!    (`bend::damp_bending`, also for why it is needed and what the first, root-to-tip version
//!    cost). Rigid swinging of the whole strand (equal angular velocities) is untouched, so air
//!    damping alone still sets how long hair swings.
//! 6. **Rest.** A guide whose root segment has not moved (bit for bit) and whose particles
//!    have all stayed within `rest_tolerance_m` (default 20 µm) of where they were for
//!    [`super::REST_WINDOW_S`] (0.5 s) is held exactly there: its computed positions are
//!    replaced by those. It wakes the step its roots move or a computed particle leaves the
//!    tolerance. Why: settled hair is an equilibrium of the dynamics only up to f32 rounding,
//!    which leaves a flicker of a few ulps per step (measured over 10 s, 1.6 m from the origin
//!    where the ulp is 1.2e-7 m: up to 7 µm for the presets and 15 µm for twice their density,
//!    at 1/480 s); a flicker that small still changes a few pixels of every 800×800 frame
//!    (measured: 6 to 20 pixels by 1 to 3 levels), because some pixel always sits on a
//!    rounding boundary. Cost: motion slower than 20 µm / 0.5 s = 40 µm/s (a pixel at 800×800
//!    in 20 s) does not move resting hair, and a response to a disturbance smaller than the
//!    tolerance may stop part-way. The hair's own settling does not rely on it: the tests check
//!    the dynamics settle with it off.
//!
//! What remains step-dependent is the discretisation itself: measured on the dance
//! (`examples/sim_steps.rs`), the guide-tip error falls with an observed order of 0.4 to 0.7
//! at steps coarser than 1/480 s and 1 to 1.4 below; the default 1/480 s is 0.4 frames of
//! motion from converged on the smooth preset (`docs/DESIGN.md`).
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
//! the collider
//! closure writes into a `Colliders` kept by the simulator (clearing and refilling its sphere
//! vector reuses its capacity).

use super::SimParams;
use super::bend;
use super::collide::{Colliders, CollisionScene};
use super::density::DensityGrid;
use super::state::{SimState, sanitized_link_m, usable_guides};
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
    /// Guides held exactly still at the last step (see the module doc, rest).
    pub resting_guides: u32,
    /// Simulated time skipped by the catch-up cap, seconds (the hair was carried rigidly with
    /// the head over it).
    pub dropped_s: f64,
}

/// Per-guide results of one step, merged with order-independent operations.
#[derive(Clone, Copy, Default)]
struct GuideStats {
    repelled: u32,
    max_penetration_m: f32,
    reset: u32,
    grid_skipped: u32,
    resting: u32,
}

impl GuideStats {
    fn merge(a: Self, b: Self) -> Self {
        Self {
            repelled: a.repelled + b.repelled,
            max_penetration_m: a.max_penetration_m.max(b.max_penetration_m),
            reset: a.reset + b.reset,
            grid_skipped: a.grid_skipped + b.grid_skipped,
            resting: a.resting + b.resting,
        }
    }
}

/// Constant per-particle data of the rest shape, head frame.
struct Shape {
    points_per_guide: usize,
    /// Rest positions, head frame (roots and the rigid first link are placed from these).
    rest: Vec<Vec3A>,
    /// Unit rest direction of the link ending at each particle, head frame (index 0 of each
    /// guide holds the root normal).
    rest_dir: Vec<Vec3A>,
    /// Link length per guide, metres.
    link_m: Vec<f32>,
    /// Hair volume each particle of a guide stands for, m³ (`density.rs`).
    particle_volume_m3: Vec<f32>,
    /// Weights of the exact bending damping over one step (`bend::damping_weights`).
    damping_weights: Vec<f32>,
}

/// Step constants derived from [`SimParams`].
#[derive(Clone, Copy)]
struct Consts {
    dt: f32,
    inv_dt: f32,
    gravity: Vec3A,
    damping_factor: f32,
    bend_k: f32,
    bend_damp: f32,
    ftl_correction: f32,
    density_threshold: f32,
    repulsion_m2_s2: f32,
    friction_per_s: f32,
    rest_tolerance_m: f32,
    /// Steps of [`super::REST_WINDOW_S`], at least 1.
    rest_steps: u32,
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
    /// Head semi-axes given to `new`, used when the closure leaves invalid ones.
    head_radii_m: Vec3,
    /// The self-collision density grid, rebuilt every step when self-collision is on.
    grid: DensityGrid,
    /// Whether the parameters and the hair cross-section give self-collision any strength.
    self_collision_possible: bool,
    /// Self-collision on (the default when possible) or off.
    self_collision: bool,
}

/// Cross-section of real hair (m²) each guide stands for: every fibre of every render strand,
/// π r² per fibre, shared by the guides (3 per wisp), times the helix length factor
/// √(1 + (2π R / P)²) of curled strands (a curl of radius R and period P puts that much more
/// fibre length along each metre of guide).
pub fn hair_section_per_guide_m2(style: &Hairstyle, guides: &GuideSet) -> f32 {
    let fibers = style.wisps.count as f64
        * f64::from(style.wisps.strands_per_wisp)
        * f64::from(style.strands.fibers_per_strand);
    let r = f64::from(style.fiber.radius_m);
    let (cr, cp) = (
        f64::from(style.curl.radius_m),
        f64::from(style.curl.period_m),
    );
    let curl = if cr > 0.0 && cp > 0.0 {
        (1.0 + (std::f64::consts::TAU * cr / cp).powi(2)).sqrt()
    } else {
        1.0
    };
    let per_guide = fibers * std::f64::consts::PI * r * r * curl / guides.count().max(1) as f64;
    if per_guide.is_finite() {
        per_guide as f32
    } else {
        0.0
    }
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
        let ppg = guides.points_per_guide;
        let count = usable_guides(guides);
        let n = count * ppg;
        let rest: Vec<Vec3A> = guides.rest[..n].iter().map(|p| Vec3A::from(*p)).collect();
        let mut rest_dir = Vec::with_capacity(n);
        for g in 0..count {
            let normal = Vec3A::from(guides.root_normal[g]).normalize_or(Vec3A::Y);
            rest_dir.push(normal);
            for i in 1..ppg {
                let d = rest[g * ppg + i] - rest[g * ppg + i - 1];
                let prev = rest_dir[g * ppg + i - 1];
                rest_dir.push(d.normalize_or(prev));
            }
        }
        let link_m: Vec<f32> = guides.link_length_m[..count]
            .iter()
            .map(|l| sanitized_link_m(*l))
            .collect();
        let section = if hair_section_m2.is_finite() && hair_section_m2 > 0.0 {
            hair_section_m2
        } else {
            0.0
        };
        // Each of the ppg particles stands for an equal share of the guide's hair.
        let share = if ppg > 0 {
            (ppg - 1) as f32 / ppg as f32
        } else {
            0.0
        };
        let particle_volume_m3 = link_m.iter().map(|l| section * l * share).collect();
        // How far from the head centre any particle can be: root distance plus guide length.
        let reach_m = (0..count)
            .map(|g| {
                let root = rest[g * ppg].length();
                root + link_m[g] * (ppg.saturating_sub(1)) as f32
            })
            .fold(0.0f32, f32::max);
        // Grid spacing: the mean link length, so that one sample per particle gives a density
        // that is smooth along the strand (the B-spline's partition of unity), but at least
        // 1/60 of the reach, so that the whole reachable cube, 2·reach/h + 4 ≤ 124 nodes a
        // side, fits in the grid's node budget.
        let mean_link_m = if count > 0 {
            link_m.iter().map(|l| f64::from(*l)).sum::<f64>() / count as f64
        } else {
            0.02
        };
        let cell_m = (mean_link_m as f32).max(reach_m / 60.0).clamp(1e-3, 1.0);
        let dt = params.step_s;
        let omega = bend::bending_frequency_rad_s(params.bending_stiffness);
        let (bend_k, bend_damp) = bend::step_factors(
            omega,
            f64::from(params.bending_damping_ratio),
            f64::from(dt),
        );
        let consts = Consts {
            dt,
            inv_dt: 1.0 / dt,
            gravity: Vec3A::new(0.0, -params.gravity_m_s2, 0.0),
            damping_factor: (-params.damping_per_s * dt).exp(),
            bend_k,
            bend_damp,
            ftl_correction: 1.0 - (1.0 - params.ftl_correction).powf(dt / super::REFERENCE_STEP_S),
            density_threshold: params.density_threshold,
            repulsion_m2_s2: params.repulsion_m2_s2,
            friction_per_s: params.hair_friction_per_s,
            rest_tolerance_m: params.rest_tolerance_m,
            rest_steps: (super::REST_WINDOW_S / f64::from(dt)).ceil().max(1.0) as u32,
        };
        let self_collision =
            section > 0.0 && (params.repulsion_m2_s2 > 0.0 || params.hair_friction_per_s > 0.0);
        Simulator {
            params,
            consts,
            shape: Shape {
                points_per_guide: ppg,
                rest,
                rest_dir,
                link_m,
                particle_volume_m3,
                damping_weights: bend::damping_weights(bend_damp, ppg),
            },
            correction: vec![Vec3A::ZERO; n],
            colliders: Colliders::head_only(Affine3A::IDENTITY, head_radii_m),
            head_radii_m,
            grid: DensityGrid::new(cell_m, if self_collision { reach_m } else { 0.0 }),
            self_collision_possible: self_collision,
            self_collision,
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
            colliders_at(restart_s, &mut self.colliders);
            self.sanitize_colliders(state.head);
            carry_rigidly(state, self.colliders.head);
            stats.dropped_s = restart_s - state.time_s;
            state.origin_s = restart_s;
            state.steps = 0;
            state.time_s = restart_s;
        }
        // Steps to reach the instant nearest t_end_s (robust to the f32 rounding of step_s).
        let target_steps = ((t_end_s - state.origin_s) / dt).round();
        while (state.steps as f64) < target_steps {
            let t = state.origin_s + (state.steps + 1) as f64 * dt;
            colliders_at(t, &mut self.colliders);
            self.sanitize_colliders(state.head);
            let s = self.step(state);
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

    /// Keeps the previous head transform if the closure produced a non-finite one, and the
    /// head semi-axes given to `new` if it produced invalid ones (if those are invalid too,
    /// the ellipsoid test simply finds nothing inside).
    fn sanitize_colliders(&mut self, previous_head: Affine3A) {
        if !self.colliders.head.is_finite() {
            self.colliders.head = previous_head;
        }
        let r = self.colliders.head_radii_m;
        if !(r.is_finite() && r.min_element() > 0.0) {
            self.colliders.head_radii_m = self.head_radii_m;
        }
    }

    /// One fixed step of every guide, in parallel.
    fn step(&mut self, state: &mut SimState) -> GuideStats {
        let ppg = self.shape.points_per_guide;
        // 0. The density grid of the positions and velocities the step starts from, in the head
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
        let grid = if self.self_collision && self.grid.is_active() {
            Some(&self.grid)
        } else {
            None
        };
        let scene = CollisionScene::new(&self.colliders);
        let head = self.colliders.head;
        let head_rot = Quat::from_mat3a(&head.matrix3).normalize();
        let frame = Frame {
            head,
            head_rot,
            scene: &scene,
        };
        let shape = &self.shape;
        let c = self.consts;
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
                let rest = Rest { anchor, still };
                step_guide(g, pos, prev, vel, corr, rest, shape, &c, &frame, grid)
            })
            .reduce(GuideStats::default, GuideStats::merge);
        GuideStats {
            grid_skipped,
            ..stats
        }
    }
}

/// Moves the whole state rigidly from its head pose to `new_head` (used when a time gap is
/// skipped): positions, previous positions and velocities.
fn carry_rigidly(state: &mut SimState, new_head: Affine3A) {
    let delta = new_head * state.head.inverse();
    for p in state
        .positions
        .iter_mut()
        .chain(state.prev_positions.iter_mut())
    {
        *p = delta.transform_point3(*p);
    }
    for v in &mut state.velocities {
        *v = delta.transform_vector3(*v);
    }
    state.anchor.copy_from_slice(&state.positions);
    state.still_steps.iter_mut().for_each(|s| *s = 0);
    state.head = new_head;
}

/// One guide's rest bookkeeping (see the module doc, rest).
struct Rest<'a> {
    anchor: &'a mut [Vec3],
    still: &'a mut u32,
}

/// The head pose of one step.
struct Frame<'a> {
    head: Affine3A,
    head_rot: Quat,
    scene: &'a CollisionScene<'a>,
}

/// One step of guide `g` (see the module doc for the stages).
#[allow(clippy::too_many_arguments)]
fn step_guide(
    g: usize,
    pos: &mut [Vec3],
    prev: &mut [Vec3],
    vel: &mut [Vec3],
    corr: &mut [Vec3A],
    rest_state: Rest,
    shape: &Shape,
    c: &Consts,
    frame: &Frame,
    grid: Option<&DensityGrid>,
) -> GuideStats {
    let ppg = pos.len();
    let base = g * ppg;
    let rest = &shape.rest[base..base + ppg];
    let rest_dir = &shape.rest_dir[base..base + ppg];
    let link = shape.link_m[g];
    let inv_link = 1.0 / link;
    let mut stats = GuideStats::default();
    prev.copy_from_slice(pos);

    // 1. Kinematic root segment.
    for i in 0..2.min(ppg) {
        pos[i] = Vec3::from(frame.head.transform_point3a(rest[i]));
        corr[i] = Vec3A::ZERO;
    }
    // 2. Forces and prediction.
    for i in 2..ppg {
        let x = Vec3A::from(prev[i]);
        let mut v = Vec3A::from(vel[i]);
        let mut a = c.gravity;
        if let Some(grid) = grid {
            let hair = grid.around(x);
            if c.friction_per_s > 0.0 && hair.volume_fraction > 0.0 {
                let fullness = if c.density_threshold > 0.0 {
                    (hair.volume_fraction / c.density_threshold).min(1.0)
                } else {
                    1.0
                };
                let keep = (-c.friction_per_s * fullness * c.dt).exp();
                v = hair.mean_velocity_m_s + (v - hair.mean_velocity_m_s) * keep;
            }
            if c.repulsion_m2_s2 > 0.0 && hair.excess_gradient_per_m != Vec3A::ZERO {
                a -= hair.excess_gradient_per_m * c.repulsion_m2_s2;
                stats.repelled += 1;
            }
        }
        let v = v * c.damping_factor + a * c.dt;
        pos[i] = Vec3::from(x + v * c.dt);
    }
    // 3. Root-to-tip sweep: bending, follow the leader, collisions.
    let mut q = frame.head_rot;
    let mut p_prev = Vec3A::from(pos[1.min(ppg - 1)]);
    for i in 2..ppg {
        // Unit to rounding: q is a unit quaternion, rest_dir a unit vector.
        let target_dir = q * rest_dir[i];
        let mut p = Vec3A::from(pos[i]);
        p += (p_prev + target_dir * link - p) * c.bend_k;
        let dir = (p - p_prev).normalize_or(target_dir);
        let p_ftl = p_prev + dir * link;
        corr[i] = p_ftl - p;
        let (p_final, touched) = frame.scene.resolve(p_prev, p_ftl, link, target_dir);
        if touched {
            stats.max_penetration_m = stats
                .max_penetration_m
                .max(frame.scene.penetration_m(p_final));
        }
        // |p_final − p_prev| = L to rounding, so no square root is needed; q is rebuilt from
        // the head rotation every step, so rounding drift cannot accumulate beyond one strand.
        let actual_dir = (p_final - p_prev) * inv_link;
        q = bend::rotation_arc(target_dir, actual_dir) * q;
        pos[i] = Vec3::from(p_final);
        p_prev = p_final;
    }
    // 4. Velocities with the DFTL correction of the next particle.
    for i in 0..ppg {
        let mut v = (Vec3A::from(pos[i]) - Vec3A::from(prev[i])) * c.inv_dt;
        if i >= 2 && i + 1 < ppg {
            v -= corr[i + 1] * (c.ftl_correction * c.inv_dt);
        }
        vel[i] = Vec3::from(v);
    }
    // 5. Bending damping, root to tip (after the velocities it damps).
    if c.bend_damp > 0.0 && ppg >= 3 {
        bend::damp_bending(pos, vel, &shape.damping_weights);
    }
    // 6. Rest: held exactly still once it has stayed within the tolerance for the window.
    let Rest { anchor, still } = rest_state;
    if c.rest_tolerance_m > 0.0 {
        let roots = 2.min(ppg);
        let roots_still = pos[..roots] == anchor[..roots];
        let tol2 = c.rest_tolerance_m * c.rest_tolerance_m;
        let near = pos[roots..]
            .iter()
            .zip(&anchor[roots..])
            .all(|(p, a)| (*p - *a).length_squared() <= tol2);
        if roots_still && near {
            *still = still.saturating_add(1);
            if *still >= c.rest_steps {
                pos.copy_from_slice(anchor);
                stats.resting = 1;
            }
        } else {
            anchor.copy_from_slice(pos);
            *still = 0;
        }
    }
    // NaN guard: a guide that went non-finite restarts from its rest shape, at rest.
    if !pos.iter().chain(vel.iter()).all(|p| p.is_finite()) {
        for i in 0..ppg {
            pos[i] = Vec3::from(frame.head.transform_point3a(rest[i]));
            prev[i] = pos[i];
            vel[i] = Vec3::ZERO;
        }
        anchor.copy_from_slice(pos);
        *still = 0;
        stats.reset = 1;
        stats.resting = 0;
        stats.max_penetration_m = 0.0;
    }
    stats
}

#[cfg(test)]
mod tests;
