//! The hair map pass: one light-oriented map per light (Bertails 2005 §2–3, carrying Zinke
//! 2008's dual-scattering statistics; `crate::map`), built from the render strands, and for
//! hair of one fibre per strand its contact shadows (the fibres just in front of each vertex,
//! taken exactly). Maps of several lights are built side by side; each build is itself
//! parallel and its result does not depend on the thread count.

use super::reuse::Kept;
use super::sizes::RunSizes;
use crate::budget::{MemoryPart, grouped};
use crate::fiber::Fiber;
use crate::hairstyle::Hairstyle;
use crate::interp::StrandGeometry;
use crate::light::Light;
use crate::map::contact::{ContactInput, ContactShadows};
use crate::map::{CONTACT_BIN_COLUMNS, CountModel, LightMap, MapBuildInput, MapGeometry, MapLight};
use glam::Vec3;
use rayon::prelude::*;

/// How the hair's light maps are made, and how often.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HairMapConfig {
    /// Map cells per axis; `None` (the default) sizes the map from the scene
    /// ([`MapGeometry::for_scene`]).
    pub map_res: Option<u32>,
    /// With `map_res` unset, cells this many times as wide as the scene's own choice
    /// (default 1; [`MapGeometry::for_scene_scaled`]).
    pub cell_scale: f32,
    /// Seconds of motion between two builds of the hair maps; the hair of the frames between
    /// is lit by the last build, read where each point was then (the occluders and the skin
    /// texture follow every frame). 0 (the default) builds them for every frame. See
    /// `engine::map_rate`.
    pub rebuild_interval_s: f64,
    /// Contact shadows for hair of one fibre per render strand (default off).
    pub contact: ContactShadowing,
}

impl Default for HairMapConfig {
    fn default() -> Self {
        Self {
            map_res: None,
            cell_scale: 1.0,
            rebuild_interval_s: 0.0,
            contact: ContactShadowing::Off,
        }
    }
}

/// Whether the maps take the fibres just in front of each vertex exactly (`map::contact`).
/// Only hair whose render strands are single fibres (the geometry is then exact) can use them;
/// bundles of fibres, whose fibres the engine does not place, never do.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum ContactShadowing {
    /// Off: the map alone. They cost seconds per frame on dense one-fibre hair
    /// (BENCHMARKS.md).
    #[default]
    Off,
    /// On with this window, metres (> 0), for one-fibre strands.
    WindowM(f32),
}

/// The contact window `wisp accuracy` uses by default and the documents recommend, metres:
/// against the path tracer, 120 mm reads dense back-lit dual scattering 0.92–0.95 where
/// 40 mm read 0.87–0.92, at the same cost (ACCURACY.md).
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

/// The map geometry for `style` under `config`: `config.map_res` cells per axis over the span
/// the hair needs, or sized from the scene with cells `config.cell_scale` times as wide
/// ([`MapGeometry::for_scene_scaled`]).
pub fn map_geometry(style: &Hairstyle, config: &HairMapConfig) -> MapGeometry {
    let span = map_span_m(style);
    match config.map_res {
        Some(n) => MapGeometry::with_resolution(span, n),
        None => MapGeometry::for_span_scaled(
            span,
            style.strand_spacing_m(),
            style.strands.fibers_per_strand,
            config.cell_scale,
        ),
    }
}

/// The span of `style`'s map, metres: 2·lmax + hmax (Bertails §2.2, [`MapGeometry::span_m`]),
/// or twice an imported groom's reach when that is larger (`Hairstyle::reach_m`: roots off the
/// head ellipsoid).
pub fn map_span_m(style: &Hairstyle) -> f32 {
    let swing = MapGeometry::span_m(style.max_length_m(), style.head_size_m());
    match style.guides.reach_m {
        Some(r) => swing.max(MapGeometry::span_for_reach_m(r)),
        None => swing,
    }
}

/// What a frame's maps are built from.
#[derive(Clone, Copy)]
pub struct HairMapInput<'a> {
    pub strands: &'a StrandGeometry,
    pub lights: &'a [Light],
    /// Where point lights aim their map's axis: the head's centre.
    pub aim_m: Vec3,
    pub fiber: &'a Fiber,
    pub fibers_per_strand: f32,
}

impl<'a> HairMapInput<'a> {
    /// The map build's input for `light`.
    pub fn for_light(&self, light: &Light) -> MapBuildInput<'a> {
        MapBuildInput {
            positions: &self.strands.positions,
            tangents: &self.strands.tangents,
            lengths_m: &self.strands.lengths_m,
            fiber_share: &self.strands.fiber_share,
            fibers_per_strand: self.fibers_per_strand,
            light: MapLight::of(light, self.aim_m),
            fiber: self.fiber,
        }
    }
}

/// One map per light, and what they were last built from.
pub struct HairMapPass {
    pub config: HairMapConfig,
    maps: Vec<LightMap>,
    kept_points: Kept<Vec3>,
    kept_lengths: Kept<f32>,
    kept_lights: Kept<Light>,
    /// Whether the last run kept the maps it had.
    reused: bool,
}

