//! The simulation pass: the guide strands of every wisp as rigid links (Bertails 2005 §4),
//! roots on the moving scalp, with gravity, damping, bending, collisions with the head and
//! body, and self-collision from the simulator's own density grid (`crate::sim`). Without
//! simulation the guides ride rigidly on the head in their rest pose.

use super::setup::{colliders_of, write_colliders};
use super::sizes::RunSizes;
use crate::budget::{MemoryPart, WorkPart, cost_ns, grouped};
use crate::hairstyle::{GuideSet, Hairstyle};
use crate::motion::{Motion, Pose};
use crate::sim::{CoarseSettle, Colliders, SimState, Simulator, StepStats};
use glam::Vec3;

/// How the guides move.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimulationConfig {
    /// Simulate the guides; `false` keeps them in their rest pose riding on the head
    /// (default true).
    pub simulate: bool,
    /// Density-based self-collision (Bertails §4.1; default true).
    pub self_collision: bool,
    /// Seconds of simulated time with the head held at the first pose before frame 0, so the
    /// hair starts settled (default 2).
    pub settle_s: f64,
    /// The simulation step, seconds, in (1e-5, 0.05] (default `None`: the hairstyle's
    /// `dynamics.step_s`). Every parameter is a rate per unit time, so a step changes only the
    /// discretisation error (ACCURACY.md §4's step table).
    pub step_s: Option<f32>,
    /// The step of the settle but its last [`crate::sim::SETTLE_TAIL_S`], seconds, when longer than the
    /// simulation's (`crate::sim::settle`; default `None`: the simulation's step throughout).
    /// Imported grooms settle in [`GROOM_SETTLE_STEP_S`].
    pub settle_step_s: Option<f32>,
}

/// The settle step of imported grooms, seconds (`crate::sim::settle`: 4× fewer steps before
/// the first frame than at 1/480 s).
pub const GROOM_SETTLE_STEP_S: f32 = 1.0 / 60.0;

impl Default for SimulationConfig {
    fn default() -> Self {
        Self {
            simulate: true,
            self_collision: true,
            settle_s: 2.0,
            step_s: None,
            settle_step_s: None,
        }
    }
}

impl SimulationConfig {
    /// The step the simulation of `style` takes, seconds.
    pub fn step_s(&self, style: &Hairstyle) -> f32 {
        self.step_s.unwrap_or(style.dynamics.step_s)
    }
}

/// The simulator, the guides' state and the figures of the last advance.
pub struct SimulationPass {
    pub config: SimulationConfig,
    sim: Simulator,
    /// The guide particles (positions, velocities) and the simulation's clock.
    pub state: SimState,
    /// Scratch pose for the sub-steps' collider queries (reused, no allocation).
    scratch_pose: Pose,
    /// Figures of the last advance.
    pub stats: StepStats,
    /// The settle in coarse steps, while it lasts (`SimulationConfig::settle_step_s`).
    settle: Option<CoarseSettle>,
}

impl SimulationPass {
    /// The guides at rest on the head of `pose` (the motion at t = 0), at −`settle_s`.
    pub fn new(
        config: SimulationConfig,
        style: &Hairstyle,
        guides: &GuideSet,
        pose: &Pose,
        head_radii_m: Vec3,
    ) -> Self {
        let mut stepped = style.clone();
        stepped.dynamics.step_s = config.step_s(style);
        let mut sim = Simulator::from_hairstyle(&stepped, guides);
        sim.set_self_collision(config.self_collision);
        let state = SimState::at_rest(guides, &colliders_of(pose, head_radii_m), -config.settle_s);
        let settle = config
            .settle_step_s
            .filter(|_| config.simulate)
            .and_then(|coarse| {
                CoarseSettle::start(&mut sim, &state, 0.0, coarse, crate::sim::SETTLE_TAIL_S)
            });
        Self {
            config,
            sim,
            state,
            scratch_pose: pose.clone(),
            stats: StepStats::default(),
            settle,
        }
    }

