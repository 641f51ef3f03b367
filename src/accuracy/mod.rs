//! Measurements of the pipeline against independent references, shared by `wisp accuracy`,
//! `wisp bench` and the tests, so that ACCURACY.md, the benchmark and the asserted targets are
//! computed the same way.
//!
//! - [`measure_map`]: the light map at several resolutions against the exact reference
//!   (`map::exact`, ray shooting through explicit fibres), per vertex and after shading.
//! - [`placement_floor`]: the reference against itself with the fibres placed otherwise in
//!   each bundle: the error no estimate from the render strands can go below.
//! - [`skin::measure_skin`]: the hair's shadow on the skin against the same reference, per
//!   pixel.

pub mod comparison;
pub mod exact;
pub mod skin;

use crate::accuracy::comparison::{BIN_EDGES, Bin, Comparison, sample_vertices};
use crate::accuracy::exact::{ExactInput, ExactReference, Footprint};
use crate::engine::{ContactShadowing, Engine};
use crate::fiber::Fiber;
use crate::fiber::LightAtPoint;
use crate::hairstyle::Hairstyle;
use crate::interp::StrandGeometry;
use crate::map::contact::ContactInput;
use crate::map::{CountModel, LightMap, MapBuildInput, MapGeometry, MapLight};
use crate::shade::{Lighting, VertexGeometry, shade_vertices_with};
use glam::Vec3;
use rayon::prelude::*;
use std::time::Instant;

/// Placements the references of `wisp accuracy` and `wisp bench` average for bundles of
/// several fibres ([`ensemble_light`]): against 8, another placement reads within 0.008 of
/// them in every true-T_f bin at 30,000 vertices (against one placement, −0.03 to −0.045 in
/// smooth's lit bin; ACCURACY.md §1).
pub const DEFAULT_PLACEMENTS: u32 = 8;

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

/// The exact-geometry variant of a hairstyle: K render strands of one fibre for every render
/// strand of F fibres.
pub fn single_fiber_variant(style: &Hairstyle, k: u32) -> Hairstyle {
    let mut s = style.clone();
    s.wisps.strands_per_wisp = s.wisps.strands_per_wisp.saturating_mul(k);
    s.strands.fibers_per_strand = 1.0;
    s.name = format!("{} (x{k} strands, 1 fibre each)", style.name);
    s
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
/// resolutions `ns`, at `vertices` vertices spread evenly over the strands. Time per row is the map build plus a
/// lookup at every vertex of the hair (with the contact shadows' build and queries when
/// `contact` asks for them; lookups in parallel), median of `repeats` runs.
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
    let key = engine.scene.lights[0];
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
    let pos: Vec<Vec3> = verts.iter().map(|&v| strands.positions[v]).collect();
    let tan: Vec<Vec3> = verts.iter().map(|&v| strands.tangents[v]).collect();
    let eye = engine.camera().eye();
    let key_only = [key];
    let lighting = &Lighting {
        lights: &key_only,
        ..engine.shading.lighting(&engine.scene)
    };
    let lum = |c: &Vec3| c.dot(Vec3::new(0.2126, 0.7152, 0.0722)) as f64;
    // The sampled vertices shaded with the given light at each.
    let shade = |light: &[LightAtPoint]| {
        let mut colors = Vec::new();
        shade_vertices_with(
            &engine.fiber,
            lighting,
            eye,
            // A sample of vertices, each on its own: shaded at its tangent.
            VertexGeometry {
                positions: &pos,
                tangents: &tan,
                points_per_strand: 1,
                segment_pieces: 1,
            },
            |_, i, _| light[i],
            &mut colors,
        );
        colors
    };
    let ref_colors = shade(&truth);
    let ref_mean = ref_colors.iter().map(lum).sum::<f64>() / ref_colors.len().max(1) as f64;
    let ref_rms = (ref_colors.iter().map(|c| lum(c).powi(2)).sum::<f64>()
        / ref_colors.len().max(1) as f64)
        .sqrt();
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
    let read = |map: &LightMap, vertices: &mut dyn Iterator<Item = usize>| -> Vec<LightAtPoint> {
        let away = map.frame().x;
        let list: Vec<usize> = vertices.collect();
        list.par_iter()
            .map(|&v| map.light_at_vertex_seen(v, strands.positions[v], away, Vec3::X, 0.0))
            .collect()
    };
    let mut rows = Vec::new();
    for &geom in geometries {
        let mut map = LightMap::new(geom, CountModel::Poisson);
        let mut times: Vec<f64> = (0..repeats.max(1))
            .map(|_| {
                let t0 = Instant::now();
                map.build(&input);
                map.build_contact(contact.as_ref());
                let all = read(&map, &mut (0..strands.positions.len()));
                std::hint::black_box(all);
                t0.elapsed().as_secs_f64() * 1e3
            })
            .collect();
        times.sort_by(f64::total_cmp);
        let estimate = read(&map, &mut verts.iter().copied());
        let colors = shade(&estimate);
        let rms = (colors
            .iter()
            .zip(&ref_colors)
            .map(|(a, b)| (lum(a) - lum(b)).powi(2))
            .sum::<f64>()
            / colors.len().max(1) as f64)
            .sqrt()
            / ref_rms.max(1e-12);
        let mean = colors.iter().map(lum).sum::<f64>() / colors.len().max(1) as f64;
        rows.push(Row {
            n: geom.n,
            ds_mm: geom.ds_m * 1e3,
            lateral: geom.lateral,
            is_default: geom == engine.map_geometry(),
            ms: times[times.len() / 2],
            comparison: Comparison::new(&truth, &estimate),
            luminance_rel_rms: rms,
            luminance_ratio: mean / ref_mean.max(1e-12),
        });
    }
    MapMeasurement {
        rows,
        reference_ms,
        vertices: verts,
        footprint: *footprint,
        placements,
        truth,
    }
}

