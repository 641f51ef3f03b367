//! The engine: the passes of a frame, and the order and timing in which they run.
//!
//! ```text
//! animation      motion at t                     -> head and body colliders, posed character
//! simulation     guides advanced to t            -> guide particles (rigid links, Bertails §4)
//! interpolation  render strands from the guides  -> positions, tangents, lengths
//! hair map       one map per light               -> Tf, σ̄f², direct fraction per cell
//! occluders      the solids across each light    -> entry depths
//! skin texture   the hair's shadow on the solids -> optical depth per texel
//! raster (1)     the solids, then the hair's     -> colour and depth; which points are seen
//!                first pass
//! shading        the seen points, per light      -> vertex colours
//! raster (2)     the kept fragments composited   -> the image
//! output         the image converted and written -> frame files (`crate::output::FrameWriter`)
//! ```
//!
//! Each pass is a type that owns its config (where it has options), its buffers (so after the
//! first frame nothing allocates) and the estimate of its memory (`estimate`); the engine
//! holds them and decides their order and their timing, nothing else. The camera follows the
//! head before each render. Passes that build from the strands keep what they built when
//! their inputs did not change (`reuse`), to the same bits. A [`Quality`] level is a set of
//! the pass configs' values that trade time for error.
//!
//! The solids come first so that hair hidden behind them or behind nearer hair at every pixel
//! is neither shaded nor drawn: the frame of shading every point, byte for byte. The raster's
//! time counts the solids and the composite, the shading's the hair's first pass and the
//! shading.

mod animation;
mod camera;
mod config;
mod estimate;
mod hair_map;
mod interpolation;
mod map_rate;
mod occluders;
mod paths_rate;
mod quality;
mod raster;
mod reuse;
mod setup;
mod shading;
mod simulation;
mod sizes;
mod skin_texture;
mod timings;

pub use animation::AnimationPass;
pub use camera::{CameraPass, FramingInput};
pub use config::EngineConfig;
pub use estimate::{estimate, fit_map_resolution};
pub use hair_map::{
    ContactShadowing, DEFAULT_CONTACT_WINDOW_M, HairMapConfig, HairMapInput, HairMapPass,
    map_geometry,
};
pub use interpolation::{GuideHair, InterpolationConfig, InterpolationPass};
pub use occluders::{OccluderConfig, OccluderPass, SolidsInput};
pub use quality::Quality;
pub use raster::{
    DEFAULT_MIN_LINE_WIDTH_PX, DrawLines, HairToDraw, RasterConfig, RasterPass, SolidsToDraw,
};
pub use setup::{
    carry_roots_by_bones, fit_style_to_character, roots_of_guides_on_head, roots_on_head,
    write_colliders,
};
pub use shading::{PathsInput, ShadingConfig, ShadingInput, ShadingPass};
pub use simulation::{GROOM_SETTLE_STEP_S, SimulationConfig, SimulationPass};
pub use sizes::{RunSizes, SizedBy};
pub use skin_texture::{SkinTextureConfig, SkinTexturePass};
pub use timings::{MapPartTimings, StageTimings};

use crate::fiber::{Fiber, ShadingMode};
use crate::hairstyle::{GuideSet, Hairstyle, StrandLayout, generate, thin_strands};
use crate::interp::StrandGeometry;
use crate::map::{BuiltEarlier, LightMap, MapGeometry, MapStats, Shadows};
use crate::motion::{CharacterPose, Motion, Pose};
use crate::raster::{Camera, Framebuffer, draw_polylines, draw_seen_polylines};
use crate::scene::{CameraSetup, Scene};
use crate::shade::shade_skin;
use crate::sim::SimState;
use glam::{Affine3A, Vec3};
use map_rate::MapSchedule;
use paths_rate::{PathsKey, PathsSchedule, slot_of};
use std::time::Instant;

