//! `wisp bench --plot FILE.png`: the quality report as a picture, speed against error. Each
//! level is a point at its mean ms a frame on the largest thread count measured (log x axis)
//! and its mean relative luminance error over the hair's pixels (%, y axis), labelled with its
//! name: against `reference` (`reference` itself at 0), the points joined by a line; and
//! `preview` against `final` (`final` at 0) as a second series of other markers. A run of the
//! bench is one scene (one hairstyle), named in the legend; `--plot-with A.json,…` adds the
//! scenes of earlier runs' `--json` reports ([`earlier`]), a colour per scene.
//!
//! Drawn with plotters' bitmap backend into a buffer, text with the DejaVu Sans subset the
//! binary carries (`assets/fonts/`), and written as an 8-bit PNG through a temporary file
//! renamed into place (`wisp::output::write_png_rgb8`).

mod earlier;

pub use earlier::read_report;

use super::quality::LevelPoint;
use crate::cli::AppError;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;
use wisp::quality::Quality;

/// The picture's size, pixels.
pub const WIDTH: u32 = 960;
pub const HEIGHT: u32 = 640;

/// DejaVu Sans, printable ASCII and a few symbols (`assets/fonts/README.md`).
const FONT: &[u8] = include_bytes!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/assets/fonts/DejaVuSans-subset.ttf"
));

/// One scene's levels: the hairstyle's name and the levels' points.
#[derive(Clone, Debug)]
pub struct ScenePoints {
    pub name: String,
    pub points: Vec<LevelPoint>,
}

/// What the picture shows: the thread count of this run's times and each scene's points.
pub struct PlotData<'a> {
    pub threads: u32,
    pub scenes: &'a [ScenePoints],
}

/// A colour per scene (the first is this run's), in turn.
const SCENE_COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
];

/// Whether `levels` give the plot something to draw: a level against `reference`, or
/// `preview` against `final`.
pub fn has_comparison(levels: &[Quality]) -> bool {
    let has = |q| levels.contains(&q);
    (has(Quality::Reference) && levels.len() > 1) || (has(Quality::Preview) && has(Quality::Final))
}

/// Draws `data` (the module doc) and writes it to `path`.
pub fn write_plot(path: &Path, data: &PlotData) -> Result<(), AppError> {
    plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
        .map_err(|_| AppError::other(anyhow::anyhow!("--plot: the built-in font does not load")))?;
    let mut rgb = vec![0u8; 3 * WIDTH as usize * HEIGHT as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (WIDTH, HEIGHT)).into_drawing_area();
        draw(&root, data)
            .and_then(|()| root.present())
            .map_err(|e| AppError::other(anyhow::anyhow!("--plot: drawing failed: {e}")))?;
    }
    wisp::output::write_png_rgb8(path, WIDTH, HEIGHT, &rgb)
        .map_err(|e| AppError::input(anyhow::anyhow!("--plot: {e}")))
}

type DrawResult =
    Result<(), DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>>;