/// The placements a reference of `requested` placements averages for `style`: one when each
/// render strand is a single fibre (nothing to place: every seed gives the same bytes,
/// `tests/map_exact.rs`), else `requested` (at least one).
pub fn placements_used(style: &Hairstyle, requested: u32) -> u32 {
    if style.strands.fibers_per_strand.round() <= 1.0 {
        1
    } else {
        requested.max(1)
    }
}

/// The exact reference's light at `vertices`, averaged over `placements` placements of each
/// bundle's fibres (`ExactInput::placement_seed` 0, the documented one, then 1, 2, …): the
/// light a render strand of F fibres receives when where its fibres lie inside the bundle is
/// not known, which is all the render strands say (ACCURACY.md §1, "One placement or the
/// ensemble"). Every field is the plain mean: T_f and the direct fraction are fractions of the
/// same rays, σ̄f² and the crossings behind are means over rays already. Seeds are summed in
/// order, so the result does not depend on the thread count.
pub fn ensemble_light(
    style: &Hairstyle,
    strands: &StrandGeometry,
    fiber: &Fiber,
    light: MapLight,
    vertices: &[usize],
    footprint: &Footprint,
    placements: u32,
) -> Vec<LightAtPoint> {
    let placed = |seed: u64| {
        exact_reference_placed(style, strands, fiber, light, seed)
            .light_at_vertices(vertices, footprint)
    };
    let mut sum = placed(0);
    for seed in 1..placements.max(1) as u64 {
        for (a, b) in sum.iter_mut().zip(placed(seed)) {
            a.direct_fraction += b.direct_fraction;
            a.tf += b.tf;
            a.sigma_f2 += b.sigma_f2;
            a.crossings_behind += b.crossings_behind;
        }
    }
    if placements > 1 {
        let k = placements as f32;
        for a in &mut sum {
            a.direct_fraction /= k;
            a.tf /= k;
            a.sigma_f2 /= k;
            a.crossings_behind /= k;
        }
    }
    sum
}

