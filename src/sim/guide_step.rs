//! One fixed step of one guide: the kinematic root segment, forces, the root-to-tip sweep of
//! bending, follow-the-leader links and collisions, velocities, bending damping, and rest.
//!
//! Particles `0..n` run root to tip; stage 0, the density grid the forces read, is built once
//! for all guides before them (`step.rs`, `density.rs`).
//!
//! 1. **Kinematic root segment.** Particles 0 and 1 are the rest positions carried by the head
//!    transform (or by the bone that carries the guide, `GuideSet::carrier`): the root sits on the scalp and the first link keeps its rest direction relative
//!    to the head, the slant at which the hair leaves its follicle (the rest generator starts a
//!    generated guide 25° above the scalp, toward its comb). A follicle does not pivot, so a
//!    rigid first link is the physical reading, and it removes the need for a stiff (and
//!    step-limiting) root constraint.
//! 2. **Forces, symplectic Euler.** For free particles (i ≥ 2): hair-hair friction
//!    `v ← v̄ + (v − v̄) e^{−c dt}` toward the local mean velocity v̄, then
//!    `v ← v · exp(−damping_per_s · dt) + dt · (g + a_rep)`, `p* = x + dt · v`, with
//!    `g = (0, −gravity_m_s2, 0)` and `a_rep = −K ∇ẽ(x)` the Bertails §4.1 repulsion
//!    (`density.rs`), all read at `x` from the grid of this step. The decay factors are exact
//!    solutions of `dv/dt = −c v` over the step, so they do not depend on `dt`.
//! 3. **Root-to-tip sweep** (Gauss–Seidel, each particle sees its predecessor's final position):
//!    - a) *Bending.* `Q` is a rotation carrying rest directions (head frame) to the current
//!      frame of the previous link, parallel-transported down the strand: `Q₁ = R_head` (the
//!      carrier's rotation for a carried guide), and
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
//!      kept for stage 4. A degenerate direction falls back to `tᵢ`.
//!    - c) *Collisions* (`collide.rs`): out of the head ellipsoid, the spheres and the
//!      capsules, keeping the particle on the sphere of radius L around `pᵢ₋₁`; the length
//!      projection is always last.
//!    - d) *Static friction on a still scene.* When no collider moved since the step before
//!      (a still head and body), a particle that touched one and would move less than
//!      [`STICK_SPEED_M_S`] × dt (0.1 m/s) goes back to where it was, at one link from
//!      `pᵢ₋₁`, and through the collisions again. Without it contact is frictionless, and a
//!      guide lying across a still character's shoulder slid on at the speed the settle left
//!      it, slowed only by air damping (measured on the dance held still: one guide 2 mm per
//!      frame at the first frame, 37 mm over the next 3 s; 34 of 402 guides not at rest).
//!      Hair on cloth or skin does not creep. A moving scene keeps frictionless contact: the
//!      collider's own motion would be needed to hold a particle relative to it.
//! 4. **Velocities** (DFTL velocity update): `vᵢ = (pᵢ − xᵢ)/dt − s · dᵢ₊₁/dt` with
//!    `s = ftl_correction` (default 0.5; `d` past the tip is 0). Plain FTL moves a particle
//!    without moving its predecessor, as if each particle were infinitely heavier than the
//!    next; adding back the child's correction approximates the reaction on the parent. Measured
//!    here: with `s = 0` a limp guide set (`bending_stiffness` 0) never settles under a still
//!    head (kinetic energy still 1e4 m²/s² after 10 s), with `s` = 0.5 or 0.9 it settles within
//!    8 s; on the stiff presets `s` changes dance kinetic energy by about 1%. But `s > 0` keeps
//!    a velocity `−s·dᵢ₊₁/dt` in every hanging particle at rest (undone each step by the
//!    projection), whose rounding noise raises the rest kinetic-energy floor from 3e-7 (s = 0)
//!    to 4e-6 (0.5) and 3e-4 m²/s² (0.9) and makes settled particles wander 0.3 mm (0.9). 0.5 is
//!    the compromise. `s` is defined per 1/240 s: a step of `dt` uses
//!    `1 − (1 − s)^(dt / (1/240 s))`, because the correction acts as a damping per step:
//!    measured, s = 0.5 against s = 0 moves the dance's guide tips by 0.94 mm RMS at 1/240 s
//!    but 4.3 mm at 1/1920 s without the scaling; with it, 1.35 / 0.94 / 0.82 / 0.64 mm at
//!    1/60, 1/240, 1/960 and 1/1920 s.
//! 5. **Bending damping.** Each link's angular velocity relative to its parent link decays at
//!    the damping rate of the same exactly advanced oscillator as `k` (ratio
//!    `ζ = bending_damping_ratio`, default 1), solved exactly over the step for the whole chain
//!    (`bend::damp_bending`, also for why it is needed and why exactly). Rigid swinging of the
//!    whole strand (equal angular velocities) is untouched, so air damping alone still sets
//!    how long hair swings.
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
//! A guide that turns non-finite restarts from its rest shape, at rest, and is counted.

