//! `wisp accuracy`: the map against the exact reference (explicit fibres, ray shooting), over
//! map resolutions: time, T_f error and bias, and the error of the shaded result. This is what
//! ACCURACY.md's map tables are made of, and what `wisp bench` reports as speed against error.
//!
//! One hair state (the dance at `--at-s`) is prepared; the exact reference is built once and
//! queried at `--vertices` vertices spread evenly over the strands; then, per resolution N, the
//! map is built and read at the same vertices. Time is the map build plus a lookup at every
//! vertex of the hair (the map's whole per-frame cost), median of `--repeats` runs.

use super::{AppError, SceneArgs};
use glam::Vec3;
use std::time::Instant;
use wisp::frame::Engine;
use wisp::hairstyle::Hairstyle;
use wisp::map::accuracy::{BIN_EDGES, Comparison, sample_vertices};
use wisp::map::exact::{ExactInput, ExactReference, Footprint};
use wisp::map::{CountModel, LightMap, MapBuildInput, MapGeometry};
use wisp::shade::shade_vertices_with;

#[derive(clap::Args, Debug)]
pub struct AccuracyArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Map resolutions (cells per axis) to compare, comma separated; the scene's own choice is
    /// always added.
    #[arg(long, default_value = "32,64,96,128,192,256", value_delimiter = ',', value_parser = clap::value_parser!(u32).range(4..=1024))]
    pub map_res_list: Vec<u32>,
    /// Time in the dance of the hair state, seconds.
    #[arg(long, default_value_t = 4.0, value_parser = super::parse_finite_f32)]
    pub at_s: f32,
    /// Vertices at which the map is compared with the reference.
    #[arg(long, default_value_t = 3000, value_parser = clap::value_parser!(u32).range(10..=1_000_000))]
    pub vertices: u32,
    /// Rays per vertex in the reference.
    #[arg(long, default_value_t = 128, value_parser = clap::value_parser!(u32).range(1..=65_536))]
    pub rays: u32,
    /// Where the reference's rays start: `fibres` (the fibres the vertex is drawn for, along its
    /// piece of strand), `ball:R` (all hair within R millimetres) or `disc:R` (a disc of R
    /// millimetres across the light at the vertex's depth).
    #[arg(long, default_value = "fibres")]
    pub footprint: String,
    /// Replace every render strand of F fibres by K render strands of one fibre each (the
    /// exact-geometry variant: with one fibre per strand the reference needs no placement).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub single_fibre_strands: Option<u32>,
    /// Timed repetitions per map resolution.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub repeats: u32,
}

/// One row of the table.
#[derive(Clone, Debug)]
pub struct Row {
    pub n: u32,
    pub ds_mm: f32,
    pub ms: f64,
    pub comparison: Comparison,
    /// Relative RMS of the shaded vertex luminance against shading with the reference light.
    pub luminance_rel_rms: f64,
    /// Mean shaded luminance, map ÷ reference.
    pub luminance_ratio: f64,
}

/// Parses `--footprint`.
fn parse_footprint(s: &str, rays: u32) -> Result<Footprint, AppError> {
    let mm = |v: &str| -> Result<f32, AppError> {
        match v.parse::<f32>() {
            Ok(x) if x.is_finite() && x > 0.0 => Ok(x * 1e-3),
            _ => Err(AppError::input(anyhow::anyhow!(
                "--footprint: `{v}` must be a radius in millimetres > 0"
            ))),
        }
    };
    match s.split_once(':') {
        None if s == "fibres" => Ok(Footprint::Fibres { rays }),
        Some(("ball", r)) => Ok(Footprint::Ball {
            radius_m: mm(r)?,
            rays,
        }),
        Some(("disc", r)) => Ok(Footprint::Disc {
            radius_m: mm(r)?,
            rays,
            exclude_segments: 1,
        }),
        _ => Err(AppError::input(anyhow::anyhow!(
            "--footprint: `{s}` is not one of fibres, ball:R, disc:R (R in millimetres)"
        ))),
    }
}

/// The exact-geometry variant of a hairstyle: K render strands of one fibre for every render
/// strand of F fibres.
pub fn single_fibre_variant(style: &Hairstyle, k: u32) -> Hairstyle {
    let mut s = style.clone();
    s.wisps.strands_per_wisp = s.wisps.strands_per_wisp.saturating_mul(k);
    s.strands.fibers_per_strand = 1.0;
    s.name = format!("{} (x{k} strands, 1 fibre each)", style.name);
    s
}