/// The hairstyle, its hair, the scene and the passes of a frame.
pub struct Engine {
    /// The hairstyle (head, fibre, dynamics, sizes); fitted to the character's head.
    pub style: Hairstyle,
    /// The fibre's scattering model and tables.
    pub fiber: Fiber,
    /// The guide strands at rest and the render strands' layout among them.
    pub guides: GuideSet,
    pub layout: StrandLayout,
    /// What is in the frame and how it is looked at.
    pub scene: Scene,
    /// The quality level the engine's pass configs were set from (`EngineConfig::level`).
    pub level: Quality,
    pub animation: AnimationPass,
    pub simulation: SimulationPass,
    pub interpolation: InterpolationPass,
    pub camera: CameraPass,
    pub hair_map: HairMapPass,
    pub occluders: OccluderPass,
    pub skin_texture: SkinTexturePass,
    pub shading: ShadingPass,
    pub raster: RasterPass,
    /// Timings of the last frame, and of the last map stage's parts (inside `timings.map_s`).
    pub timings: StageTimings,
    pub map_parts: MapPartTimings,
    /// When the hair maps were last built (`HairMapConfig::rebuild_interval_s`), the head's
    /// pose then, and whether the current frame's hair is lit by that earlier build.
    map_schedule: MapSchedule,
    head_at_build: Affine3A,
    lit_earlier: bool,
    /// When the light paths were last built (`ShadingConfig::paths_interval_s`), and the
    /// seconds the last build outside a render took, counted once in the next render's
    /// shading (a build for frames never rendered is not).
    paths_schedule: PathsSchedule,
    paths_built_s: f64,
}

impl Engine {
    /// Builds the hair, settles it on the first pose of the motion and frames the camera. A
    /// character with a head mesh gets the hairstyle's head fitted to it first
    /// ([`fit_style_to_character`]).
    pub fn new(style: Hairstyle, motion: Motion, config: EngineConfig) -> Self {
        let style = fit_style_to_character(&style, &motion);
        let (guides, layout) = generate(&style);
        Self::with_hair(style, guides, layout, motion, config)
    }

    /// [`Engine::new`] with hair made elsewhere (an imported groom, `crate::groom`): `style`
    /// gives the head, fibre, dynamics and sizes; `guides` and `layout` the hair. `style` is
    /// used as given: the groom was placed on its head, so fit that head to a character first
    /// ([`fit_style_to_character`]) and place the groom on the fitted head.
    pub fn with_hair(
        style: Hairstyle,
        guides: GuideSet,
        layout: StrandLayout,
        motion: Motion,
        config: EngineConfig,
    ) -> Self {
        let mut engine = Self::unsettled(style, guides, layout, motion, config);
        // Settle with the head held at the first pose (the simulation starts at −settle_s).
        engine.run_up_to(0.0);
        engine.place_camera();
        engine
    }

    /// Builds the hair without simulating: the guide particles are `settled_positions` at time
    /// 0 (what [`Engine::new`]'s settle left, read back from a simulation cache), and the
    /// camera is framed on them as `new` frames it. Later frames come from
    /// [`Engine::set_guide_state`]; rendered frames are then the bytes `new` + `frame` make.
    pub fn from_settled(
        style: Hairstyle,
        motion: Motion,
        config: EngineConfig,
        settled_positions: &[Vec3],
    ) -> Self {
        let style = fit_style_to_character(&style, &motion);
        let (guides, layout) = generate(&style);
        let mut engine = Self::unsettled(style, guides, layout, motion, config);
        engine.set_guide_state(0.0, settled_positions);
        engine.place_camera();
        engine
    }

    /// The engine with its guides at rest at −settle_s; the camera is not placed yet.
    fn unsettled(
        style: Hairstyle,
        guides: GuideSet,
        layout: StrandLayout,
        motion: Motion,
        config: EngineConfig,
    ) -> Self {
        let radii = head_radii_m(&style);
        let animation = AnimationPass::new(motion);
        let pose = animation.pose();
        let character = animation.motion().character();
        // The map's resolution and the simulation follow the hair as the groom has it; the
        // strands' level of detail changes only how many strands stand for it.
        let geom = map_geometry(&style, &config.hair_map);
        let simulation = SimulationPass::new(config.simulation, &style, &guides, pose, radii);
        let (style, layout) = thin_strands(style, layout, config.interpolation.strand_fraction);
        let mut scene = config.scene;
        // A point light too far for its map is the directional light it is (the command line
        // has said so already, with the same rule).
        crate::scene::far_light::far_point_lights_as_directional(
            &mut scene.lights,
            Vec3::from(pose.head.translation),
            style.reach_m(),
        );
        Self {
            fiber: Fiber::new(&style.fiber),
            simulation,
            interpolation: InterpolationPass::new(config.interpolation, pose, radii),
            camera: CameraPass::new(&scene),
            hair_map: HairMapPass::new(config.hair_map, geom, scene.lights.len()),
            occluders: OccluderPass::new(config.occluders, character),
            skin_texture: SkinTexturePass::new(config.skin_texture),
            shading: ShadingPass::new(config.shading),
            raster: RasterPass::new(config.raster, &scene, &style, character),
            animation,
            style,
            guides,
            layout,
            scene,
            level: config.level,
            timings: StageTimings::default(),
            map_parts: MapPartTimings::default(),
            map_schedule: MapSchedule::default(),
            head_at_build: Affine3A::IDENTITY,
            lit_earlier: false,
            paths_schedule: PathsSchedule::default(),
            paths_built_s: 0.0,
        }
    }