impl HairMapPass {
    /// Empty maps of `geom`, one per light (at least one).
    pub fn new(config: HairMapConfig, geom: MapGeometry, lights: usize) -> Self {
        Self {
            config,
            maps: vec![LightMap::new(geom, CountModel::Poisson); lights.max(1)],
            kept_points: Kept::default(),
            kept_lengths: Kept::default(),
            kept_lights: Kept::default(),
            reused: false,
        }
    }

    /// Builds every light's map from `input`, unless nothing it is made of changed since the
    /// last build (the maps would be the same bits). Returns whether the maps changed.
    pub fn run(&mut self, input: &HairMapInput) -> bool {
        self.reused = self.unchanged(input) && self.maps.len() == input.lights.len().max(1);
        if self.reused {
            return false;
        }
        if self.maps.len() != input.lights.len() {
            let geom = self.maps[0].geometry();
            self.maps.resize(
                input.lights.len().max(1),
                LightMap::new(geom, CountModel::Poisson),
            );
        }
        let contact = self
            .config
            .contact
            .window_m(input.fibers_per_strand)
            .map(|window_m| ContactInput {
                positions: &input.strands.positions,
                points_per_strand: input.strands.points_per_strand,
                fiber_share: &input.strands.fiber_share,
                window_m,
                fiber: input.fiber,
            });
        self.maps
            .par_iter_mut()
            .zip(input.lights.par_iter())
            .for_each(|(map, light)| {
                map.build(&input.for_light(light));
                map.build_contact(contact.as_ref());
            });
        true
    }

    /// True when `input` equals what the maps were last built from; records it otherwise.
    fn unchanged(&mut self, input: &HairMapInput) -> bool {
        let s = input.strands;
        // Every record is updated, so none is left behind when another differs.
        let points = self.kept_points.unchanged_or_record(&[
            &s.positions,
            &s.tangents,
            std::slice::from_ref(&input.aim_m),
        ]);
        let lengths = self.kept_lengths.unchanged_or_record(&[&s.lengths_m]);
        let lights = self.kept_lights.unchanged_or_record(&[input.lights]);
        points && lengths && lights
    }

    /// The render-strand points the maps were last built from (empty before the first
    /// build).
    pub fn built_positions(&self) -> &[Vec3] {
        self.kept_points.first()
    }

    /// Makes the next run rebuild the maps even if nothing they are made of changed.
    pub fn invalidate(&mut self) {
        self.kept_points.forget();
    }

    /// Whether the last run kept the maps it had.
    pub fn reused(&self) -> bool {
        self.reused
    }

    /// Every light's map, in the lights' order.
    pub fn maps(&self) -> &[LightMap] {
        &self.maps
    }

    /// The maps, the contact shadows and the inputs kept for reuse.
    pub fn estimate(config: &HairMapConfig, sizes: &RunSizes) -> Vec<MemoryPart> {
        let (geom, lights, points) = (sizes.geom, sizes.lights, sizes.points);
        let set_by_points =
            "wisps.count × wisps.strands_per_wisp × strands.points (× --segment-pieces)";
        let window = config.contact.window_m(sizes.fibers_per_strand);
        let bin_m = geom.column_m() * CONTACT_BIN_COLUMNS;
        vec![
            MemoryPart {
                what: "map inputs kept for reuse",
                product: format!(
                    "{} render points × {} B (position, tangent, length)",
                    grouped(points),
                    2 * size_of::<Vec3>() + size_of::<f32>()
                ),
                bytes: Kept::<Vec3>::estimated_bytes(2 * points)
                    + Kept::<f32>::estimated_bytes(points),
                set_by: set_by_points,
            },
            MemoryPart {
                what: "light map",
                product: format!(
                    "{lights} light(s) × {} render points × {} fill piece(s) per segment in a {}³ map",
                    grouped(points),
                    sizes.pieces,
                    geom.n
                ),
                bytes: geom
                    .estimated_bytes(points, sizes.pieces)
                    .saturating_mul(lights),
                set_by: "wisps.count × wisps.strands_per_wisp × strands.points (× --segment-pieces), --map-res and the lights",
            },
            MemoryPart {
                what: "contact shadows",
                product: match window {
                    Some(_) => format!(
                        "{lights} light(s) × {} render points, segments cut into parts of {:.2} mm",
                        grouped(points),
                        bin_m * 1e3
                    ),
                    None => "off (fibre bundles, or --contact-mm 0)".to_string(),
                },
                bytes: match window {
                    Some(_) => {
                        ContactShadows::estimated_bytes(points, sizes.sample_len_m as f32, bin_m)
                            .saturating_mul(lights)
                    }
                    None => 0,
                },
                set_by: "one fibre per render strand: render points, --map-res and --contact-mm",
            },
        ]
    }
}
