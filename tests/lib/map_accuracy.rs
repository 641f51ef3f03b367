//! The map against the exact reference (`map::exact`: ray shooting through explicit fibre
//! cylinders) on the presets during the dance, at the resolution the engine chooses itself:
//! the targets of ACCURACY.md, computed by the same function as `wisp accuracy`.
//!
//! Footprint (why, in ACCURACY.md): the rays start on the fibres each vertex is drawn for,
//! along the piece of strand it represents: the light the drawn hair receives.
//!
//! Fewer vertices and rays than ACCURACY.md (2,000 × 64 instead of 3,000 × 128 at full size,
//! `WISP_FULL_TESTS=1`; 1,000 × 64 by default) keep this to seconds per preset; the bounds below
//! leave room for that sampling. Fewer vertices leave the error's mean as it is and widen only
//! its scatter (∝ 1/√N); the calibration bins are asserted only where they hold at least 40
//! vertices, so a bin's scatter stays within the same bound at either size. Fewer rays would
//! not do: the reference's own noise adds to the MAE.

use crate::support::full_size;
use wisp::accuracy::exact::Footprint;
use wisp::accuracy::{Row, measure_map, single_fiber_variant, sweep_geometries};
use wisp::engine::{ContactShadowing, DEFAULT_CONTACT_WINDOW_M};
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::{MotionOptions, dance::try_dance};

/// The engine at 4 s of the dance on its collider spheres, without the mannequin: the scene
/// ACCURACY.md's figures and these bounds were set on. The map is the same code with the
/// mannequin, but the hair lies otherwise at 4 s (spread on its capsule shoulders) and reads a
/// little darker against the exact rays (luminance ratio: tapered smooth 0.980, one fibre per
/// strand 0.967). The map here has no occluders either way.
fn engine_at_4s(style: Hairstyle) -> Engine {
    let opts = MotionOptions {
        meshes: false,
        ..MotionOptions::default()
    };
    let motion = try_dance(&opts).expect("embedded dance");
    let config = EngineConfig::sized(160, 160);
    let mut engine = Engine::new(style, motion, config);
    engine.run_up_to(4.0);
    engine.frame(4.0);
    engine
}

/// Vertices sampled per row: 2,000 at full size (`WISP_FULL_TESTS=1`), 1,000 by default.
fn vertices() -> usize {
    if full_size() { 2000 } else { 1000 }
}

fn rows(engine: &Engine, ns: &[u32], fp: Footprint) -> Vec<Row> {
    rows_against(engine, ns, fp, vertices(), 1)
}

/// The rows against the reference averaged over `placements` placements of each bundle's
/// fibres, at `vertices` vertices.
fn rows_against(
    engine: &Engine,
    ns: &[u32],
    fp: Footprint,
    vertices: usize,
    placements: u32,
) -> Vec<Row> {
    measure_map(
        engine,
        &sweep_geometries(engine, ns),
        vertices,
        &fp,
        placements,
        1,
        ContactShadowing::WindowM(DEFAULT_CONTACT_WINDOW_M),
    )
    .rows
}

/// Bounds on the default row: T_f MAE, worst calibration bin, |overall bias|, |luminance − 1|.
struct Bounds {
    mae: f64,
    calibration: f64,
    overall_bias: f64,
    luminance: f64,
}

/// The presets' targets (ACCURACY.md); calibration 0.035: see the call.
const PRESET_BOUNDS: Bounds = Bounds {
    mae: 0.02,
    calibration: 0.035,
    overall_bias: 0.01,
    luminance: 0.02,
};

