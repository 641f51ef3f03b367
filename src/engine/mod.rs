//! One frame of the pipeline, stage by stage, with per-stage timings.
//!
//! ```text
//! animation   motion.sample(t)                -> head and body-collider transforms, and the
//!                                                character's skinned mesh
//! simulation  sim.advance(t, colliders)       -> guide particles (self-collision from the
//!                                                simulator's own density grid, Bertails §4.1)
//! interp      interpolate(guides, colliders)  -> render strands (positions, tangents), kept
//!                                                out of the head and body
//! map         map.build(strands, light)       -> Tf, σ̄f², direct fraction per cell, one map
//!                                                per light, built side by side
//! raster (1)  character mesh (or the head and  -> framebuffer: colour and opaque depth
//!             body spheres)
//! shading     seen_points(depth, strands),     -> kept hair fragments; vertex colours, over
//!             shade_vertices(maps, fiber)         the lights, of the points they reach
//! raster (2)  draw_seen_polylines(colours)     -> framebuffer: the kept fragments composited
//! ```
//!
//! The solids come first so that hair hidden behind them or nearer hair at every pixel
//! (`raster::seen_points`: four fifths of the dance's points at 1280 × 720) is neither shaded
//! nor drawn, the same frame to the byte (timed: the solids as raster, the first pass as shading).
//!
//! [`Engine`] owns every buffer, so after the first frame no stage allocates. Each stage is a
//! plain function of explicit inputs (see the modules); the engine only sequences them and
//! times them.

mod config;
mod hair_lines;
mod light_paths_pass;
mod map_reuse;
mod setup;

pub use config::{
    ContactShadowing, DEFAULT_CONTACT_WINDOW_M, DEFAULT_MIN_LINE_WIDTH_PX, EngineConfig,
    MapPartTimings, StageTimings,
};
use setup::{colliders_of, solids_of};
pub use setup::{
    fit_style_to_character, map_geometry, roots_of_guides_on_head, roots_on_head, write_colliders,
};