/// The `vertices` vertices a measurement samples, spread evenly over the strands' points
/// where at least one fibre is present (past the tips, hair is not drawn).
fn sampled_vertices(engine: &Engine, vertices: usize) -> Vec<usize> {
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

/// The reference against itself: at the vertices `measured` sampled, the exact reference
/// with each bundle's fibres turned by other angles (`ExactInput::placement_seed` = each of
/// `seeds`, outside the measurement's own ensemble) compared with the measurement's reference,
/// as if it were a map. Against one placement (`placements` = 1) this is the floor below which
/// no estimate that knows the render strands but not where their fibres lie can go: at a
/// vertex the camera sees lit, a few fibres of its own bundle and its neighbours' decide its
/// light, and their places are the reference's construction. Against an ensemble it is how
/// far one real head of hair lies from the ensemble's mean. With one fibre per strand there is
/// nothing to place, and the comparison is exact (0). Costs one reference per seed.
pub fn placement_floor(
    engine: &Engine,
    measured: &MapMeasurement,
    seeds: &[u64],
) -> Vec<Comparison> {
    let light = key_light(engine);
    seeds
        .iter()
        .map(|&seed| {
            let placed =
                exact_reference_placed(&engine.style, engine.strands(), &engine.fiber, light, seed)
                    .light_at_vertices(&measured.vertices, &measured.footprint);
            Comparison::new(&measured.truth, &placed)
        })
        .collect()
}

/// The key light (the first: its map is the one measured) in the map's terms.
pub fn key_light(engine: &Engine) -> MapLight {
    let key = engine.scene.lights[0];
    MapLight::of(&key, glam::Vec3::from(engine.pose().head.translation))
}

/// The exact reference for render strands `strands` of hairstyle `style` under `light`: F
/// fibres per render strand (the hairstyle's count rounded) within half the strand spacing,
/// binned across the light at half the strand spacing.
pub fn exact_reference<'a>(
    style: &Hairstyle,
    strands: &'a StrandGeometry,
    fiber: &'a Fiber,
    light: MapLight,
) -> ExactReference<'a> {
    exact_reference_placed(style, strands, fiber, light, 0)
}

/// [`exact_reference`] with the bundles' fibres placed by `placement_seed`
/// (`ExactInput::placement_seed`; 0 is the documented placement).
pub fn exact_reference_placed<'a>(
    style: &Hairstyle,
    strands: &'a StrandGeometry,
    fiber: &'a Fiber,
    light: MapLight,
    placement_seed: u64,
) -> ExactReference<'a> {
    ExactReference::build(
        &ExactInput {
            positions: &strands.positions,
            points_per_strand: strands.points_per_strand,
            fibers_per_strand: style.strands.fibers_per_strand.round().max(1.0) as u32,
            bundle_radius_m: 0.5 * style.strand_spacing_m(),
            placement_seed,
            fiber_share: &strands.fiber_share,
            light,
            fiber,
        },
        0.5 * style.strand_spacing_m(),
    )
}

/// The resolutions a sweep compares: `ns` cubic cells per axis (the "N"), then the
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

/// A row's label: N, and the columns per cell when they are not 1, marking the default.
fn label(r: &Row) -> String {
    let cols = if r.lateral > 1 {
        format!(" × {} cols", r.lateral)
    } else {
        String::new()
    };
    let mark = if r.is_default { " **(default)**" } else { "" };
    format!("{}{cols}{mark}", r.n)
}

/// The rows as Markdown tables (error binned by truth, and calibration binned by the estimate).
pub fn markdown(rows: &[Row]) -> String {
    let bins: Vec<String> = (0..4)
        .map(|b| format!("{:.1}–{:.1}", BIN_EDGES[b], BIN_EDGES[b + 1]))
        .collect();
    let mut s = String::new();
    s += &format!(
        "| N | cell (mm) | map ms | T_f MAE | overall bias | bias, true T_f {} | lum. rel. RMS | lum. map ÷ ref |\n",
        bins.join(" / ")
    );
    s += "|---|---|---|---|---|---|---|---|\n";
    for r in rows {
        let c = &r.comparison;
        s += &format!(
            "| {} | {:.2} | {:.1} | {:.4} | {:+.4} | {} | {:.3} | {:.3} |\n",
            label(r),
            r.ds_mm,
            r.ms,
            c.mae,
            c.overall_bias,
            bias_per_bin(&c.by_truth),
            r.luminance_rel_rms,
            r.luminance_ratio
        );
    }
    s += "\nCalibration (bias binned by the map's own T_f):\n\n";
    s += &format!("| N | bias, map T_f {} |\n|---|---|\n", bins.join(" / "));
    for r in rows {
        s += &format!(
            "| {} | {} |\n",
            label(r),
            bias_per_bin(&r.comparison.by_estimate)
        );
    }
    s
}

/// A table cell of the bias in each bin with its count, "—" for an empty bin, " / " between.
pub fn bias_per_bin(bins: &[Bin; 4]) -> String {
    let cells: Vec<String> = bins
        .iter()
        .map(|b| match b.count {
            0 => "—".to_string(),
            n => format!("{:+.3} ({n})", b.bias),
        })
        .collect();
    cells.join(" / ")
}