fn check_default(name: &str, row: &Row, bounds: &Bounds) {
    let Bounds {
        mae: max_mae,
        calibration: max_calibration,
        overall_bias: max_overall_bias,
        luminance: max_luminance,
    } = *bounds;
    let c = &row.comparison;
    println!(
        "{name} N = {}: MAE {:.4}, overall bias {:+.4}, by truth {:?}, by map {:?}, luminance ratio {:.3}",
        row.n,
        c.mae,
        c.overall_bias,
        c.by_truth.map(|b| (b.count, (b.bias * 1e3).round() / 1e3)),
        c.by_estimate
            .map(|b| (b.count, (b.bias * 1e3).round() / 1e3)),
        row.luminance_ratio
    );
    assert!(c.mae <= max_mae, "{name}: T_f MAE {} > {max_mae}", c.mae);
    // Calibration: where the map says T_f, the hair receives T_f on average (bins holding at
    // least 40 vertices; the brightest bin often holds a handful).
    assert!(
        c.worst_bin_bias(false, 40) <= max_calibration,
        "{name}: calibration bias {:?}",
        c.by_estimate
    );
    assert!(
        c.overall_bias.abs() <= max_overall_bias,
        "{name}: overall bias {}",
        c.overall_bias
    );
    // Shaded, the map's hair is as bright as the reference's (within 2% for the presets).
    assert!(
        (row.luminance_ratio - 1.0).abs() <= max_luminance,
        "{name}: luminance ratio {}",
        row.luminance_ratio
    );
    // The deep-shadow bin, where most vertices are, is unbiased binned by truth too.
    assert!(
        c.by_truth[0].bias.abs() <= 0.03,
        "{name}: {:?}",
        c.by_truth[0]
    );
}

/// The presets with every fibre reaching its strand's tip (the scene the targets were set on).
fn untapered(mut style: Hairstyle) -> Hairstyle {
    style.strands.tip_taper = 0.0;
    style.name = format!("{} (untapered)", style.name);
    style
}

#[test]
fn presets_meet_the_targets_and_error_falls_with_resolution() {
    for style in [
        untapered(Hairstyle::default_smooth()),
        untapered(Hairstyle::default_curly()),
    ] {
        let name = style.name.clone();
        let engine = engine_at_4s(style);
        let rows = rows(&engine, &[32, 64, 128, 256], Footprint::Fibers { rays: 64 });
        let default = rows.iter().find(|r| r.is_default).expect("default row");
        // Calibration bound 0.035: the 0.5–0.8 bin holds ~50 vertices whose errors spread by
        // ~0.07, a standard error of ~0.01 on the bin's bias (measured −0.033 for smooth with
        // two columns per cell, −0.017 with one; the finer columns buy MAE 0.0154 → 0.0115).
        check_default(&name, default, &PRESET_BOUNDS);
        // Cubic cells (the N): the error falls as they shrink.
        let mae = |n: u32| {
            rows.iter()
                .find(|r| r.n == n && r.lateral == 1)
                .expect("row")
                .comparison
                .mae
        };
        assert!(
            mae(32) > mae(64) && mae(64) > mae(128) && mae(128) > mae(256),
            "{name}: the error must fall as N grows: {:?}",
            rows.iter()
                .map(|r| (r.n, r.comparison.mae))
                .collect::<Vec<_>>()
        );
    }
}

#[test]
fn tapered_presets_stay_calibrated() {
    // Tips that thin to a few fibres: the light of a tip vertex depends on where its last
    // fibres lie, which raises the MAE (smooth 0.0115 → 0.0196 at the default map, ACCURACY.md)
    // while the map stays calibrated; these bounds guard that.
    for style in [Hairstyle::default_smooth(), Hairstyle::default_curly()] {
        let name = style.name.clone();
        let engine = engine_at_4s(style);
        let rows = rows(&engine, &[], Footprint::Fibers { rays: 64 });
        check_default(
            &name,
            &rows[0],
            &Bounds {
                mae: 0.03,
                calibration: 0.04,
                ..PRESET_BOUNDS
            },
        );
    }
}

