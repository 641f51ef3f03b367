//! The light map against the exact reference: at several resolutions, at vertices spread
//! evenly over the hair, per vertex (T_f binned by the reference's and by the map's value,
//! `comparison.rs`) and after shading (the sampled vertices shaded with the map's light and
//! with the reference's), with the time of each map's build and lookups.
//!
//! After shading, with ℓ the luminance of a shaded vertex (Rec. 709 weights):
//!
//!   relative RMS = √(mean (ℓ_map − ℓ_ref)²) / √(mean ℓ_ref²),  ratio = mean ℓ_map / mean ℓ_ref.

use super::image::luminance;
use crate::accuracy::comparison::{Comparison, sample_vertices};
use crate::accuracy::exact::Footprint;
use crate::accuracy::reference::{ensemble_light, key_light, placements_used};
use crate::engine::{ContactShadowing, Engine};
use crate::fiber::LightAtPoint;
use crate::map::contact::ContactInput;
use crate::map::{CountModel, LightMap, MapBuildInput, MapGeometry};
use crate::shade::{Lighting, VertexGeometry, shade_vertices_with};
use glam::Vec3;
use rayon::prelude::*;
use std::time::Instant;

/// One row of the table.
#[derive(Clone, Debug)]
pub struct Row {
    pub n: u32,
    pub ds_mm: f32,
    /// Columns per cell width across the light.
    pub lateral: u32,
    /// The engine's own choice (`MapGeometry::for_scene`).
    pub is_default: bool,
    pub ms: f64,
    pub comparison: Comparison,
    /// Relative RMS of the shaded vertex luminance against shading with the reference light.
    pub luminance_rel_rms: f64,
    /// Mean shaded luminance, map ÷ reference.
    pub luminance_ratio: f64,
}

/// What [`measure_map`] measured: the rows, and the reference they were measured against.
#[derive(Clone, Debug)]
pub struct MapMeasurement {
    pub rows: Vec<Row>,
    /// Time the reference took (build + queries), ms.
    pub reference_ms: f64,
    /// The sampled vertices, the footprint and the reference's light at each.
    pub vertices: Vec<usize>,
    pub footprint: Footprint,
    /// Placements of each bundle's fibres the reference averages ([`ensemble_light`]).
    pub placements: u32,
    pub truth: Vec<LightAtPoint>,
}

/// Measures the map against the exact reference for an engine's current hair state, at the
/// resolutions `geometries`, at `vertices` vertices spread evenly over the strands. Time per
/// row is the map build plus a lookup at every vertex of the hair (with the contact shadows'
/// build and queries when `contact` asks for them; lookups in parallel), median of `repeats`
/// runs.
pub fn measure_map(
    engine: &Engine,
    geometries: &[MapGeometry],
    vertices: usize,
    footprint: &Footprint,
    placements: u32,
    repeats: u32,
    contact: ContactShadowing,
) -> MapMeasurement {
    let style = &engine.style;
    let strands = &engine.strands();
    let t0 = Instant::now();
    let light = key_light(engine);
    let verts = sampled_vertices(engine, vertices);
    let placements = placements_used(style, placements);
    let truth = ensemble_light(
        style,
        strands,
        &engine.fiber,
        light,
        &verts,
        footprint,
        placements,
    );
    let reference_ms = t0.elapsed().as_secs_f64() * 1e3;
    let shading = Shading::new(engine, &verts);
    let ref_colors = shading.shade(&truth);
    let input = MapBuildInput {
        positions: &strands.positions,
        tangents: &strands.tangents,
        lengths_m: &strands.lengths_m,
        fiber_share: &strands.fiber_share,
        fibers_per_strand: style.strands.fibers_per_strand,
        light,
        fiber: &engine.fiber,
    };
    // Contact shadows when asked for and usable (one fibre per strand), read as the shader
    // reads them but without the camera's opposition term (the reference has no camera): a
    // view direction along the light's travel shares no fibres with the light ray.
    let contact = contact
        .window_m(style.strands.fibers_per_strand)
        .map(|window_m| ContactInput {
            positions: &strands.positions,
            points_per_strand: strands.points_per_strand,
            fiber_share: &strands.fiber_share,
            window_m,
            fiber: &engine.fiber,
        });
    let bench = RowBench {
        engine,
        input,
        contact,
        verts: &verts,
        shading,
        reference: ShadedReference::new(ref_colors),
        truth: &truth,
        repeats,
    };
    let rows = geometries.iter().map(|&geom| bench.row(geom)).collect();
    MapMeasurement {
        rows,
        reference_ms,
        vertices: verts,
        footprint: *footprint,
        placements,
        truth,
    }
}

/// The sampled vertices, shaded on their own with the key light alone.
struct Shading<'a> {
    engine: &'a Engine,
    lighting: Lighting<'a>,
    eye: Vec3,
    positions: Vec<Vec3>,
    tangents: Vec<Vec3>,
}

impl<'a> Shading<'a> {
    /// The shading of `engine`'s vertices `verts` under its key light (the first).
    fn new(engine: &'a Engine, verts: &[usize]) -> Self {
        let strands = engine.strands();
        Shading {
            engine,
            lighting: Lighting {
                lights: std::slice::from_ref(&engine.scene.lights[0]),
                ..engine.shading.lighting(&engine.scene)
            },
            eye: engine.camera().eye(),
            positions: verts.iter().map(|&v| strands.positions[v]).collect(),
            tangents: verts.iter().map(|&v| strands.tangents[v]).collect(),
        }
    }