    /// Simulates from the current time up to `t_s` in slices of 0.2 s (the simulation caps its
    /// catch-up per call), so that a first frame late in the clip has the hair's history. The
    /// render strands are interpolated once, at `t_s` (they follow from the guides alone).
    pub fn run_up_to(&mut self, t_s: f64) {
        let mut t = self.simulation.state.time_s;
        while t < t_s {
            t = (t + 0.2).min(t_s);
            if t < t_s {
                self.animate_and_simulate(t);
            } else {
                self.advance(t);
            }
        }
    }

    /// Animation, simulation and interpolation up to time `t_s` (seconds of the motion).
    pub fn advance(&mut self, t_s: f64) {
        let t0 = Instant::now();
        self.animation.run(t_s);
        let t1 = Instant::now();
        self.simulate(t_s);
        self.interpolate([t0, t1, Instant::now()]);
    }

    /// Animation and simulation up to time `t_s`, without the render strands.
    fn animate_and_simulate(&mut self, t_s: f64) {
        self.animation.run(t_s);
        self.simulate(t_s);
    }

    /// The simulation up to `t_s` on the animation's motion and pose.
    fn simulate(&mut self, t_s: f64) {
        self.simulation.run(
            t_s,
            self.animation.motion(),
            self.animation.pose(),
            &self.guides,
            head_radii_m(&self.style),
        );
    }

    /// Animation and interpolation at time `t_s` with the guide particles set to `positions`
    /// instead of simulated (a frame of a simulation cache): the passes after the simulation
    /// see exactly what [`Engine::advance`] leaves when it simulated those positions. The
    /// caller checks that `positions` has one entry per guide particle
    /// (`simulation.state.positions.len()`). For rendering only: the simulation's velocities
    /// and step clock are not set, so an [`Engine::advance`] after this does not continue the
    /// cached motion.
    pub fn set_guide_state(&mut self, t_s: f64, positions: &[Vec3]) {
        let t0 = Instant::now();
        self.animation.run(t_s);
        let t1 = Instant::now();
        self.simulation.set_positions(positions);
        self.map_schedule.forget();
        self.interpolate([t0, t1, Instant::now()]);
    }

    /// The interpolation pass; `marks` are the instants the animation and simulation started
    /// and the simulation ended, for the timings.
    fn interpolate(&mut self, marks: [Instant; 3]) {
        let hair = GuideHair {
            guides: &self.guides,
            layout: &self.layout,
            curl: &self.style.curl,
            positions: &self.simulation.state.positions,
        };
        self.interpolation
            .run(hair, self.animation.pose(), head_radii_m(&self.style));
        let [t0, t1, t2] = marks;
        let t3 = Instant::now();
        self.timings.animation_s = (t1 - t0).as_secs_f64();
        self.timings.simulation_s = (t2 - t1).as_secs_f64();
        self.timings.interpolation_s = (t3 - t2).as_secs_f64();
        // A slot's light paths are built from its first frame's hair, rendered or not, so that
        // every run through these times builds from the same hair (`paths_rate`).
        if self.shading.config.paths_at_rate() {
            let built_s = self.build_paths_when_due();
            if built_s > 0.0 {
                self.paths_built_s = built_s;
            }
        }
    }

    /// One whole frame at time `t_s`.
    pub fn frame(&mut self, t_s: f64) -> &Framebuffer {
        self.advance(t_s);
        self.render()
    }

