//! One frame of the pipeline, stage by stage, with per-stage timings.
//!
//! ```text
//! animation   motion.sample(t)                -> head and body-sphere transforms
//! simulation  sim.advance(t, colliders)       -> guide particles (self-collision from the
//!                                                simulator's own density grid, Bertails §4.1)
//! interp      interpolate(guides)             -> render strands (positions, tangents)
//! map         map.build(strands, light)       -> Tf, σ̄f², direct fraction per cell
//! shading     shade_vertices(map, fiber)      -> vertex colours
//! raster      head, body spheres, hair lines  -> framebuffer
//! ```
//!
//! [`Engine`] owns every buffer, so after the first frame no stage allocates. Each stage is a
//! plain function of explicit inputs (see the modules); the engine only sequences them and
//! times them.

use crate::fiber::Fiber;
use crate::hairstyle::{GuideSet, Hairstyle, StrandLayout, generate};
use crate::interp::{StrandGeometry, interpolate};
use crate::map::{CountModel, LightMap, MapGeometry, MapStats};
use crate::motion::{Motion, Pose};
use crate::raster::{
    Camera, Framebuffer, LineScratch, LineStyle, Polylines, draw_ellipsoid, draw_polylines,
};
use crate::shade::{Lighting, shade_skin, shade_vertices};
use crate::sim::{Colliders, SimState, Simulator, SphereCollider, StepStats};
use glam::{Affine3A, Vec3};
use std::time::Instant;

/// Seconds spent in each stage of one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageTimings {
    pub animation_s: f64,
    pub simulation_s: f64,
    pub interpolation_s: f64,
    pub map_s: f64,
    pub shading_s: f64,
    pub raster_s: f64,
}

impl StageTimings {
    pub const NAMES: [&'static str; 6] = [
        "animation",
        "simulation",
        "interpolation",
        "map",
        "shading",
        "raster",
    ];

    pub fn as_array(&self) -> [f64; 6] {
        [
            self.animation_s,
            self.simulation_s,
            self.interpolation_s,
            self.map_s,
            self.shading_s,
            self.raster_s,
        ]
    }
    pub fn total_s(&self) -> f64 {
        self.as_array().iter().sum()
    }
    pub fn add(&mut self, o: &StageTimings) {
        self.animation_s += o.animation_s;
        self.simulation_s += o.simulation_s;
        self.interpolation_s += o.interpolation_s;
        self.map_s += o.map_s;
        self.shading_s += o.shading_s;
        self.raster_s += o.raster_s;
    }
    pub fn scaled(&self, k: f64) -> StageTimings {
        let a = self.as_array().map(|v| v * k);
        StageTimings {
            animation_s: a[0],
            simulation_s: a[1],
            interpolation_s: a[2],
            map_s: a[3],
            shading_s: a[4],
            raster_s: a[5],
        }
    }
}

/// Everything about a run that is not the hairstyle or the motion.
#[derive(Clone, Debug)]
pub struct EngineConfig {
    /// Image size in pixels.
    pub width: u32,
    pub height: u32,
    /// Light and shader.
    pub lighting: Lighting,
    /// Map cells per axis; `None` sizes the map from the scene (`MapGeometry::for_scene`).
    pub map_res: Option<u32>,
    /// Density-based self-collision (Bertails §4.1).
    pub self_collision: bool,
    /// Simulate the guides; `false` keeps them in their rest pose riding on the head.
    pub simulate: bool,
    /// Seconds of simulated time with the head held at the first pose before frame 0, so the
    /// hair starts settled.
    pub settle_s: f64,
    /// Hair line width in pixels and coverage multiplier.
    pub line: LineStyle,
    /// Background colour (linear RGB).
    pub background: Vec3,
}

impl Default for EngineConfig {
    fn default() -> Self {
        Self {
            width: 800,
            height: 800,
            lighting: Lighting::default(),
            map_res: None,
            self_collision: true,
            simulate: true,
            settle_s: 2.0,
            line: LineStyle {
                width_px: 1.0,
                opacity: 0.85,
            },
            background: Vec3::new(0.012, 0.014, 0.018),
        }
    }
}

/// Skin albedo of the head and the body spheres.
const SKIN: Vec3 = Vec3::new(0.55, 0.38, 0.30);
const CLOTH: Vec3 = Vec3::new(0.10, 0.14, 0.22);

/// The whole engine: hairstyle, motion, simulation state, map and image buffers.
pub struct Engine {
    pub style: Hairstyle,
    pub fiber: Fiber,
    pub guides: GuideSet,
    pub layout: StrandLayout,
    pub motion: Motion,
    pub config: EngineConfig,
    pose: Pose,
    /// Scratch pose for the simulation's sub-step collider queries (reused, no allocation).
    sim_pose: Pose,
    sim: Simulator,
    pub state: SimState,
    map: LightMap,
    pub strands: StrandGeometry,
    colors: Vec<Vec3>,
    camera: Camera,
    /// Camera target relative to the head centre (world), fixed at start.
    camera_offset: Vec3,
    /// Camera eye relative to the target.
    camera_eye_offset: Vec3,
    fb: Framebuffer,
    scratch: LineScratch,
    /// Timings of the last frame.
    pub timings: StageTimings,
    /// Figures of the last simulation advance.
    pub step_stats: StepStats,
}