/// Measures the map against the exact reference for an engine's current hair state, at the
/// resolutions `ns`; prints nothing.
pub fn measure(
    engine: &Engine,
    ns: &[u32],
    vertices: usize,
    footprint: &Footprint,
    repeats: u32,
) -> (Vec<Row>, f64) {
    let style = &engine.style;
    let strands = &engine.strands;
    let light_dir = engine.config.lighting.light_dir;
    let t0 = Instant::now();
    let reference = ExactReference::build(
        &ExactInput {
            positions: &strands.positions,
            points_per_strand: strands.points_per_strand,
            fibers_per_strand: style.strands.fibers_per_strand.round().max(1.0) as u32,
            bundle_radius_m: 0.5 * style.strand_spacing_m(),
            light_dir,
            fiber: &engine.fiber,
        },
        0.5 * style.strand_spacing_m(),
    );
    let verts = sample_vertices(strands.positions.len(), vertices);
    let truth = reference.light_at_vertices(&verts, footprint);
    let reference_ms = t0.elapsed().as_secs_f64() * 1e3;
    let pos: Vec<Vec3> = verts.iter().map(|&v| strands.positions[v]).collect();
    let tan: Vec<Vec3> = verts.iter().map(|&v| strands.tangents[v]).collect();
    let eye = engine.camera().eye();
    let lighting = &engine.config.lighting;
    let lum = |c: &Vec3| c.dot(Vec3::new(0.2126, 0.7152, 0.0722)) as f64;
    let mut ref_colors = Vec::new();
    shade_vertices_with(
        &engine.fiber,
        lighting,
        eye,
        &pos,
        &tan,
        |i, _| truth[i],
        &mut ref_colors,
    );
    let ref_mean = ref_colors.iter().map(lum).sum::<f64>() / ref_colors.len().max(1) as f64;
    let ref_rms = (ref_colors.iter().map(|c| lum(c).powi(2)).sum::<f64>()
        / ref_colors.len().max(1) as f64)
        .sqrt();
    let span = MapGeometry::span_m(style.max_length_m(), style.head_size_m());
    let input = MapBuildInput {
        positions: &strands.positions,
        tangents: &strands.tangents,
        lengths_m: &strands.lengths_m,
        fibers_per_strand: style.strands.fibers_per_strand,
        light_dir,
        fiber: &engine.fiber,
    };
    let mut rows = Vec::new();
    for &n in ns {
        let mut map = LightMap::new(MapGeometry::with_resolution(span, n), CountModel::Poisson);
        let mut times: Vec<f64> = (0..repeats.max(1))
            .map(|_| {
                let t0 = Instant::now();
                map.build(&input);
                let mut sink = 0.0f32;
                for p in &strands.positions {
                    sink += map.light_at(*p).direct_fraction;
                }
                std::hint::black_box(sink);
                t0.elapsed().as_secs_f64() * 1e3
            })
            .collect();
        times.sort_by(f64::total_cmp);
        let estimate: Vec<_> = pos.iter().map(|p| map.light_at(*p)).collect();
        let mut colors = Vec::new();
        shade_vertices_with(
            &engine.fiber,
            lighting,
            eye,
            &pos,
            &tan,
            |i, _| estimate[i],
            &mut colors,
        );
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
            n,
            ds_mm: span / n as f32 * 1e3,
            ms: times[times.len() / 2],
            comparison: Comparison::new(&truth, &estimate),
            luminance_rel_rms: rms,
            luminance_ratio: mean / ref_mean.max(1e-12),
        });
    }
    (rows, reference_ms)
}

/// The rows as Markdown tables (error binned by truth, and calibration binned by the estimate).
pub fn markdown(rows: &[Row], default_n: u32) -> String {
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
        let bias: Vec<String> = c
            .by_truth
            .iter()
            .map(|b| {
                if b.count == 0 {
                    "—".into()
                } else {
                    format!("{:+.3} ({})", b.bias, b.count)
                }
            })
            .collect();
        let mark = if r.n == default_n {
            " **(default)**"
        } else {
            ""
        };
        s += &format!(
            "| {}{mark} | {:.2} | {:.1} | {:.4} | {:+.4} | {} | {:.3} | {:.3} |\n",
            r.n,
            r.ds_mm,
            r.ms,
            c.mae,
            c.overall_bias,
            bias.join(" / "),
            r.luminance_rel_rms,
            r.luminance_ratio
        );
    }
    s += "\nCalibration (bias binned by the map's own T_f):\n\n";
    s += &format!("| N | bias, map T_f {} |\n|---|---|\n", bins.join(" / "));
    for r in rows {
        let bias: Vec<String> = r
            .comparison
            .by_estimate
            .iter()
            .map(|b| {
                if b.count == 0 {
                    "—".into()
                } else {
                    format!("{:+.3} ({})", b.bias, b.count)
                }
            })
            .collect();
        s += &format!("| {} | {} |\n", r.n, bias.join(" / "));
    }
    s
}

pub fn run(args: AccuracyArgs) -> Result<(), AppError> {
    let (mut style, motion, config) = args.scene.resolve()?;
    if let Some(k) = args.single_fibre_strands {
        style = single_fibre_variant(&style, k);
    }
    let footprint = parse_footprint(&args.footprint, args.rays)?;
    let mut engine = Engine::new(style.clone(), motion, config);
    engine.run_up_to(args.at_s as f64);
    engine.frame(args.at_s as f64);
    let default_n = engine.map_geometry().n;
    let mut ns = args.map_res_list.clone();
    if !ns.contains(&default_n) {
        ns.push(default_n);
    }
    ns.sort_unstable();
    let (rows, reference_ms) = measure(
        &engine,
        &ns,
        args.vertices as usize,
        &footprint,
        args.repeats,
    );
    println!(
        "wisp accuracy: {}, {} strands × {} fibres, {} vertices of {}, t = {} s, footprint {:?}; \
         exact reference {:.0} ms",
        style.name,
        style.wisps.count as u64 * style.wisps.strands_per_wisp as u64,
        style.strands.fibers_per_strand,
        args.vertices,
        engine.strands.positions.len(),
        args.at_s,
        footprint,
        reference_ms
    );
    println!();
    print!("{}", markdown(&rows, default_n));
    Ok(())
}