use crate::fiber::Fiber;
use crate::hairstyle::{GuideSet, Hairstyle, StrandLayout, generate};
use crate::interp::{StrandGeometry, interpolate_among};
use crate::map::surface::SurfaceShadow;
use crate::map::{
    CountModel, LightMap, MapGeometry, MapStats, OccluderGrid, OccluderMesh, Shadows, Solid,
};
use crate::motion::{CharacterPose, Motion, Pose};
use crate::raster::{
    Camera, Framebuffer, LineScratch, Mesh, MeshScratch, Surface, Texture, draw_ellipsoid,
    draw_mesh, draw_polylines, draw_seen_polylines, seen_points,
};
use crate::scene::{CameraSetup, HEAD_FOLLOWING_FOV_Y_RAD, HeadFollowing};
use crate::shade::{Lighting, ShadeScratch, VertexGeometry, shade_skin, shade_vertices};
use crate::sim::{Colliders, SimState, Simulator, StepStats};
use glam::Vec3;
use hair_lines::{DrawLines, hair_lines, strand_widths_m};
use map_reuse::{MapInputs, MapInputsView};
use rayon::prelude::*;
use std::time::Instant;

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
    /// The colliders of `pose`, which render strands are kept out of (reused).
    frame_colliders: Colliders,
    sim: Simulator,
    pub state: SimState,
    /// One light-oriented map per light of `config.lighting`, in its order.
    maps: Vec<LightMap>,
    /// Per light, the solids' entry depths in its map's frame.
    occluders: Vec<OccluderGrid>,
    /// Per light, the hair's shadow texture on skin (when solids are drawn).
    skin_textures: Vec<Option<SurfaceShadow>>,
    /// What the maps were last built from, and whether the last build kept them.
    map_inputs: MapInputs,
    map_reused: bool,
    pub strands: StrandGeometry,
    colors: Vec<Vec3>,
    /// Per render-strand point: whether the raster could draw its colour this frame
    /// ([`seen_points`], after the solids); [`Engine::render`] shades only those.
    seen: Vec<bool>,
    shade_scratch: ShadeScratch,
    /// Physical width of each render-strand point in metres (fibres per strand × diameter).
    widths_m: Vec<f32>,
    /// A render strand's fibres in its bundle's unit disc (as the exact reference places
    /// them), for the raster to draw them where they lie; empty for one fibre per strand.
    bundle_points: Vec<glam::Vec2>,
    camera: Camera,
    /// The head-following framing, when the camera is not fixed.
    follow: Option<HeadFollowing>,
    fb: Framebuffer,
    scratch: LineScratch,
    /// The head and body solids of the current pose (reused buffer), and their albedos.
    solids: Vec<Solid>,
    solid_albedo: Vec<Vec3>,
    /// The character's mesh posed at the current time (empty without a character).
    character: CharacterPose,
    /// How the character's triangles look (from its materials) and its textures.
    surfaces: Vec<Surface>,
    textures: Vec<Texture>,
    /// The character's mesh includes its head (else the head ellipsoid is drawn too).
    character_has_head: bool,
    mesh_scratch: MeshScratch,
    /// Timings of the last frame.
    pub timings: StageTimings,
    /// The last map stage's parts (inside `timings.map_s`).
    pub map_parts: MapPartTimings,
    /// Figures of the last simulation advance.
    pub step_stats: StepStats,
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
        let fiber = Fiber::new(&style.fiber);
        let radii = Vec3::from(style.head.radii_m);
        let pose = motion.sample(0.0);
        let mut sim = Simulator::from_hairstyle(&style, &guides);
        sim.set_self_collision(config.self_collision);
        let (surfaces, textures, character_has_head) = match motion.character() {
            Some(ch) => (
                ch.materials
                    .iter()
                    .map(|m| Surface {
                        albedo: m.base_color,
                        texture: m.texture.map(|t| t as u32),
                        double_sided: m.double_sided,
                    })
                    .collect(),
                ch.textures
                    .iter()
                    .map(|t| Texture {
                        width: t.width,
                        height: t.height,
                        texels: t.texels.clone(),
                    })
                    .collect(),
                ch.has_head(),
            ),
            None => (Vec::new(), Vec::new(), false),
        };
        let state = SimState::at_rest(&guides, &colliders_of(&pose, radii), -config.settle_s);
        let geom = map_geometry(&style, &config);
        // Replaced once the settled hair is framed (`place_camera`), before any render.
        let camera = Camera::look_at(
            Vec3::Z,
            Vec3::ZERO,
            Vec3::Y,
            HEAD_FOLLOWING_FOV_Y_RAD,
            config.width,
            config.height,
        );
        let fb = Framebuffer::new(config.width, config.height, config.background);
        let fibers = style.strands.fibers_per_strand.round();
        let bundle_points = if fibers >= 2.0 {
            crate::disc::bundle_disc_points(fibers.min(256.0) as u32)
        } else {
            Vec::new()
        };
        Self {
            style,
            fiber,
            guides,
            layout,
            motion,
            sim_pose: pose.clone(),
            frame_colliders: colliders_of(&pose, radii),
            pose,
            sim,
            state,
            maps: vec![
                LightMap::new(geom, CountModel::Poisson);
                config.lighting.lights.len().max(1)
            ],
            occluders: Vec::new(),
            skin_textures: Vec::new(),
            map_inputs: MapInputs::default(),
            map_reused: false,
            strands: StrandGeometry::default(),
            colors: Vec::new(),
            seen: Vec::new(),
            shade_scratch: ShadeScratch::default(),
            widths_m: Vec::new(),
            bundle_points,
            camera,
            follow: None,
            fb,
            scratch: LineScratch::default(),
            solids: Vec::new(),
            solid_albedo: Vec::new(),
            character: CharacterPose::default(),
            surfaces,
            textures,
            character_has_head,
            mesh_scratch: MeshScratch::default(),
            timings: StageTimings::default(),
            map_parts: MapPartTimings::default(),
            step_stats: StepStats::default(),
            config,
        }
    }

    /// Map geometry in use.
    pub fn map_geometry(&self) -> MapGeometry {
        self.maps[0].geometry()
    }
    /// Figures of the last map build.
    pub fn map_stats(&self) -> &MapStats {
        self.maps[0].stats()
    }
    /// The first light's map (the key light's).
    pub fn map(&self) -> &LightMap {
        &self.maps[0]
    }
    /// Every light's map, in the order of `config.lighting.lights`.
    pub fn maps(&self) -> &[LightMap] {
        &self.maps
    }
    /// Every light's shadows (hair map, solids, skin texture), in the order of
    /// `config.lighting.lights`.
    pub fn shadows(&self) -> Shadows<'_> {
        Shadows {
            maps: &self.maps,
            solids: &self.occluders,
            skin: &self.skin_textures,
        }
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
    /// The character's mesh at the current time (pose world; empty without a character).
    pub fn character_pose(&self) -> &CharacterPose {
        &self.character
    }
    /// Vertex colours of the last render (linear RGB), indexed like `strands.positions`. After
    /// [`Engine::render`] (or [`Engine::frame`]) the points the raster could not draw (behind
    /// the solids or nearer hair at every pixel their segments touch, or off screen) are
    /// black, as they were not shaded; after [`Engine::shade`] every point is shaded.
    pub fn colors(&self) -> &[Vec3] {
        &self.colors
    }
    /// Physical width of each render-strand point in metres, indexed like
    /// `strands.positions`: the width a render strand of F fibres of radius r covers at most,
    /// F·2r (its fibres side by side). Filled by [`Engine::render`].
    pub fn widths_m(&self) -> &[f32] {
        &self.widths_m
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
        self.motion.pose_character(t_s as f32, &mut self.character);
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
        self.interpolate_strands([t0, t1, Instant::now()]);
    }

    /// Animation and interpolation at time `t_s` with the guide particles set to `positions`
    /// instead of simulated (a frame of a simulation cache): the stages after the simulation
    /// see exactly what [`Engine::advance`] leaves when it simulated those positions. The
    /// caller checks that `positions` has one entry per guide particle
    /// (`state.positions.len()`); extra entries are ignored, missing ones keep their value.
    /// For rendering only: the simulation's velocities and step clock are not set, so an
    /// [`Engine::advance`] after this does not continue the cached motion.
    pub fn set_guide_state(&mut self, t_s: f64, positions: &[Vec3]) {
        let t0 = Instant::now();
        self.motion.sample_into(t_s as f32, &mut self.pose);
        self.motion.pose_character(t_s as f32, &mut self.character);
        let t1 = Instant::now();
        for (p, q) in self.state.positions.iter_mut().zip(positions) {
            *p = *q;
        }
        self.interpolate_strands([t0, t1, Instant::now()]);
    }

    /// Interpolation of the render strands from the guides; `marks` are the instants the
    /// animation and simulation stages started and the simulation ended, for the timings.
    fn interpolate_strands(&mut self, marks: [Instant; 3]) {
        let radii = Vec3::from(self.style.head.radii_m);
        write_colliders(&self.pose, radii, &mut self.frame_colliders);
        interpolate_among(
            &self.guides,
            &self.layout,
            &self.style.curl,
            &self.state.positions,
            Some(&self.frame_colliders),
            self.config.segment_pieces as usize,
            &mut self.strands,
        );
        let [t0, t1, t2] = marks;
        let t3 = Instant::now();
        self.timings.animation_s = (t1 - t0).as_secs_f64();
        self.timings.simulation_s = (t2 - t1).as_secs_f64();
        self.timings.interpolation_s = (t3 - t2).as_secs_f64();
    }

    /// Map, shading and raster of the current hair; returns the image. The solids come first,
    /// so the hair's first pass ([`seen_points`]) keeps only what they and nearer hair leave to
    /// see, and only its points are shaded: the frame of shading every point, byte for byte.
    /// The raster's time counts the solids and the composite, the shading's the first pass.
    pub fn render(&mut self) -> &Framebuffer {
        self.follow_head();
        let t0 = Instant::now();
        self.build_map();
        let t1 = Instant::now();
        self.draw_solids_layer();
        let t2 = Instant::now();
        self.update_widths();
        let lines = hair_lines(
            &self.strands,
            &self.colors,
            &self.widths_m,
            &self.bundle_points,
            &self.style,
        );
        seen_points(
            &self.fb,
            &self.camera,
            &lines,
            &self.config.line,
            &mut self.scratch,
            &mut self.seen,
        );
        self.shade_where(true);
        let t3 = Instant::now();
        self.draw_hair(draw_seen_polylines);
        let t4 = Instant::now();
        self.timings.map_s = (t1 - t0).as_secs_f64();
        self.timings.shading_s = (t3 - t2).as_secs_f64();
        self.timings.raster_s = ((t2 - t1) + (t4 - t3)).as_secs_f64();
        &self.fb
    }

    /// The shading stage alone: every vertex's colour from the current maps (after
    /// [`Engine::build_map`]), seen from the current camera.
    pub fn shade(&mut self) {
        self.shade_where(false);
    }

    /// Shades every vertex (+ the light paths' light, `volume_pass.rs`), or with `only_seen`
    /// those [`Engine::render`] found the raster could draw (the rest black).
    fn shade_where(&mut self, only_seen: bool) {
        let eye = self.camera.eye();
        let shadows = Shadows {
            maps: &self.maps,
            solids: &self.occluders,
            skin: &self.skin_textures,
        };
        shade_vertices(
            &self.fiber,
            shadows,
            &self.config.lighting,
            eye,
            VertexGeometry {
                positions: &self.strands.positions,
                tangents: &self.strands.tangents,
                points_per_strand: self.strands.points_per_strand,
                segment_pieces: self.strands.segment_pieces,
            },
            only_seen.then_some(&self.seen[..]),
            &mut self.colors,
            &mut self.shade_scratch,
        );
        self.add_volume_light(only_seen);
    }

    /// The raster stage alone: clears the image, draws the solids (lit through the maps) and
    /// the hair with the current vertex colours.
    pub fn draw(&mut self) -> &Framebuffer {
        self.draw_solids_layer();
        self.update_widths();
        self.draw_hair(draw_polylines);
        &self.fb
    }

    /// Clears the image and draws the solids, when the configuration draws them.
    fn draw_solids_layer(&mut self) {
        self.fb.clear(self.config.background);
        if self.config.draw_solids {
            self.draw_solids();
        }
    }

    /// Each point's physical width: its strand's fibres side by side, thinning where they end.
    fn update_widths(&mut self) {
        strand_widths_m(&self.style, &self.strands, &mut self.widths_m);
    }

    /// The hair over what is drawn, with the current colours and widths, by `draw`
    /// ([`draw_seen_polylines`] composites what [`seen_points`] kept).
    fn draw_hair(&mut self, draw: DrawLines) {
        let lines = hair_lines(
            &self.strands,
            &self.colors,
            &self.widths_m,
            &self.bundle_points,
            &self.style,
        );
        draw(
            &mut self.fb,
            &self.camera,
            &lines,
            &self.config.line,
            &mut self.scratch,
        );
    }

    /// The character's mesh (or the head and the body spheres), opaque, lit through the hair's
    /// shadow.
    fn draw_solids(&mut self) {
        // The maps move out for the call (no copy) so the shader can read them while the
        // solids are drawn into the engine's own framebuffer.
        let maps = std::mem::take(&mut self.maps);
        let occluders = std::mem::take(&mut self.occluders);
        let skin_textures = std::mem::take(&mut self.skin_textures);
        let mode = self.config.lighting.mode;
        let lighting = std::mem::replace(
            &mut self.config.lighting,
            Lighting {
                lights: Vec::new(),
                ambient: Vec3::ZERO,
                mode,
            },
        );
        let shadows = Shadows {
            maps: &maps,
            solids: &occluders,
            skin: &skin_textures,
        };
        self.draw_solids_with(|p, n, albedo| shade_skin(shadows, &lighting, albedo, p, n));
        self.maps = maps;
        self.occluders = occluders;
        self.skin_textures = skin_textures;
        self.config.lighting = lighting;
    }

    /// The solids alone on black, shaded by `skin(p, n, albedo)` (world point, unit normal,
    /// albedo → linear RGB) instead of the map-lit skin shader of [`Self::draw`]: for
    /// measuring the skin's shadow against another light (`accuracy::skin`). The next
    /// [`Self::draw`] clears it.
    pub fn solids_image(&mut self, skin: impl Fn(Vec3, Vec3, Vec3) -> Vec3 + Sync) -> &Framebuffer {
        self.fb.clear(Vec3::ZERO);
        self.draw_solids_with(skin);
        &self.fb
    }

    /// Draws the solids into the current framebuffer (not cleared) with the surface shader
    /// `skin`.
    fn draw_solids_with(&mut self, skin: impl Fn(Vec3, Vec3, Vec3) -> Vec3 + Sync) {
        for (s, albedo) in self.solids.iter().zip(&self.solid_albedo) {
            draw_ellipsoid(
                &mut self.fb,
                &self.camera,
                s.unit_sphere_to_world,
                |p, n| skin(p, n, *albedo),
            );
        }
        if let Some(ch) = self.motion.character() {
            let mesh = Mesh {
                positions: &self.character.positions,
                normals: &self.character.normals,
                uv: &ch.uv,
                triangles: &ch.triangles,
                triangle_surface: &ch.triangle_material,
                surfaces: &self.surfaces,
                textures: &self.textures,
            };
            draw_mesh(
                &mut self.fb,
                &self.camera,
                &mesh,
                &skin,
                &mut self.mesh_scratch,
            );
        }
    }

    /// One whole frame at time `t_s`.
    pub fn frame(&mut self, t_s: f64) -> &Framebuffer {
        self.advance(t_s);
        self.render()
    }

    /// Rebuilds the light-oriented map from the current render strands, with the head and
    /// body solids as opaque occluders (they shadow the hair as the hair shadows them). With
    /// `draw_solids` off there are no solids at all: no invisible head casts a shadow.
    pub fn build_map(&mut self) {
        self.solids.clear();
        self.solid_albedo.clear();
        let character = self.motion.character().filter(|_| self.config.draw_solids);
        if self.config.draw_solids {
            // The head ellipsoid unless the character's mesh has a head, then body spheres.
            let radii = Vec3::from(self.style.head.radii_m);
            let skip_head = usize::from(character.is_some() && self.character_has_head);
            for (k, s) in solids_of(&self.pose, radii).enumerate().skip(skip_head) {
                self.solids.push(s);
                self.solid_albedo.push(if k == 0 { SKIN } else { CLOTH });
            }
        }
        let lights = &self.config.lighting.lights;
        let aim_m = Vec3::from(self.pose.head.translation);
        let mesh_positions: &[Vec3] = match character {
            Some(_) => &self.character.positions,
            None => &[],
        };
        // Nothing the maps are made of changed: they would be rebuilt to the same bits.
        self.map_reused = self.map_inputs.unchanged_or_record(&MapInputsView {
            positions: &self.strands.positions,
            tangents: &self.strands.tangents,
            lengths_m: &self.strands.lengths_m,
            lights,
            aim_m,
            solids: &self.solids,
            mesh: mesh_positions,
        }) && self.maps.len() == lights.len().max(1);
        self.map_parts = MapPartTimings::default();
        if self.map_reused {
            return;
        }
        let started = Instant::now();
        // One map per light, built side by side (each build is itself parallel and its
        // result does not depend on the thread count).
        if self.maps.len() != lights.len() {
            let geom = self.maps[0].geometry();
            self.maps.resize(
                lights.len().max(1),
                LightMap::new(geom, CountModel::Poisson),
            );
        }
        let input = |light| crate::map::MapBuildInput {
            positions: &self.strands.positions,
            tangents: &self.strands.tangents,
            lengths_m: &self.strands.lengths_m,
            fiber_share: &self.strands.fiber_share,
            fibers_per_strand: self.style.strands.fibers_per_strand,
            light: crate::map::MapLight::of(light, aim_m),
            fiber: &self.fiber,
        };
        // Skin and clothes read the hair's shadow from a finer texture (`map::surface`).
        let draw_solids = self.config.draw_solids;
        let bundle_radius_m = 0.5 * self.style.strand_spacing_m();
        let contact = self
            .config
            .contact
            .window_m(self.style.strands.fibers_per_strand)
            .map(|window_m| crate::map::contact::ContactInput {
                positions: &self.strands.positions,
                points_per_strand: self.strands.points_per_strand,
                fiber_share: &self.strands.fiber_share,
                window_m,
                fiber: &self.fiber,
            });
        self.maps
            .par_iter_mut()
            .zip(lights.par_iter())
            .for_each(|(map, light)| {
                map.build(&input(light));
                map.build_contact(contact.as_ref());
            });
        self.map_parts.hair_s = started.elapsed().as_secs_f64();
        let mesh = match character {
            Some(ch) => OccluderMesh {
                positions: &self.character.positions,
                triangles: &ch.triangles,
            },
            None => OccluderMesh::EMPTY,
        };
        self.occluders
            .resize_with(self.maps.len(), OccluderGrid::default);
        self.skin_textures.resize_with(self.maps.len(), || None);
        for (k, (map, light)) in self.maps.iter().zip(lights).enumerate() {
            let t = Instant::now();
            self.occluders[k].build_for(map, &self.solids, mesh);
            let t_surface = Instant::now();
            if draw_solids {
                SurfaceShadow::build_for(
                    &mut self.skin_textures[k],
                    map,
                    &self.occluders[k],
                    &input(light),
                    bundle_radius_m,
                );
            }
            self.map_parts.occluders_s += (t_surface - t).as_secs_f64();
            self.map_parts.surface_s += t_surface.elapsed().as_secs_f64();
        }
    }

    /// Whether the last [`Engine::build_map`] kept the maps it had (nothing they are made of
    /// had changed; see `frame::map_reuse`).
    pub fn map_reused(&self) -> bool {
        self.map_reused
    }

    /// Makes the next [`Engine::build_map`] rebuild the maps even if nothing they are made
    /// of changed (a benchmark of the map stage on still hair).
    pub fn invalidate_maps(&mut self) {
        self.map_inputs.forget();
    }

    /// Places the camera once the hair has settled: the fixed camera, or the head-following
    /// framing of the settled hair (`scene::HeadFollowing`).
    fn place_camera(&mut self) {
        let (w, h) = (self.config.width, self.config.height);
        match self.config.camera {
            CameraSetup::Fixed(spec) => {
                self.follow = None;
                self.camera = spec.camera(w, h);
            }
            CameraSetup::HeadFollowing => {
                let (rig, cam) = HeadFollowing::frame(
                    &self.strands.positions,
                    self.pose.head,
                    self.style.max_length_m(),
                    w,
                    h,
                );
                self.follow = Some(rig);
                self.camera = cam;
            }
        }
    }

    /// Sets where the camera is (`config.camera`) and places it at once: a fixed camera as
    /// given, a head-following one framed anew on the current hair and pose. The window's
    /// mouse camera uses it.
    pub fn set_camera(&mut self, setup: CameraSetup) {
        self.config.camera = setup;
        self.place_camera();
    }

    /// Moves a head-following camera with the head's translation (a fixed one stays).
    fn follow_head(&mut self) {
        if let Some(rig) = &self.follow {
            self.camera = rig.camera(
                Vec3::from(self.pose.head.translation),
                self.config.width,
                self.config.height,
            );
        }
    }
}