impl Engine {
    /// Builds the hair, settles it on the first pose of the motion and frames the camera.
    pub fn new(style: Hairstyle, motion: Motion, config: EngineConfig) -> Self {
        let fiber = Fiber::new(&style.fiber);
        let (guides, layout) = generate(&style);
        let radii = Vec3::from(style.head.radii_m);
        let pose = motion.sample(0.0);
        let mut sim = Simulator::from_hairstyle(&style, &guides);
        sim.set_self_collision(config.self_collision);
        let state = SimState::at_rest(&guides, &colliders_of(&pose, radii), -config.settle_s);
        let geom = match config.map_res {
            Some(n) => MapGeometry::with_resolution(
                MapGeometry::span_m(style.max_length_m(), style.head_size_m()),
                n,
            ),
            None => MapGeometry::for_scene(
                style.max_length_m(),
                style.head_size_m(),
                style.strand_spacing_m(),
            ),
        };
        let camera = initial_camera(&config);
        let fb = Framebuffer::new(config.width, config.height, config.background);
        let mut engine = Self {
            style,
            fiber,
            guides,
            layout,
            motion,
            sim_pose: pose.clone(),
            pose,
            sim,
            state,
            map: LightMap::new(geom, CountModel::Poisson),
            strands: StrandGeometry::default(),
            colors: Vec::new(),
            camera,
            camera_offset: Vec3::ZERO,
            camera_eye_offset: Vec3::Z,
            fb,
            scratch: LineScratch::default(),
            timings: StageTimings::default(),
            step_stats: StepStats::default(),
            config,
        };
        // Settle with the head held at the first pose (the simulation starts at −settle_s).
        engine.run_up_to(0.0);
        engine.frame_camera();
        engine
    }

    /// Map geometry in use.
    pub fn map_geometry(&self) -> MapGeometry {
        self.map.geometry()
    }
    /// Figures of the last map build.
    pub fn map_stats(&self) -> &MapStats {
        self.map.stats()
    }
    pub fn map(&self) -> &LightMap {
        &self.map
    }
    pub fn camera(&self) -> &Camera {
        &self.camera
    }
    pub fn framebuffer(&self) -> &Framebuffer {
        &self.fb
    }
    pub fn pose(&self) -> &Pose {
        &self.pose
    }
    /// Vertex colours of the last render (linear RGB), indexed like `strands.positions`.
    pub fn colors(&self) -> &[Vec3] {
        &self.colors
    }

    /// Simulates from the current time up to `t_s` in slices of 0.2 s (the simulation caps its
    /// catch-up per call), so that a first frame late in the clip has the hair's history.
    pub fn run_up_to(&mut self, t_s: f64) {
        let mut t = self.state.time_s;
        while t < t_s {
            t = (t + 0.2).min(t_s);
            self.advance(t);
        }
    }

    /// Animation, simulation and interpolation up to time `t_s` (seconds of the motion).
    pub fn advance(&mut self, t_s: f64) {
        let t0 = Instant::now();
        self.motion.sample_into(t_s as f32, &mut self.pose);
        let radii = Vec3::from(self.style.head.radii_m);
        let t1 = Instant::now();
        if self.config.simulate {
            let motion = &self.motion;
            let scratch_pose = &mut self.sim_pose;
            let colliders_at = |t: f64, c: &mut Colliders| {
                motion.sample_into(t.max(0.0) as f32, scratch_pose);
                write_colliders(scratch_pose, radii, c);
            };
            self.sim.set_self_collision(self.config.self_collision);
            self.step_stats = self.sim.advance(&mut self.state, t_s, colliders_at);
        } else {
            let head = self.pose.head;
            for (p, r) in self.state.positions.iter_mut().zip(&self.guides.rest) {
                *p = head.transform_point3(*r);
            }
            self.state.time_s = t_s;
        }
        let t2 = Instant::now();
        interpolate(
            &self.guides,
            &self.layout,
            &self.style.curl,
            &self.state.positions,
            &mut self.strands,
        );
        let t3 = Instant::now();
        self.timings.animation_s = (t1 - t0).as_secs_f64();
        self.timings.simulation_s = (t2 - t1).as_secs_f64();
        self.timings.interpolation_s = (t3 - t2).as_secs_f64();
    }