use super::SimParams;
use super::bend;
use super::collide::CollisionScene;
use super::density::DensityGrid;
use super::shape::Shape;
use glam::{Affine3A, Quat, Vec3, Vec3A};

/// Step constants derived from [`SimParams`].
#[derive(Clone, Copy)]
pub(super) struct Consts {
    pub(super) dt: f32,
    pub(super) inv_dt: f32,
    pub(super) gravity: Vec3A,
    pub(super) damping_factor: f32,
    pub(super) bend_k: f32,
    pub(super) bend_damp: f32,
    pub(super) ftl_correction: f32,
    pub(super) density_threshold: f32,
    pub(super) repulsion_m2_s2: f32,
    pub(super) friction_per_s: f32,
    pub(super) rest_tolerance_m: f32,
    /// Steps of [`super::REST_WINDOW_S`], at least 1.
    pub(super) rest_steps: u32,
}

impl Consts {
    /// The per-step factors of `params` (sanitised) at its step (module doc: exact decays,
    /// the bending oscillator's `k` and `κ`, the FTL correction scaled from 1/240 s).
    pub(super) fn new(params: &SimParams) -> Consts {
        let dt = params.step_s;
        let omega = bend::bending_frequency_rad_s(params.bending_stiffness);
        let (bend_k, bend_damp) = bend::step_factors(
            omega,
            f64::from(params.bending_damping_ratio),
            f64::from(dt),
        );
        Consts {
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
        }
    }
}

/// Per-guide results of one step, merged with order-independent operations.
#[derive(Clone, Copy, Default)]
pub(super) struct GuideStats {
    pub(super) repelled: u32,
    pub(super) max_penetration_m: f32,
    pub(super) reset: u32,
    pub(super) grid_skipped: u32,
    pub(super) resting: u32,
}

impl GuideStats {
    pub(super) fn merge(a: Self, b: Self) -> Self {
        Self {
            repelled: a.repelled + b.repelled,
            max_penetration_m: a.max_penetration_m.max(b.max_penetration_m),
            reset: a.reset + b.reset,
            grid_skipped: a.grid_skipped + b.grid_skipped,
            resting: a.resting + b.resting,
        }
    }
}

/// One guide's particles in the state and the simulator's scratch (`points_per_guide` each).
pub(super) struct Guide<'a> {
    /// Positions, world; the step's result.
    pub(super) pos: &'a mut [Vec3],
    /// Positions before the step (written here).
    pub(super) prev: &'a mut [Vec3],
    /// Velocities, world.
    pub(super) vel: &'a mut [Vec3],
    /// Follow-the-leader corrections `d` of the step (scratch).
    pub(super) corr: &'a mut [Vec3A],
    /// Where each particle was when the guide's rest window began (stage 6).
    pub(super) anchor: &'a mut [Vec3],
    /// Steps the guide has stayed within the rest tolerance.
    pub(super) still: &'a mut u32,
}