    /// The map, raster and shading passes on the current hair; returns the image. Only the
    /// points the raster finds drawable past the solids and nearer hair are shaded.
    pub fn render(&mut self) -> &Framebuffer {
        self.camera.follow(&self.scene, self.animation.pose());
        let t0 = Instant::now();
        self.build_map_when_due();
        let t1 = Instant::now();
        self.draw_solids();
        let t2 = Instant::now();
        let hair = HairToDraw {
            strands: self.interpolation.strands(),
            colors: self.shading.colors(),
        };
        self.raster.find_seen(self.camera.camera(), hair);
        self.shade_points(true);
        let t3 = Instant::now();
        self.draw_hair(draw_seen_polylines);
        let t4 = Instant::now();
        self.timings.map_s = (t1 - t0).as_secs_f64();
        self.timings.shading_s = (t3 - t2).as_secs_f64() + std::mem::take(&mut self.paths_built_s);
        self.timings.raster_s = ((t2 - t1) + (t4 - t3)).as_secs_f64();
        self.raster.framebuffer()
    }

    /// The map stage ([`Engine::build_map`]), its hair maps only when their rate asks for them
    /// at the current time (`map_rate`; otherwise the hair is lit by their last build and
    /// the hair map's part reads 0).
    fn build_map_when_due(&mut self) {
        let t_s = self.animation.time_s();
        let interval_s = self.hair_map.config.rebuild_interval_s;
        self.lit_earlier = !self.map_schedule.due(t_s, &self.scene.lights, interval_s);
        self.build_map_parts(!self.lit_earlier);
        if !self.lit_earlier {
            self.map_schedule.built(t_s, &self.scene.lights);
            self.head_at_build = self.animation.pose().head;
        }
    }

    /// World now → world at the hair maps' last build, when the frame is lit by it.
    fn head_back(&self) -> Option<Affine3A> {
        self.lit_earlier
            .then(|| self.head_at_build * self.animation.pose().head.inverse())
    }

    /// The hair map, occluder and skin texture passes on the current hair and pose, each
    /// timed; a pass whose inputs did not change keeps what it has.
    pub fn build_map(&mut self) {
        self.build_map_parts(true);
        self.lit_earlier = false;
    }

    /// [`Engine::build_map`], with the hair maps kept as they are unless `hair_maps`: the
    /// occluders and the skin texture are then built for the current pose and hair in the
    /// frames of the maps' last build.
    fn build_map_parts(&mut self, hair_maps: bool) {
        let started = Instant::now();
        let hair = HairMapInput {
            strands: self.interpolation.strands(),
            lights: &self.scene.lights,
            aim_m: Vec3::from(self.animation.pose().head.translation),
            fiber: &self.fiber,
            fibers_per_strand: self.style.strands.fibers_per_strand,
        };
        let maps_changed = hair_maps && self.hair_map.run(&hair);
        let t_occluders = Instant::now();
        let solids = SolidsInput {
            pose: self.animation.pose(),
            head_radii_m: head_radii_m(&self.style),
            character: self.animation.character(),
            draw_solids: self.scene.draw_solids,
        };
        let maps = self.hair_map.maps();
        let grids_changed = self.occluders.run(maps, maps_changed, &solids);
        let t_skin = Instant::now();
        self.skin_texture.run(
            (maps, self.occluders.grids()),
            &hair,
            0.5 * self.style.strand_spacing_m(),
            self.scene.draw_solids,
            maps_changed || grids_changed,
        );
        self.map_parts = MapPartTimings {
            hair_s: if hair_maps {
                (t_occluders - started).as_secs_f64()
            } else {
                0.0
            },
            occluders_s: (t_skin - t_occluders).as_secs_f64(),
            surface_s: t_skin.elapsed().as_secs_f64(),
        };
    }

    /// The shading pass alone: every point's colour from the current maps, seen from the
    /// current camera.
    pub fn shade(&mut self) {
        self.shade_points(false);
    }

    /// Shades every point, or with `only_seen` those the raster found drawable (the rest
    /// black).
    fn shade_points(&mut self, only_seen: bool) {
        self.build_paths_when_due();
        let input = ShadingInput {
            fiber: &self.fiber,
            fibers_per_strand: self.style.strands.fibers_per_strand,
            scene: &self.scene,
            strands: self.interpolation.strands(),
            eye: self.camera.camera().eye(),
            seen: only_seen.then_some(self.raster.seen()),
        };
        let shadows = lit_by(
            (&self.hair_map, &self.occluders, &self.skin_texture),
            self.head_back(),
        );
        let paths_back = self
            .paths_schedule
            .head_back(self.animation.time_s(), self.animation.pose().head);
        self.shading.run(shadows, &input, paths_back);
    }