#[test]
fn tapered_presets_meet_the_targets_against_the_placement_ensemble() {
    // Issue 7's targets on the presets as they are (tapered tips), against the reference
    // averaged over 8 placements of each bundle's 30 fibres: the light a render strand
    // receives when where its fibres lie is not known, which is all the map (or any model of
    // the render strands) knows. Against one placement the lit bin cannot meet ±0.03 even for
    // the reference itself (another placement reads −0.03 to −0.045 there); against the
    // ensemble another placement reads within 0.008 in every bin (ACCURACY.md §1, "One
    // placement or the ensemble"). Measured at 30,000 vertices × 128 rays: smooth MAE 0.0119, bins +0.001 /
    // −0.010 / −0.013 / −0.023; curly 0.0051, +0.001 / +0.002 / −0.006 / −0.029. Here 6,000
    // vertices and 32 rays asked per placement (2 on each fibre, a quarter piece either side
    // of the vertex): smooth, about 45 s; curly as well at full size (`WISP_FULL_TESTS=1`,
    // another 75 s). Fewer vertices would not do: at 2,000 the lit bin holds 42 vertices and
    // reads −0.031 for smooth (−0.025 at 6,000), curly's 49 at 6,000. Bins of fewer than 40
    // vertices are not asserted (their mean's standard error exceeds 0.01). N = 128 fails the
    // same bounds (lit bins −0.068 smooth, −0.066 to −0.078 curly), so they discriminate.
    let mut styles = vec![Hairstyle::default_smooth()];
    if full_size() {
        styles.push(Hairstyle::default_curly());
    }
    for style in styles {
        let name = style.name.clone();
        let engine = engine_at_4s(style);
        let rows = rows_against(&engine, &[128], Footprint::Fibers { rays: 32 }, 6000, 8);
        let default = rows.iter().find(|r| r.is_default).expect("default row");
        check_default(&name, default, &PRESET_BOUNDS);
        let c = &default.comparison;
        assert!(c.by_truth[3].count >= 40, "{name}: {:?}", c.by_truth);
        assert!(
            c.worst_bin_bias(true, 40) <= 0.03,
            "{name}: binned by truth {:?}",
            c.by_truth
        );
        let coarse = &rows
            .iter()
            .find(|r| r.n == 128)
            .expect("N = 128")
            .comparison;
        assert!(
            coarse.worst_bin_bias(true, 40) > 0.03,
            "{name}: N = 128 meets the bounds too, so they do not discriminate: {:?}",
            coarse.by_truth
        );
    }
}

#[test]
fn one_fiber_per_strand_meets_the_targets_with_contact_shadows() {
    // With one fibre per strand the light a fibre receives depends on the few single fibres
    // right in front of it, which no grid resolves: the map alone reads MAE 0.052 and the lit
    // bins 0.16–0.28 too dark binned by truth (ACCURACY.md, `--contact-mm 0`). With contact
    // shadows (`map::contact`, `--contact-mm 40`: the fibres within 40 mm in front taken
    // exactly) the targets hold: MAE ≤ 0.02 and |bias| ≤ 0.03 in every true-T_f bin.
    // Contact shadows read the light at the vertex's point on the fibre's lit side
    // (`map::contact`, "What a vertex receives"), so the reference is the ray from that point:
    // one lit-side ray for one fibre. Its light is exact, so the truly lit vertices (truth 1)
    // bin by truth against the map's expectation for the light beyond the window, and the
    // window must be longer than it was against the piece average for that bin: at 40 mm it
    // reads −0.047, at 80 mm −0.030, at 120 mm (the default window) −0.026 (these 2,000
    // vertices; ACCURACY.md §1: −0.035 at 3,000), all from the axis point; from the lit side
    // (since 2026-12-05, stop 44) −0.020 at 120 mm, MAE 0.0065.
    let style = single_fiber_variant(&untapered(Hairstyle::default_smooth()), 12);
    let engine = engine_at_4s(style);
    let rows = rows(&engine, &[], Footprint::FibersLitSide { rays: 1 });
    check_default(
        "smooth, 1 fibre per strand",
        &rows[0],
        &Bounds {
            mae: 0.02,
            calibration: 0.03,
            overall_bias: 0.01,
            luminance: 0.02,
        },
    );
    let c = &rows[0].comparison;
    assert!(
        c.worst_bin_bias(true, 40) <= 0.03,
        "binned by truth: {:?}",
        c.by_truth
    );
}