/// What every guide reads in one step: the rest shape, the constants, the head pose, the
/// colliders and the density grid (when self-collision is on and the grid usable).
pub(super) struct StepInputs<'a> {
    pub(super) shape: &'a Shape,
    pub(super) consts: &'a Consts,
    pub(super) head: Affine3A,
    pub(super) head_rot: Quat,
    /// Head frame → world of each bone that carries roots, and its rotation
    /// (`Colliders::carriers`); the guides' carrier indices are in `shape.carrier`.
    pub(super) carriers: &'a [Affine3A],
    pub(super) carrier_rot: &'a [Quat],
    pub(super) scene: &'a CollisionScene<'a>,
    /// No collider moved since the step before (stage 3d).
    pub(super) still_scene: bool,
    pub(super) grid: Option<&'a DensityGrid>,
}

impl StepInputs<'_> {
    /// Head frame → world for guide `g`'s root, and its rotation: its carrier's, or the
    /// head's when it has none (hair on a head) or the carrier is missing.
    #[inline]
    fn root_frame(&self, g: usize) -> (Affine3A, Quat) {
        match self.shape.carrier.get(g).map(|&c| c as usize) {
            Some(c) if c < self.carriers.len() && c < self.carrier_rot.len() => {
                (self.carriers[c], self.carrier_rot[c])
            }
            _ => (self.head, self.head_rot),
        }
    }
}