/// The series: (legend, colour, points as (ms, error %, level name), against `reference`),
/// the points in order of time.
type Series = (String, RGBColor, Vec<(f64, f64, &'static str)>, bool);

/// Each scene's two series: against `reference` and `preview` against `final`.
fn series(data: &PlotData) -> Vec<Series> {
    let mut all = Vec::new();
    for (k, scene) in data.scenes.iter().enumerate() {
        let of = |error: fn(&LevelPoint) -> Option<f64>| {
            let mut v: Vec<(f64, f64, &'static str)> = scene
                .points
                .iter()
                .filter_map(|p| error(p).map(|e| (p.ms.max(1e-3), e * 100.0, p.level.name())))
                .collect();
            v.sort_by(|a, b| a.0.total_cmp(&b.0));
            v
        };
        let color = SCENE_COLORS[k % SCENE_COLORS.len()];
        all.push((
            format!("{}: against reference", scene.name),
            color,
            of(|p| p.vs_reference),
            true,
        ));
        all.push((
            format!("{}: preview against final", scene.name),
            lighter(color),
            of(|p| p.vs_final),
            false,
        ));
    }
    all
}

/// The scenes' names, each once, in order.
fn scene_names(data: &PlotData) -> String {
    let mut names: Vec<&str> = Vec::new();
    for s in data.scenes {
        if !names.contains(&s.name.as_str()) {
            names.push(&s.name);
        }
    }
    names.join(", ")
}

/// `c` halfway to white: the preview-against-final series of a scene.
fn lighter(c: RGBColor) -> RGBColor {
    let half = |v: u8| v + (255 - v) / 2;
    RGBColor(half(c.0), half(c.1), half(c.2))
}

/// The label of an x tick at `ms`: the value at 1, 2 and 5 times a power of ten, none at the
/// ticks between (their grid lines stay).
fn round_ticks_only(ms: &f64) -> String {
    let leading = ms / 10f64.powf(ms.log10().floor());
    if [1.0, 2.0, 5.0].iter().any(|d| (leading - d).abs() < 1e-6) {
        format!("{ms:.0}")
    } else {
        String::new()
    }
}

fn draw(root: &DrawingArea<BitMapBackend, Shift>, data: &PlotData) -> DrawResult {
    root.fill(&WHITE)?;
    let all = series(data);
    let points = || all.iter().flat_map(|s| s.2.iter());
    let (lo, hi) = points().fold((f64::MAX, 0.0f64), |(lo, hi), p| (lo.min(p.0), hi.max(p.0)));
    // From a power of ten, so that the axis has its ticks from there on (plotters puts the
    // ticks between decades after the first power of ten in the range).
    let (lo, hi) = if hi > 0.0 {
        (10f64.powf((lo / 1.6).log10().floor()), hi * 1.6)
    } else {
        (1.0, 1000.0)
    };
    let top = points().map(|p| p.1).fold(1.0f64, f64::max) * 1.2;
    let mut chart = ChartBuilder::on(root)
        .caption(
            format!(
                "wisp bench: time against image error, {}",
                scene_names(data)
            ),
            ("sans-serif", 24),
        )
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d((lo..hi).log_scale(), 0.0..top)?;
    chart
        .configure_mesh()
        .x_desc(format!(
            "mean ms a frame on {} thread{} (log scale)",
            data.threads,
            if data.threads == 1 { "" } else { "s" }
        ))
        .x_labels(12)
        .x_label_formatter(&round_ticks_only)
        .y_label_formatter(&|e| format!("{e:.prec$}", prec = if top >= 10.0 { 0 } else { 1 }))
        .y_desc("mean relative luminance error over the hair (%)")
        .axis_desc_style(("sans-serif", 18))
        .label_style(("sans-serif", 15))
        .draw()?;
    for (k, (name, color, pts, against_reference)) in all.iter().enumerate() {
        // Labels above the points of every other scene and below the rest, so that two
        // scenes' levels at about the same place (their `reference`) stay readable.
        let label_dy = if (k / 2) % 2 == 0 { -22 } else { 8 };
        if pts.is_empty() {
            continue;
        }
        let color = *color;
        chart
            .draw_series(LineSeries::new(
                pts.iter().map(|p| (p.0, p.1)),
                color.stroke_width(2),
            ))?
            .label(name.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(2))
            });
        if *against_reference {
            chart.draw_series(
                pts.iter()
                    .map(|p| Circle::new((p.0, p.1), 6, color.filled())),
            )?;
        } else {
            chart.draw_series(
                pts.iter()
                    .map(|p| TriangleMarker::new((p.0, p.1), 8, color.filled())),
            )?;
        }
        chart.draw_series(pts.iter().map(|&(x, y, level)| {
            EmptyElement::at((x, y)) + Text::new(level, (9, label_dy), ("sans-serif", 16))
        }))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .label_font(("sans-serif", 16))
        .draw()?;
    Ok(())
}
