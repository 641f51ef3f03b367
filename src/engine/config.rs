//! What a run is configured with (everything that is not the hairstyle or the motion) and the
//! per-stage timings of a frame.

use crate::raster::LineStyle;
use crate::scene::CameraSetup;
use crate::shade::Lighting;
use glam::Vec3;

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

/// Seconds spent in each part of the map stage of one frame (all 0 when the maps were
/// reused: nothing they are made of had moved).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MapPartTimings {
    /// The hair's light maps (fill, sorts, merge and sweep; contact shadows' bins when on).
    pub hair_s: f64,
    /// The head's and body's entry depths across each light.
    pub occluders_s: f64,
    /// The skin's shadow texture (`map::surface`), when solids are drawn.
    pub surface_s: f64,
}

impl MapPartTimings {
    pub const NAMES: [&'static str; 3] = ["hair map", "occluders", "skin texture"];

    pub fn as_array(&self) -> [f64; 3] {
        [self.hair_s, self.occluders_s, self.surface_s]
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
    /// How hair lines are drawn: by default each render strand's physical width (fibres per
    /// strand × fibre diameter) projected per segment, at least
    /// [`DEFAULT_MIN_LINE_WIDTH_PX`] wide with its opacity lowered to conserve coverage.
    pub line: LineStyle,
    /// Background colour (linear RGB).
    pub background: Vec3,
    /// Where the camera is (default: framing the hair and following the head).
    pub camera: CameraSetup,
    /// Draw the head and the body spheres (default true); without them hair behind the head
    /// shows, as in a scene of hair alone.
    pub draw_solids: bool,
    /// Contact shadows (`map::contact`): the fibres in front of each vertex taken exactly
    /// (default off: they cost seconds per frame on dense one-fibre hair, BENCHMARKS.md).
    pub contact: ContactShadowing,
    /// Each segment of the groom's render strands is cut into this many straight pieces (1:
    /// as the groom says): the drawn geometry is the same, but the map, the contact shadows
    /// and the shader read the hair this many times as often along it
    /// ([`crate::interp::subdivide_in_place`]), at about as many times their cost.
    pub segment_pieces: u32,
    /// The light-path volume of [`crate::fiber::ShadingMode::Volume`] (unused by the other
    /// shaders).
    pub volume: crate::light_paths::LightPathParams,
}

/// Whether the maps take the fibres just in front of each vertex exactly (`map::contact`).
/// Only hair whose render strands are single fibres (one fibre per strand: the geometry is
/// then exact) can use them; bundles of fibres, whose fibres the engine does not place, never
/// do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ContactShadowing {
    /// Off: the map alone.
    Off,
    /// On with this window, metres (> 0), for one-fibre strands.
    WindowM(f32),
}

/// The contact window `wisp accuracy` uses by default and the documents recommend, metres.
/// Since contact shadows read each vertex's point (2026-12-05), the exact point light's lit
/// vertices bin against the map's expectation beyond the window (ACCURACY.md §1: lit bin by
/// truth −0.062 at 40 mm, −0.035 at 120 mm), and against the path tracer 120 mm reads dense
/// back-lit dual 0.92–0.95 where 40 mm read 0.87–0.92 (§2), at the same cost.
pub const DEFAULT_CONTACT_WINDOW_M: f32 = 0.12;

impl ContactShadowing {
    /// From a window in millimetres (`--contact-mm`): 0 is off.
    pub fn from_mm(mm: f32) -> Self {
        if mm > 0.0 {
            ContactShadowing::WindowM(mm * 1e-3)
        } else {
            ContactShadowing::Off
        }
    }

    /// The window for hair of `fibers_per_strand` fibres per render strand, or `None` (off).
    pub fn window_m(self, fibers_per_strand: f32) -> Option<f32> {
        if fibers_per_strand.round() != 1.0 {
            return None;
        }
        match self {
            ContactShadowing::Off => None,
            ContactShadowing::WindowM(w) => (w > 0.0 && w.is_finite()).then_some(w),
        }
    }
}

/// Narrowest drawn hair line in pixels; thinner strands are drawn this wide at lower opacity.
/// Half a pixel: eight of a pixel's 16 sub-samples across, so a thin line's coverage moves
/// in steps of an eighth of its α as it slides. Fibres side by side then hide what is behind
/// them nearly as their summed width does; 1 px (before 2026-12-05) drew each fibre over a
/// whole pixel row at a fraction of the opacity, so neighbours overlapped as independent
/// layers: side-lit dense single scattering read 0.91 of the path tracer at 1 px, 0.92 at
/// 0.5 px and at 0.25 px, brown front 0.97 / 0.95 / 0.94 at 1 px and 1.00 / 0.98 / 0.97 at
/// 0.5 px (ACCURACY.md §2).
pub const DEFAULT_MIN_LINE_WIDTH_PX: f32 = 0.5;

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
            line: LineStyle::projected(DEFAULT_MIN_LINE_WIDTH_PX),
            background: Vec3::new(0.012, 0.014, 0.018),
            camera: CameraSetup::HeadFollowing,
            draw_solids: true,
            contact: ContactShadowing::Off,
            segment_pieces: 1,
            volume: crate::light_paths::LightPathParams::default(),
        }
    }
}

impl EngineConfig {
    /// This configuration with the image size, camera, lights, ambient, background and solids
    /// of a validated scene.
    pub fn with_scene(self, scene: &crate::scene::Scene) -> Self {
        Self {
            width: scene.width,
            height: scene.height,
            lighting: Lighting {
                lights: scene.lights.clone(),
                ambient: scene.ambient,
                ..self.lighting
            },
            background: scene.background,
            camera: scene.camera,
            draw_solids: scene.draw_solids,
            ..self
        }
    }
}
