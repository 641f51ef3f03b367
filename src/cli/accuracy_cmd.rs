//! `wisp accuracy`: the map against the exact reference (explicit fibres, ray shooting), over
//! map resolutions: time, T_f error and bias, and the error of the shaded result. This is what
//! ACCURACY.md's map tables are made of, and what `wisp bench` reports as speed against error.
//!
//! One hair state (the dance at `--at-s`) is prepared; the exact reference is built once and
//! queried at `--vertices` vertices spread evenly over the strands; then, per resolution N, the
//! map is built and read at the same vertices. Time is the map build plus a lookup at every
//! vertex of the hair (the map's whole per-frame cost), median of `--repeats` runs.

use super::{AppError, SceneArgs};
use wisp::accuracy::exact::Footprint;
use wisp::accuracy::skin::measure_skin;
use wisp::accuracy::{
    MapMeasurement, bias_per_bin, markdown, measure_map, placement_floor, single_fiber_variant,
    sweep_geometries,
};
use wisp::engine::{ContactShadowing, DEFAULT_CONTACT_WINDOW_M};
use wisp::output::write_png_rgb8;

#[derive(clap::Args, Debug)]
#[command(mut_arg("contact_mm", |a| {
    a.help("Contact shadows of one-fibre strands, mm (0: off) [default: 120]")
}))]
pub struct AccuracyArgs {
    /// Map resolutions to compare
    #[arg(long, value_name = "N,…", default_value = "32,64,96,128,192,256", value_delimiter = ',', value_parser = clap::value_parser!(u32).range(4..=1024))]
    pub map_res_list: Vec<u32>,
    /// Time in the dance of the hair state, seconds
    #[arg(long, value_name = "SECONDS", default_value_t = 4.0, value_parser = super::parse_finite_f32)]
    pub at_s: f32,
    /// Vertices compared with the reference, 10–1000000
    #[arg(long, value_name = "N", default_value_t = 3000, value_parser = clap::value_parser!(u32).range(10..=1_000_000))]
    pub vertices: u32,
    /// Reference rays per vertex or pixel, 1–65536
    #[arg(long, value_name = "N", default_value_t = 128, value_parser = clap::value_parser!(u32).range(1..=65_536))]
    pub rays: u32,
    /// Rays from fibres, fibres-lit, ball:MM or disc:MM
    #[arg(long, value_name = "WHERE", default_value = "fibres")]
    pub footprint: String,
    /// Replace each render strand by K strands of one fibre each, 1–64
    #[arg(long, alias = "single-fibre-strands", value_name = "K", value_parser = clap::value_parser!(u32).range(1..=64))]
    pub single_fiber_strands: Option<u32>,
    /// Measure the hair's shadow on the skin and clothes instead
    #[arg(long)]
    pub skin: bool,
    /// With --skin: write map, reference and their difference to this PNG
    #[arg(long, value_name = "FILE.png", requires = "skin")]
    pub skin_image: Option<std::path::PathBuf>,
    /// Fibre placements the reference averages, 1–64
    #[arg(long, value_name = "N", default_value_t = wisp::accuracy::DEFAULT_PLACEMENTS, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub placements: u32,
    /// Also measure the reference against two other fibre placements
    #[arg(long)]
    pub placement_floor: bool,
    /// Timed repetitions per map resolution, 1–1000
    #[arg(long, value_name = "N", default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub repeats: u32,
    #[command(flatten)]
    pub scene: SceneArgs,
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
        None if s == "fibres" => Ok(Footprint::Fibers { rays }),
        None if s == "fibres-lit" => Ok(Footprint::FibersLitSide { rays }),
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
            "--footprint: `{s}` is not one of fibres, fibres-lit, ball:R, disc:R (R in millimetres)"
        ))),
    }
}