    /// The sampled vertices' colours with `light` at each.
    fn shade(&self, light: &[LightAtPoint]) -> Vec<Vec3> {
        let mut colors = Vec::new();
        shade_vertices_with(
            &self.engine.fiber,
            &self.lighting,
            self.eye,
            // A sample of vertices, each on its own: shaded at its tangent.
            VertexGeometry {
                positions: &self.positions,
                tangents: &self.tangents,
                points_per_strand: 1,
                segment_pieces: 1,
            },
            |_, i, _| light[i],
            &mut colors,
        );
        colors
    }
}

/// The vertices shaded with the reference's light: their colours, mean luminance and RMS
/// luminance.
struct ShadedReference {
    colors: Vec<Vec3>,
    mean: f64,
    rms: f64,
}

impl ShadedReference {
    fn new(colors: Vec<Vec3>) -> Self {
        let count = colors.len().max(1) as f64;
        let mean = colors.iter().copied().map(luminance).sum::<f64>() / count;
        let rms = (colors.iter().map(|c| luminance(*c).powi(2)).sum::<f64>() / count).sqrt();
        ShadedReference { colors, mean, rms }
    }
}

/// What every row of [`measure_map`] is measured with.
struct RowBench<'a> {
    engine: &'a Engine,
    input: MapBuildInput<'a>,
    contact: Option<ContactInput<'a>>,
    verts: &'a [usize],
    shading: Shading<'a>,
    reference: ShadedReference,
    truth: &'a [LightAtPoint],
    repeats: u32,
}

impl RowBench<'_> {
    /// The map's light at `vertices`, read as the shader reads it without a camera.
    fn read(&self, map: &LightMap, vertices: &mut dyn Iterator<Item = usize>) -> Vec<LightAtPoint> {
        let positions = &self.engine.strands().positions;
        let away = map.frame().x;
        let list: Vec<usize> = vertices.collect();
        list.par_iter()
            .map(|&v| map.light_at_vertex_seen(v, positions[v], away, Vec3::X, 0.0))
            .collect()
    }

    /// The row of a map of geometry `geom`.
    fn row(&self, geom: MapGeometry) -> Row {
        let count = self.engine.strands().positions.len();
        let mut map = LightMap::new(geom, CountModel::Poisson);
        let mut times: Vec<f64> = (0..self.repeats.max(1))
            .map(|_| {
                let t0 = Instant::now();
                map.build(&self.input);
                map.build_contact(self.contact.as_ref());
                let all = self.read(&map, &mut (0..count));
                std::hint::black_box(all);
                t0.elapsed().as_secs_f64() * 1e3
            })
            .collect();
        times.sort_by(f64::total_cmp);
        let estimate = self.read(&map, &mut self.verts.iter().copied());
        let colors = self.shading.shade(&estimate);
        let reference = &self.reference;
        let rms = (colors
            .iter()
            .zip(&reference.colors)
            .map(|(a, b)| (luminance(*a) - luminance(*b)).powi(2))
            .sum::<f64>()
            / colors.len().max(1) as f64)
            .sqrt()
            / reference.rms.max(1e-12);
        let mean = colors.iter().copied().map(luminance).sum::<f64>() / colors.len().max(1) as f64;
        Row {
            n: geom.n,
            ds_mm: geom.ds_m * 1e3,
            lateral: geom.lateral,
            is_default: geom == self.engine.map_geometry(),
            ms: times[times.len() / 2],
            comparison: Comparison::new(self.truth, &estimate),
            luminance_rel_rms: rms,
            luminance_ratio: mean / reference.mean.max(1e-12),
        }
    }
}

/// The `vertices` vertices a measurement samples, spread evenly over the strands' points
/// where at least one fibre is present (past the tips, hair is not drawn).
pub(crate) fn sampled_vertices(engine: &Engine, vertices: usize) -> Vec<usize> {
    let strands = &engine.strands();
    let fibers = engine.style.strands.fibers_per_strand.round().max(1.0);
    let with_hair: Vec<usize> = (0..strands.positions.len())
        .filter(|&i| {
            strands
                .fiber_share
                .get(i)
                .is_none_or(|s| *s >= 0.5 / fibers)
        })
        .collect();
    sample_vertices(with_hair.len(), vertices)
        .into_iter()
        .map(|k| with_hair[k])
        .collect()
}

/// The resolutions a sweep compares: `ns` cubic cells per axis (N), then the
/// engine's own geometry (its N with finer columns across the light) when it is not among them.
pub fn sweep_geometries(engine: &Engine, ns: &[u32]) -> Vec<MapGeometry> {
    let style = &engine.style;
    let span = MapGeometry::span_m(style.max_length_m(), style.head_size_m());
    let mut out: Vec<MapGeometry> = ns
        .iter()
        .map(|&n| MapGeometry::with_resolution(span, n))
        .collect();
    if !out.contains(&engine.map_geometry()) {
        out.push(engine.map_geometry());
    }
    out
}
