//! The state of the guide strands between steps, and its construction in the rest pose.
//!
//! What: world positions of every guide particle (same indexing as `GuideSet::rest`), the
//! integrator's velocities, the positions before the last step (for the measured kinetic
//! energy), the head transform the positions belong to, and the step clock.
//!
//! Why a step clock instead of a float accumulator: the time of step `n` is computed as
//! `origin + n · step` in f64, never by summing, so how a caller slices time (1/30 s or 1/60 s
//! frames) cannot change which instants are simulated; results are then identical bit for bit.

use super::collide::{Colliders, CollisionScene};
use crate::hairstyle::GuideSet;
use glam::{Affine3A, Vec3, Vec3A};

/// Positions and velocities of all guide particles at `time_s`.
#[derive(Clone, Debug)]
pub struct SimState {
    /// World positions in metres, guide-major like `GuideSet::rest`.
    pub positions: Vec<Vec3>,
    /// Simulated time of `positions` in seconds (a step instant: `origin + n · step_s`). An
    /// output: the step clock behind it is private, so to restart at another time build a new
    /// state with [`SimState::at_rest`] rather than writing this field.
    pub time_s: f64,
    /// Integrator velocities in m/s (after the follow-the-leader velocity correction).
    pub(crate) velocities: Vec<Vec3>,
    /// Positions before the last step (equal to `positions` before any step).
    pub(crate) prev_positions: Vec<Vec3>,
    /// Head frame → world at `time_s`.
    pub(crate) head: Affine3A,
    /// Start of the step clock, seconds.
    pub(crate) origin_s: f64,
    /// Steps taken since `origin_s`.
    pub(crate) steps: u64,
    /// Duration of the last step in seconds (0 before the first step).
    pub(crate) last_step_s: f32,
    /// Where each particle was when its guide's current rest window began (`guide_step.rs`, rest).
    pub(crate) anchor: Vec<Vec3>,
    /// Per guide: consecutive steps its roots stayed bitwise put and its particles within the
    /// rest tolerance of `anchor`.
    pub(crate) still_steps: Vec<u32>,
}

impl SimState {
    /// The guides in their rest shape attached to the head at `colliders.head` (or to their
    /// carriers, `GuideSet::carrier`), at rest, at
    /// time `t_s`. Particles the rest shape puts inside a body sphere (or the head) are moved
    /// out root to tip with the same projection the simulator uses, so the first step starts
    /// from a valid state instead of popping out of a collider at high speed. The first two
    /// particles of each guide (the rigid root segment) are never moved. A non-finite head
    /// transform is replaced by the identity (and the spheres ignored).
    pub fn at_rest(guides: &GuideSet, colliders: &Colliders, t_s: f64) -> SimState {
        let ppg = guides.points_per_guide;
        let count = usable_guides(guides);
        let n = count * ppg;
        // A non-finite head transform would make every position NaN: use the identity instead.
        let fallback;
        let colliders = if colliders.head.is_finite() {
            colliders
        } else {
            fallback = Colliders::head_only(Affine3A::IDENTITY, colliders.head_radii_m);
            &fallback
        };
        let head = colliders.head;
        let scene = CollisionScene::new(colliders);
        let mut positions = Vec::with_capacity(n);
        for g in 0..count {
            let rest = guides.guide(g);
            let head = guides.root_frame(g, head, &colliders.carriers);
            let link = sanitized_link_m(guides.link_length_m[g]);
            let mut prev = Vec3A::ZERO;
            for (i, r) in rest.iter().enumerate() {
                let mut p = head.transform_point3a(Vec3A::from(*r));
                if i >= 2 {
                    let fallback = head
                        .transform_vector3a(Vec3A::from(rest[i] - rest[i - 1]))
                        .normalize_or(head.transform_vector3a(Vec3A::from(guides.root_normal[g])));
                    let dir = (p - prev).normalize_or(fallback);
                    p = scene.resolve(prev, prev + dir * link, link, fallback).0;
                }
                positions.push(Vec3::from(p));
                prev = p;
            }
        }
        let t_s = if t_s.is_finite() { t_s } else { 0.0 };
        SimState {
            prev_positions: positions.clone(),
            anchor: positions.clone(),
            still_steps: vec![0; count],
            velocities: vec![Vec3::ZERO; n],
            positions,
            time_s: t_s,
            head,
            origin_s: t_s,
            steps: 0,
            last_step_s: 0.0,
        }
    }

    /// Restarts the step clock at `t_s`: the next steps are at `t_s + n · step_s`, for the
    /// simulator's step then (after [`super::Simulator::set_step_s`]), `step_ratio` times the
    /// step before. The rest windows (`guide_step.rs`, rest) count steps, so each guide's count
    /// is divided by `step_ratio`: a guide keeps the time it has been still, and a guide held
    /// at rest stays held.
    pub(crate) fn restart_clock(&mut self, t_s: f64, step_ratio: f64) {
        self.time_s = t_s;
        self.origin_s = t_s;
        self.steps = 0;
        for s in &mut self.still_steps {
            *s = (f64::from(*s) / step_ratio).min(f64::from(u32::MAX)) as u32;
        }
    }

    /// Kinetic energy per unit particle mass, Σ ½|v|² in m²/s², with `v` the displacement of
    /// each particle over the last step divided by its duration (the motion one sees, not the
    /// integrator's corrected velocity; the two differ by the follow-the-leader correction,
    /// which is not zero in a hanging strand at rest). 0 before the first step. Summed in f64
    /// in index order, so the value does not depend on the thread count.
    pub fn kinetic_energy(&self) -> f64 {
        if self.last_step_s <= 0.0 {
            return 0.0;
        }
        let inv_dt = 1.0 / f64::from(self.last_step_s);
        self.positions
            .iter()
            .zip(&self.prev_positions)
            .map(|(p, q)| 0.5 * ((*p - *q).as_dvec3() * inv_dt).length_squared())
            .sum()
    }

    /// Largest speed of any particle over the last step, m/s: its displacement divided by the
    /// step's duration (as in [`SimState::kinetic_energy`]); 0 before the first step.
    pub fn max_speed_m_s(&self) -> f64 {
        if self.last_step_s <= 0.0 {
            return 0.0;
        }
        let inv_dt = 1.0 / f64::from(self.last_step_s);
        self.positions
            .iter()
            .zip(&self.prev_positions)
            .map(|(p, q)| f64::from((*p - *q).length()) * inv_dt)
            .fold(0.0, f64::max)
    }

    /// The integrator's velocities in m/s (guide-major).
    pub fn velocities(&self) -> &[Vec3] {
        &self.velocities
    }

    /// Head frame → world at `time_s`.
    pub fn head(&self) -> Affine3A {
        self.head
    }
}

/// Number of complete guides in `guides` (defensive against inconsistent hand-built sets).
pub(crate) fn usable_guides(guides: &GuideSet) -> usize {
    if guides.points_per_guide < 2 {
        return 0;
    }
    guides
        .count()
        .min(guides.root_normal.len())
        .min(guides.rest.len() / guides.points_per_guide)
}

/// A usable link length: non-finite or non-positive lengths (impossible from `generate`) become
/// 1 mm rather than NaN positions.
pub(crate) fn sanitized_link_m(l: f32) -> f32 {
    if l.is_finite() && l > 0.0 { l } else { 1e-3 }
}