/// One step of guide `g` (module doc for the stages).
pub(super) fn step_guide(g: usize, guide: Guide, inputs: &StepInputs) -> GuideStats {
    let Guide {
        pos,
        prev,
        vel,
        corr,
        anchor,
        still,
    } = guide;
    let (c, shape) = (inputs.consts, inputs.shape);
    let ppg = pos.len();
    let base = g * ppg;
    let rest = &shape.rest[base..base + ppg];
    let mut stats = GuideStats::default();
    prev.copy_from_slice(pos);
    let (root_frame, root_rot) = inputs.root_frame(g);

    // 1. Kinematic root segment.
    for i in 0..2.min(ppg) {
        pos[i] = Vec3::from(root_frame.transform_point3a(rest[i]));
        corr[i] = Vec3A::ZERO;
    }
    // 2. Forces and prediction.
    stats.repelled = predict(pos, prev, vel, c, inputs.grid);
    // 3. Root-to-tip sweep: bending, follow the leader, collisions.
    let rest_dir = &shape.rest_dir[base..base + ppg];
    let link = shape.link_m[g];
    stats.max_penetration_m = sweep(pos, prev, corr, rest_dir, link, root_rot, inputs);
    // 4. Velocities with the DFTL correction of the next particle.
    update_velocities(pos, prev, vel, corr, c);
    // 5. Bending damping, root to tip (after the velocities it damps).
    if c.bend_damp > 0.0 && ppg >= 3 {
        bend::damp_bending(pos, vel, &shape.damping_weights);
    }
    // 6. Rest: held exactly still once it has stayed within the tolerance for the window.
    if c.rest_tolerance_m > 0.0 && hold_at_rest(pos, anchor, still, c) {
        stats.resting = 1;
    }
    // A guide that went non-finite restarts from its rest shape, at rest.
    if !pos.iter().chain(vel.iter()).all(|p| p.is_finite()) {
        for i in 0..ppg {
            pos[i] = Vec3::from(root_frame.transform_point3a(rest[i]));
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

/// Stage 2: friction toward the hair's mean velocity, damping, gravity and repulsion, and the
/// predicted positions `pos[i] = prev[i] + dt · v` of the free particles (i ≥ 2). Returns how
/// many particles the repulsion pushed.
#[inline]
fn predict(
    pos: &mut [Vec3],
    prev: &[Vec3],
    vel: &[Vec3],
    c: &Consts,
    grid: Option<&DensityGrid>,
) -> u32 {
    let mut repelled = 0;
    for i in 2..pos.len() {
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
                repelled += 1;
            }
        }
        let v = v * c.damping_factor + a * c.dt;
        pos[i] = Vec3::from(x + v * c.dt);
    }
    repelled
}

/// Stage 3: the root-to-tip sweep of the free particles (bending pull, follow the leader,
/// collisions), links of `link` metres; records each correction in `corr`. Returns the
/// largest penetration left in a collider.
#[inline]
fn sweep(
    pos: &mut [Vec3],
    prev: &[Vec3],
    corr: &mut [Vec3A],
    rest_dir: &[Vec3A],
    link: f32,
    root_rot: Quat,
    inputs: &StepInputs,
) -> f32 {
    let ppg = pos.len();
    let (bend_k, inv_link) = (inputs.consts.bend_k, 1.0 / link);
    let mut max_penetration_m = 0.0f32;
    let mut q = root_rot;
    let mut p_prev = Vec3A::from(pos[1.min(ppg - 1)]);
    for i in 2..ppg {
        // Unit to rounding: q is a unit quaternion, rest_dir a unit vector.
        let target_dir = q * rest_dir[i];
        let mut p = Vec3A::from(pos[i]);
        p += (p_prev + target_dir * link - p) * bend_k;
        let dir = (p - p_prev).normalize_or(target_dir);
        let p_ftl = p_prev + dir * link;
        corr[i] = p_ftl - p;
        let (mut p_final, touched) = inputs.scene.resolve(p_prev, p_ftl, link, target_dir);
        if touched && inputs.still_scene {
            p_final = stick(p_final, Vec3A::from(prev[i]), p_prev, link, inputs);
        }
        if touched {
            max_penetration_m = max_penetration_m.max(inputs.scene.penetration_m(p_final));
        }
        // |p_final − p_prev| = L to rounding, so no square root is needed; q is rebuilt from
        // the root's rotation every step, so rounding drift cannot accumulate beyond one strand.
        let actual_dir = (p_final - p_prev) * inv_link;
        q = bend::rotation_arc(target_dir, actual_dir) * q;
        pos[i] = Vec3::from(p_final);
        p_prev = p_final;
    }
    max_penetration_m
}

/// Largest speed at which a particle touching a still collider stays put (stage 3d), m/s.
pub(super) const STICK_SPEED_M_S: f32 = 0.1;

/// Stage 3d: static friction on a still collider. A particle that touches one and would move
/// less than `STICK_SPEED_M_S · dt` from where it was (`was`) goes back there, at one link
/// from its predecessor `p_prev` (which may have moved) and out of the colliders again;
/// otherwise it keeps `p` (what the collisions gave).
#[inline]
fn stick(p: Vec3A, was: Vec3A, p_prev: Vec3A, link: f32, inputs: &StepInputs) -> Vec3A {
    let reach = STICK_SPEED_M_S * inputs.consts.dt;
    if (p - was).length_squared() >= reach * reach {
        return p;
    }
    let fallback = (p - p_prev) * (1.0 / link);
    let back = p_prev + (was - p_prev).normalize_or(fallback) * link;
    inputs.scene.resolve(p_prev, back, link, fallback).0
}

/// Stage 4: velocities from the step's displacement, less the share `ftl_correction` of the
/// next particle's follow-the-leader correction (free particles but the tip).
#[inline]
fn update_velocities(pos: &[Vec3], prev: &[Vec3], vel: &mut [Vec3], corr: &[Vec3A], c: &Consts) {
    let ppg = pos.len();
    for i in 0..ppg {
        let mut v = (Vec3A::from(pos[i]) - Vec3A::from(prev[i])) * c.inv_dt;
        if i >= 2 && i + 1 < ppg {
            v -= corr[i + 1] * (c.ftl_correction * c.inv_dt);
        }
        vel[i] = Vec3::from(v);
    }
}

/// Stage 6: counts the steps the guide's roots stayed bitwise put and its particles within
/// the rest tolerance of `anchor`, and once they reach the rest window puts the particles
/// back at `anchor`; otherwise starts a new window at the current positions. Whether the
/// guide is held.
#[inline]
fn hold_at_rest(pos: &mut [Vec3], anchor: &mut [Vec3], still: &mut u32, c: &Consts) -> bool {
    let roots = 2.min(pos.len());
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
            return true;
        }
    } else {
        anchor.copy_from_slice(pos);
        *still = 0;
    }
    false
}