pub fn run(args: AccuracyArgs) -> Result<(), AppError> {
    let (mut style, hair, motion, mut config) = args.scene.resolve()?;
    // Contact shadows are measured (120 mm unless `--contact-mm` says otherwise); the frame
    // that settles the hair does not need them.
    let contact = match args.scene.hair_map.contact_mm {
        Some(mm) => ContactShadowing::from_mm(mm),
        None => ContactShadowing::WindowM(DEFAULT_CONTACT_WINDOW_M),
    };
    config.hair_map.contact = ContactShadowing::Off;
    if let Some(k) = args.single_fiber_strands {
        style = single_fiber_variant(&style, k);
    }
    let footprint = parse_footprint(&args.footprint, args.rays)?;
    if let Some(path) = &args.skin_image {
        super::check_output_file("--skin-image", path)?;
    }
    let mut engine = super::engine(style.clone(), hair, motion, config);
    engine.run_up_to(args.at_s as f64);
    engine.frame(args.at_s as f64);
    if args.skin {
        return skin(&mut engine, &args);
    }
    let geometries = sweep_geometries(&engine, &args.map_res_list);
    let placements = wisp::accuracy::placements_used(&style, args.placements);
    // The reference is most of the run (seconds per placement): say what is being waited for.
    eprintln!(
        "wisp accuracy: shooting {} rays at {} vertices through {} placement{} of the fibres, \
         then the map at {} resolution{}…",
        args.rays,
        args.vertices,
        placements,
        if placements == 1 { "" } else { "s" },
        geometries.len(),
        if geometries.len() == 1 { "" } else { "s" },
    );
    let measured = measure_map(
        &engine,
        &geometries,
        args.vertices as usize,
        &footprint,
        args.placements,
        args.repeats,
        contact,
    );
    println!(
        "wisp accuracy: {}, {} strands × {} fibres, {} vertices of {}, t = {} s, footprint {:?}; \
         exact reference over {} placement{} of the fibres, {:.0} ms",
        style.name,
        style.wisps.count as u64 * style.wisps.strands_per_wisp as u64,
        style.strands.fibers_per_strand,
        args.vertices,
        engine.strands().positions.len(),
        args.at_s,
        footprint,
        measured.placements,
        if measured.placements == 1 { "" } else { "s" },
        measured.reference_ms
    );
    println!();
    print!("{}", markdown(&measured.rows));
    if args.placement_floor {
        print_placement_floor(&engine, &measured);
    }
    Ok(())
}

/// `--placement-floor`: the exact reference with each bundle's fibres placed otherwise (two
/// placements outside the reference's; `accuracy::placement_floor`) against the reference, in
/// the table's terms, beside the default map's row.
fn print_placement_floor(engine: &wisp::engine::Engine, measured: &MapMeasurement) {
    let first = measured.placements as u64;
    let seeds = [first, first + 1];
    let floors = placement_floor(engine, measured, &seeds);
    println!(
        "\nPlacement floor (the exact reference with each bundle's fibres turned by other \
         angles, against the reference; no estimate from the render strands can know which \
         placement is the hair's):\n"
    );
    println!(
        "| placement seed | T_f MAE | overall bias | bias, true T_f 0.0–0.2 / 0.2–0.5 / \
         0.5–0.8 / 0.8–1.0 | MAE in the same bins |"
    );
    println!("|---|---|---|---|---|");
    let default_map = measured
        .rows
        .iter()
        .find(|r| r.is_default)
        .map(|r| &r.comparison);
    let labelled = seeds
        .iter()
        .map(|s| s.to_string())
        .zip(&floors)
        .chain(default_map.map(|c| ("(the map, default)".to_string(), c)));
    for (seed, c) in labelled {
        let maes: Vec<String> = c.by_truth.iter().map(|b| format!("{:.3}", b.mae)).collect();
        println!(
            "| {seed} | {:.4} | {:+.4} | {} | {} |",
            c.mae,
            c.overall_bias,
            bias_per_bin(&c.by_truth),
            maes.join(" / ")
        );
    }
}

/// `--skin`: the hair's shadow on the solids against exact rays.
fn skin(engine: &mut wisp::engine::Engine, args: &AccuracyArgs) -> Result<(), AppError> {
    let report = measure_skin(engine, args.rays);
    println!(
        "wisp accuracy --skin: {}, t = {} s, {}×{} px, {} rays per pixel from half a pixel's \
         width; exact reference {:.0} ms",
        engine.style.name, args.at_s, report.width, report.height, args.rays, report.reference_ms
    );
    println!();
    println!("| pixels | T_f MAE | bias | bias, true T_f 0–0.2 / 0.2–0.5 / 0.5–0.8 / 0.8–1 |");
    println!("|---|---|---|---|");
    for (label, c) in [
        (
            format!("all facing the light ({})", report.pixels),
            &report.comparison,
        ),
        (
            format!(
                "in the hair's shadow, true T_f < 0.98 ({})",
                report.shadowed_pixels
            ),
            &report.shadowed,
        ),
    ] {
        println!(
            "| {label} | {:.4} | {:+.4} | {} |",
            c.mae,
            c.overall_bias,
            bias_per_bin(&c.by_truth)
        );
    }
    if let Some(path) = &args.skin_image {
        let (w, h, rgb) = report.side_by_side_rgb8();
        write_png_rgb8(path, w, h, &rgb).map_err(|e| {
            AppError::other(anyhow::anyhow!("--skin-image {}: {e}", path.display()))
        })?;
        println!(
            "\nwrote {} (map | exact rays | map − rays, red lighter, blue darker, ±0.25)",
            path.display()
        );
    }
    Ok(())
}