    /// Advances the guides to `t_s` with the head and body following `motion` (sampled at each
    /// sub-step); `pose` is the motion at `t_s`, which rigid guides ride on.
    pub fn run(
        &mut self,
        t_s: f64,
        motion: &Motion,
        pose: &Pose,
        guides: &GuideSet,
        head_radii_m: Vec3,
    ) {
        if self.config.simulate {
            let scratch_pose = &mut self.scratch_pose;
            let mut colliders_at = |t: f64, c: &mut Colliders| {
                motion.sample_into(t.max(0.0) as f32, scratch_pose);
                write_colliders(scratch_pose, head_radii_m, c);
            };
            self.sim.set_self_collision(self.config.self_collision);
            let mut settled = StepStats::default();
            if let Some(settle) = self.settle {
                let (stats, done) =
                    settle.advance(&mut self.sim, &mut self.state, t_s, &mut colliders_at);
                if !done {
                    self.stats = stats;
                    return;
                }
                self.settle = None;
                settled = stats;
            }
            let stats = self.sim.advance(&mut self.state, t_s, colliders_at);
            self.stats = settled.then(stats);
        } else {
            let ppg = guides.points_per_guide.max(1);
            let guide_points = self.state.positions.chunks_mut(ppg);
            for (g, (ps, rs)) in guide_points.zip(guides.rest.chunks(ppg)).enumerate() {
                let frame = guides.root_frame(g, pose.head, &pose.carriers);
                for (p, r) in ps.iter_mut().zip(rs) {
                    *p = frame.transform_point3(*r);
                }
            }
            self.state.time_s = t_s;
        }
    }

    /// Sets the guide particles to `positions` (a frame of a simulation cache) at `t_s`:
    /// extra entries are ignored, missing ones keep their value. Velocities and the step clock
    /// are not set, so a later [`Self::run`] does not continue the cached motion.
    pub fn set_positions(&mut self, positions: &[Vec3]) {
        for (p, q) in self.state.positions.iter_mut().zip(positions) {
            *p = *q;
        }
    }

    /// The simulator's state and buffers.
    pub fn estimate(sizes: &RunSizes) -> Vec<MemoryPart> {
        vec![MemoryPart {
            what: "simulation",
            product: format!(
                "{} guides × {} particles",
                grouped(sizes.guides),
                sizes.points_per_guide
            ),
            bytes: Simulator::estimated_bytes(sizes.guides, sizes.points_per_guide),
            set_by: "wisps.count × guides.links",
        }]
    }

    /// The simulation before the first frame: the settle, the warm-up and the first frame's
    /// steps (or rigid updates without simulation); nothing when the guides are read from a
    /// cache.
    pub fn work_before_first_frame(config: &SimulationConfig, sizes: &RunSizes) -> WorkPart {
        let particles = sizes.particles;
        let (product, cpu_s) = if sizes.from_cache {
            (
                format!("{} guide particles read from the cache", grouped(particles)),
                0.0,
            )
        } else if config.simulate {
            let steps = steps_before_first_frame(config, sizes);
            (
                format!(
                    "{} guide particles × {} steps of {:.4} s over {:.3e} s",
                    grouped(particles),
                    grouped(steps as u64),
                    sizes.step_s,
                    sizes.before_first_s + sizes.frame_s
                ),
                particles as f64 * steps * cost_ns::PARTICLE_STEP * 1e-9,
            )
        } else {
            (
                format!(
                    "{} guide particles × {} rigid updates",
                    grouped(particles),
                    sizes.warm_up_slices + 1.0
                ),
                particles as f64 * (sizes.warm_up_slices + 1.0) * cost_ns::POINT_INTERP * 1e-9,
            )
        };
        // The simulated span is the settle and the warm-up to the first frame, then the first
        // frame's own 1/fps: name the flag behind the larger.
        let set_by = if sizes.frame_s > sizes.before_first_s {
            "wisps.count × guides.links, dynamics.step_s, --fps: the first frame alone lasts 1/fps"
        } else {
            "wisps.count × guides.links, dynamics.step_s, --start-s"
        };
        WorkPart {
            what: "settle and warm-up simulation",
            product,
            cpu_s,
            set_by,
        }
    }
}

/// Steps the simulation takes before the first frame is drawn: the settle's coarse steps
/// (`SimulationConfig::settle_step_s`), then steps of the simulation's own step up to the end of
/// the first frame.
fn steps_before_first_frame(config: &SimulationConfig, sizes: &RunSizes) -> f64 {
    let fine_s = sizes.before_first_s + sizes.frame_s;
    let coarse_span_s = config.settle_s.min(sizes.before_first_s) - crate::sim::SETTLE_TAIL_S;
    match config.settle_step_s {
        Some(coarse) if f64::from(coarse) > sizes.step_s && coarse_span_s > 0.0 => {
            (coarse_span_s / f64::from(coarse)).ceil()
                + ((fine_s - coarse_span_s) / sizes.step_s).ceil()
        }
        _ => (fine_s / sizes.step_s).ceil(),
    }
}