    /// Builds the light paths from the current hair when the light-path shader is on and
    /// they are due (`paths_rate`); returns the seconds that took.
    fn build_paths_when_due(&mut self) -> f64 {
        if self.shading.config.mode != ShadingMode::Volume {
            return 0.0;
        }
        let t_s = self.animation.time_s();
        let params = self.shading.config.light_paths;
        let key = PathsKey {
            lights: &self.scene.lights,
            params: &params,
            fiber: self.fiber.params(),
        };
        if !self
            .paths_schedule
            .due(t_s, self.shading.config.paths_interval_s, &key)
        {
            return 0.0;
        }
        let started = Instant::now();
        let input = PathsInput {
            fiber: &self.fiber,
            fibers_per_strand: self.style.strands.fibers_per_strand,
            scene: &self.scene,
            strands: self.interpolation.strands(),
            colliders: self.interpolation.colliders(),
        };
        self.shading.build_light_paths(&input);
        self.paths_schedule
            .built(t_s, &key, self.animation.pose().head);
        started.elapsed().as_secs_f64()
    }

    /// With the light paths built once per slot of motion (`paths_rate`): the slot of the
    /// frame at `t_s`, and whether the paths for it are built. A run that starts inside a slot
    /// with hair set from outside (`set_guide_state`) sets its first frame's hair first, to
    /// build from it as a run from the start does. `None` when the paths are built for every
    /// frame or not used.
    pub fn light_paths_slot(&self, t_s: f64) -> Option<i64> {
        let config = &self.shading.config;
        config
            .paths_at_rate()
            .then(|| slot_of(t_s, config.paths_interval_s))
    }

    /// Whether the light paths last built are for `slot` (of [`Engine::light_paths_slot`]).
    pub fn light_paths_built_in(&self, slot: i64) -> bool {
        let interval_s = self.shading.config.paths_interval_s;
        self.shading.config.paths_at_rate()
            && self
                .paths_schedule
                .built_at_s()
                .is_some_and(|t_s| slot_of(t_s, interval_s) == slot)
    }

    /// The raster pass alone: clears the image, draws the solids (lit through the maps) and
    /// the hair with the current colours.
    pub fn draw(&mut self) -> &Framebuffer {
        self.draw_solids();
        self.draw_hair(draw_polylines);
        self.raster.framebuffer()
    }

    /// Clears the image and draws the solids, lit through each light's shadows, when the
    /// scene draws them.
    fn draw_solids(&mut self) {
        let shadows = lit_by(
            (&self.hair_map, &self.occluders, &self.skin_texture),
            self.head_back(),
        );
        let lighting = self.shading.lighting(&self.scene);
        let (solids, albedo) = self.occluders.solids();
        let to_draw = SolidsToDraw {
            solids,
            albedo,
            character: self.animation.character(),
        };
        self.raster.draw_solids(
            &self.scene,
            self.camera.camera(),
            to_draw,
            |p, n, albedo| shade_skin(shadows, &lighting, albedo, p, n),
        );
    }

    /// The hair over what is drawn, with the current colours, by `draw`.
    fn draw_hair(&mut self, draw: DrawLines) {
        let hair = HairToDraw {
            strands: self.interpolation.strands(),
            colors: self.shading.colors(),
        };
        self.raster.draw_hair(self.camera.camera(), hair, draw);
    }

    /// The solids alone on black, shaded by `skin(p, n, albedo)` (world point, unit normal,
    /// albedo → linear RGB) instead of the map-lit skin shader: for measuring the skin's
    /// shadow against another light (`accuracy::skin`). The next render clears it.
    pub fn solids_image(&mut self, skin: impl Fn(Vec3, Vec3, Vec3) -> Vec3 + Sync) -> &Framebuffer {
        let (solids, albedo) = self.occluders.solids();
        let to_draw = SolidsToDraw {
            solids,
            albedo,
            character: self.animation.character(),
        };
        self.raster
            .solids_image(self.camera.camera(), to_draw, skin)
    }