    /// Map, shading and raster of the current hair; returns the image.
    pub fn render(&mut self) -> &Framebuffer {
        self.follow_head();
        let t0 = Instant::now();
        self.build_map();
        let t1 = Instant::now();
        let eye = self.camera.eye();
        shade_vertices(
            &self.fiber,
            &self.map,
            &self.config.lighting,
            eye,
            &self.strands.positions,
            &self.strands.tangents,
            &mut self.colors,
        );
        let t2 = Instant::now();
        self.fb.clear(self.config.background);
        let (map, lighting) = (&self.map, &self.config.lighting);
        let head = self.pose.head * Affine3A::from_scale(Vec3::from(self.style.head.radii_m));
        draw_ellipsoid(&mut self.fb, &self.camera, head, |p, n| {
            shade_skin(map, lighting, SKIN, p, n)
        });
        for s in &self.pose.spheres {
            let m = Affine3A::from_scale_rotation_translation(
                Vec3::splat(s.radius_m),
                glam::Quat::IDENTITY,
                s.center,
            );
            draw_ellipsoid(&mut self.fb, &self.camera, m, |p, n| {
                shade_skin(map, lighting, CLOTH, p, n)
            });
        }
        let lines = Polylines {
            points: &self.strands.positions,
            colors: &self.colors,
            points_per_line: self.strands.points_per_strand,
        };
        draw_polylines(
            &mut self.fb,
            &self.camera,
            &lines,
            &self.config.line,
            &mut self.scratch,
        );
        let t3 = Instant::now();
        self.timings.map_s = (t1 - t0).as_secs_f64();
        self.timings.shading_s = (t2 - t1).as_secs_f64();
        self.timings.raster_s = (t3 - t2).as_secs_f64();
        &self.fb
    }

    /// One whole frame at time `t_s`.
    pub fn frame(&mut self, t_s: f64) -> &Framebuffer {
        self.advance(t_s);
        self.render()
    }

    /// Rebuilds the light-oriented map from the current render strands.
    pub fn build_map(&mut self) {
        self.map.build(&crate::map::MapBuildInput {
            positions: &self.strands.positions,
            tangents: &self.strands.tangents,
            lengths_m: &self.strands.lengths_m,
            fibers_per_strand: self.style.strands.fibers_per_strand,
            light_dir: self.config.lighting.light_dir,
            fiber: &self.fiber,
        });
    }

    /// Frames the settled hair from three-quarters front of the first pose. The camera then
    /// follows the head's translation (not its rotation), so the head stays in frame through
    /// the dance while its turns and the hair's swing stay visible.
    fn frame_camera(&mut self) {
        let (lo, hi) = self.strands.positions.iter().fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(lo, hi), p| {
                if p.is_finite() {
                    (lo.min(*p), hi.max(*p))
                } else {
                    (lo, hi)
                }
            },
        );
        let head0: Vec3 = self.pose.head.translation.into();
        let (lo, hi) = if lo.x <= hi.x {
            (lo.min(head0), hi.max(head0))
        } else {
            (head0, head0)
        };
        let centre = 0.5 * (lo + hi);
        // Half the largest extent (a tall, thin head of hair fills the frame's height), plus room
        // for the hair to swing by about a tenth of its length.
        let radius = 0.55 * (hi - lo).max_element() + 0.1 * self.style.max_length_m();
        let view = self
            .pose
            .head
            .transform_vector3(Vec3::new(0.55, 0.12, 1.0))
            .normalize_or(Vec3::Z);
        let cam = Camera::framing(
            centre,
            radius.max(0.05),
            view,
            30f32.to_radians(),
            self.config.width,
            self.config.height,
        );
        self.camera_offset = centre - head0;
        self.camera_eye_offset = cam.eye() - centre;
        self.camera = cam;
    }

    /// Moves the camera with the head's translation.
    fn follow_head(&mut self) {
        let target = Vec3::from(self.pose.head.translation) + self.camera_offset;
        self.camera = Camera::look_at(
            target + self.camera_eye_offset,
            target,
            Vec3::Y,
            30f32.to_radians(),
            self.config.width,
            self.config.height,
        );
    }
}

/// The camera until `frame_camera` can frame the settled hair.
fn initial_camera(config: &EngineConfig) -> Camera {
    Camera::framing(
        Vec3::ZERO,
        0.5,
        Vec3::Z,
        30f32.to_radians(),
        config.width,
        config.height,
    )
}

fn colliders_of(pose: &Pose, radii: Vec3) -> Colliders {
    let mut c = Colliders {
        head: pose.head,
        head_radii_m: radii,
        spheres: Vec::new(),
    };
    write_colliders(pose, radii, &mut c);
    c
}

fn write_colliders(pose: &Pose, radii: Vec3, c: &mut Colliders) {
    c.head = pose.head;
    c.head_radii_m = radii;
    c.spheres.clear();
    c.spheres
        .extend(pose.spheres.iter().map(|s| SphereCollider {
            center: s.center,
            radius_m: s.radius_m,
        }));
}