#[test]
fn fibers_the_camera_sees_near_the_light_are_lit_as_the_exact_rays_say() {
    // The opposition effect: with the light near the camera, the fibres the camera sees are lit
    // more often than the average fibre, because the view and light rays cross the same fibres
    // near the point. The exact reference shoots both rays from the fibres each vertex stands
    // for; over the vertices, Σ P(seen and lit) against Σ P(seen) × the map's direct fraction
    // given seen (`light_at_seen`), for light exactly from the camera, 3° and 20° from it. The
    // unconditional map (`light_at`) is far too dark at 0°.
    use glam::{Quat, Vec3};
    use wisp::accuracy::comparison::sample_vertices;
    use wisp::accuracy::exact::{ExactInput, ExactReference};
    use wisp::hairstyle::Hairstyle;
    use wisp::map::{CountModel, LightMap, MapBuildInput, MapGeometry};
    let style = single_fiber_variant(&Hairstyle::default_smooth(), 4);
    let engine = engine_at_4s(style.clone());
    let strands = &engine.strands();
    let view = Vec3::new(-0.5, -0.2, -1.0).normalize(); // camera looking along `view`
    let verts = sample_vertices(strands.positions.len(), 1500);
    for (g_deg, axis) in [
        (0.0f32, Vec3::Y),
        (3.0, Vec3::Y),
        (3.0, Vec3::X),
        (20.0, Vec3::Y),
        (90.0, Vec3::Y),
        (180.0, Vec3::Y),
    ] {
        let light = Quat::from_axis_angle(axis, g_deg.to_radians()) * view;
        let input = |dir: Vec3| ExactInput {
            positions: &strands.positions,
            points_per_strand: strands.points_per_strand,
            fibers_per_strand: 1,
            bundle_radius_m: 0.0,
            placement_seed: 0,
            fiber_share: &strands.fiber_share,
            light: dir.into(),
            fiber: &engine.fiber,
        };
        let bin = 0.5 * style.strand_spacing_m();
        let lit_ref = ExactReference::build(&input(light), bin);
        let seen_ref = ExactReference::build(&input(view), bin);
        let mut map = LightMap::new(
            MapGeometry::for_scene(
                style.max_length_m(),
                style.head_size_m(),
                style.strand_spacing_m(),
                1.0,
            ),
            CountModel::Poisson,
        );
        map.build(&MapBuildInput {
            positions: &strands.positions,
            tangents: &strands.tangents,
            lengths_m: &strands.lengths_m,
            fiber_share: &strands.fiber_share,
            fibers_per_strand: 1.0,
            light: light.into(),
            fiber: &engine.fiber,
        });
        let r = engine.fiber.params().radius_m;
        let (mut exact, mut model, mut plain, mut seen_total) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for &v in &verts {
            let (seen, both) = lit_ref.seen_and_lit(&seen_ref, v, 64);
            let p = strands.positions[v];
            exact += both as f64;
            let u = strands.tangents[v];
            model += seen as f64 * map.light_at_seen(p, -view, u, r).direct_fraction as f64;
            plain += seen as f64 * map.light_at(p).direct_fraction as f64;
            seen_total += seen as f64;
        }
        let (model, plain) = (model / exact, plain / exact);
        println!(
            "g = {g_deg}° about {axis}: seen share {:.3}, lit given seen {:.3}; map given seen ÷ exact {model:.3}, unconditional ÷ exact {plain:.3}",
            seen_total / verts.len() as f64,
            exact / seen_total
        );
        assert!((model - 1.0).abs() < 0.15, "g = {g_deg}°: {model}");
        if g_deg == 0.0 {
            assert!(
                plain < 0.8,
                "at 0° the unconditional map must be clearly too dark: {plain}"
            );
        }
    }
}

#[test]
fn the_ensemble_is_the_mean_of_its_placements_and_one_fiber_has_one() {
    use wisp::accuracy::{ensemble_light, exact_reference_placed, key_light, placements_used};
    let engine = engine_at_4s(Hairstyle::default_smooth());
    let (style, strands, fiber) = (&engine.style, &engine.strands(), &engine.fiber);
    let light = key_light(&engine);
    let verts = wisp::accuracy::comparison::sample_vertices(strands.positions.len(), 300);
    let fp = Footprint::Fibers { rays: 30 };
    let placed = |seed| {
        exact_reference_placed(style, strands, fiber, light, seed).light_at_vertices(&verts, &fp)
    };
    let (a, b) = (placed(0), placed(1));
    let both = ensemble_light(style, strands, fiber, light, &verts, &fp, 2);
    let mut moved = 0;
    for ((x, y), m) in a.iter().zip(&b).zip(&both) {
        let mean = (x.tf + y.tf) * 0.5;
        assert!(
            (m.tf - mean).abs().max_element() < 1e-6,
            "{m:?} against {x:?}, {y:?}"
        );
        let direct = (x.direct_fraction + y.direct_fraction) * 0.5;
        assert!((m.direct_fraction - direct).abs() < 1e-6);
        moved += usize::from(x.tf != y.tf);
    }
    // Two placements of 30-fibre bundles light some of the vertices differently, or the mean
    // would average nothing.
    assert!(
        moved > 30,
        "only {moved} of 300 vertices differ between placements"
    );
    assert_eq!(placements_used(style, 8), 8);
    let single = single_fiber_variant(style, 2);
    assert_eq!(placements_used(&single, 8), 1);
}