    /// Makes the next [`Engine::build_map`] rebuild the maps even if nothing they are made of
    /// changed (a benchmark of the map stage on still hair).
    pub fn invalidate_maps(&mut self) {
        self.hair_map.invalidate();
        self.map_schedule.forget();
    }

    /// Whether the last [`Engine::build_map`] kept the maps it had.
    pub fn map_reused(&self) -> bool {
        self.hair_map.reused()
    }

    /// Places the camera once the hair has settled.
    fn place_camera(&mut self) {
        let input = FramingInput {
            strand_positions: &self.interpolation.strands().positions,
            pose: self.animation.pose(),
            motion: self.animation.motion(),
            max_length_m: self.style.max_length_m(),
        };
        self.camera.place(&self.scene, input);
    }

    /// Sets where the camera is and places it at once: a fixed camera as given, a
    /// head-following one framed anew on the current hair and pose (the window's mouse
    /// camera).
    pub fn set_camera(&mut self, setup: CameraSetup) {
        self.scene.camera = setup;
        self.place_camera();
    }

    /// The motion the head and body follow.
    pub fn motion(&self) -> &Motion {
        self.animation.motion()
    }
    /// The head and body colliders at the current time.
    pub fn pose(&self) -> &Pose {
        self.animation.pose()
    }
    /// The character's mesh at the current time (pose world; empty without a character).
    pub fn character_pose(&self) -> &CharacterPose {
        self.animation.character_pose()
    }
    /// The guide particles and the simulation's clock.
    pub fn state(&self) -> &SimState {
        &self.simulation.state
    }
    /// The render strands of the current time.
    pub fn strands(&self) -> &StrandGeometry {
        self.interpolation.strands()
    }
    pub fn camera(&self) -> &Camera {
        self.camera.camera()
    }
    pub fn framebuffer(&self) -> &Framebuffer {
        self.raster.framebuffer()
    }
    /// Map geometry in use.
    pub fn map_geometry(&self) -> MapGeometry {
        self.hair_map.maps()[0].geometry()
    }
    /// Figures of the last map build.
    pub fn map_stats(&self) -> &MapStats {
        self.hair_map.maps()[0].stats()
    }
    /// The first light's map (the key light's).
    pub fn map(&self) -> &LightMap {
        &self.hair_map.maps()[0]
    }
    /// Every light's map, in the order of `scene.lights`.
    pub fn maps(&self) -> &[LightMap] {
        self.hair_map.maps()
    }
    /// Every light's shadows (hair map, solids, skin texture), in the order of `scene.lights`,
    /// as the last frame was lit by them: hair maps built for it, or for an earlier frame and
    /// read where the hair and the head were then (`map::BuiltEarlier`).
    pub fn shadows(&self) -> Shadows<'_> {
        lit_by(
            (&self.hair_map, &self.occluders, &self.skin_texture),
            self.head_back(),
        )
    }
    /// Colours of the last shading (linear RGB), indexed like `strands().positions`. After
    /// [`Engine::render`] the points the raster could not draw are black, as they were not
    /// shaded; after [`Engine::shade`] every point is shaded.
    pub fn colors(&self) -> &[Vec3] {
        self.shading.colors()
    }
    /// Physical width of each render-strand point in metres (after a render): the width a
    /// render strand of F fibres of radius r covers at most, F·2r.
    pub fn widths_m(&self) -> &[f32] {
        self.raster.widths_m()
    }
}

/// The shadows of the map stage's passes; `head_back` (world now → world at their build) when
/// they were built for an earlier frame.
fn lit_by<'a>(
    (hair_map, occluders, skin): (&'a HairMapPass, &'a OccluderPass, &'a SkinTexturePass),
    head_back: Option<Affine3A>,
) -> Shadows<'a> {
    Shadows {
        maps: hair_map.maps(),
        solids: occluders.grids(),
        skin: skin.textures(),
        earlier: head_back.map(|head_back| BuiltEarlier {
            positions: hair_map.built_positions(),
            head_back,
        }),
    }
}

/// The head ellipsoid's semi-axes, metres.
fn head_radii_m(style: &Hairstyle) -> Vec3 {
    Vec3::from(style.head.radii_m)
}
