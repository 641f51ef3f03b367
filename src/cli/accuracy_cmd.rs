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
    bias_per_bin, markdown, measure_map, placement_floor, single_fiber_variant, sweep_geometries,
};
use wisp::engine::{ContactShadowing, DEFAULT_CONTACT_WINDOW_M};
use wisp::output::write_png_rgb8;

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
    /// piece of strand), `fibres-lit` (the same, on each fibre's lit side, where contact
    /// shadows read), `ball:R` (all hair within R millimetres) or `disc:R` (a disc of R
    /// millimetres across the light at the vertex's depth).
    #[arg(long, default_value = "fibres")]
    pub footprint: String,
    /// Replace every render strand of F fibres by K render strands of one fibre each (the
    /// exact-geometry variant: with one fibre per strand the reference needs no placement).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub single_fiber_strands: Option<u32>,
    /// Measure the hair's shadow on the skin and clothes instead: every pixel of the solids
    /// facing the light, the map's T_f against `--rays` exact rays from half a pixel's width
    /// (shot per pixel: 800 × 800 with 64 rays takes about 2 s for the smooth preset).
    #[arg(long)]
    pub skin: bool,
    /// With `--skin`: write the map's T_f, the reference's and their difference side by side
    /// to this PNG file.
    #[arg(long, requires = "skin")]
    pub skin_image: Option<std::path::PathBuf>,
    /// Placements of each bundle's fibres the reference averages (`accuracy::ensemble_light`):
    /// 1 is the documented placement alone; more average the same bundles turned by other
    /// angles, the light a render strand receives when where its fibres lie is not known (as
    /// the map does not know it). Each costs one reference; ignored with one fibre per strand.
    #[arg(long, default_value_t = wisp::accuracy::DEFAULT_PLACEMENTS, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub placements: u32,
    /// Also measure the reference's own floor: the exact reference with each bundle's fibres
    /// placed otherwise (2 placements outside the reference's; `accuracy::placement_floor`)
    /// against the reference, in the table's terms. Costs two more references.
    #[arg(long)]
    pub placement_floor: bool,
    /// Timed repetitions per map resolution.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub repeats: u32,
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
    // Contact shadows are measured (40 mm unless `--contact-mm` says otherwise); the frame that
    // settles the hair does not need them.
    let contact = match args.scene.contact_mm {
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
        let first = measured.placements as u64;
        let seeds = [first, first + 1];
        let floors = placement_floor(&engine, &measured, &seeds);
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
    Ok(())
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
