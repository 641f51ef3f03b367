//! The frames of a plan rendered and written: [`export_frames`].
//!
//! Frames are rendered on the calling thread (each stage parallel inside), converted there to
//! the output format (8-bit sRGB, 16-bit sRGB RGBA, or linear premultiplied RGBA), and handed
//! through a bounded channel to a writer thread that encodes and writes them
//! (`wisp::output::FrameWriter`: temporary name, then rename, so an interrupted export leaves
//! complete frames only). Pixel buffers travel back on a second channel, so the export
//! allocates nothing per frame once running. With `--curves`, each rendered frame's strands
//! are appended to the curves file on the calling thread ([`super::curves`]), which is renamed
//! into place after the last frame.
//!
//! A progress bar (indicatif) shows frames done, frames per second and the time left on a
//! terminal; it is hidden with `--quiet` and when stderr is not a terminal, where a line every
//! 30 frames stands in for it. The first frame rendered is checked for what makes a frame
//! wrong or empty ([`warn_about_first_frame`]); at the end the mean stage timings and what was
//! written and kept go to stderr.

use super::curves::CurvesExport;
use super::{FrameOutput, FramePlan};
use crate::cli::AppError;
use indicatif::ProgressBar;
use std::time::Instant;
use wisp::engine::{Engine, StageTimings};
use wisp::output::{FrameWriter, OutputTimings};

/// What the loop over a plan's frames did.
#[derive(Default)]
struct Tally {
    /// Frames rendered and written, and the sum of their stage timings.
    rendered: u32,
    timings: StageTimings,
    /// Kept frames the simulation ran through, and the seconds that took.
    simulated_only: u32,
    simulated_only_s: f64,
}

/// Why the loop over the frames stopped before the end.
enum Stop {
    /// Putting a frame's hair in place failed.
    Hair(AppError),
    /// The writer thread stopped (a write failed) before this frame.
    Writer(u32),
    /// Writing the frame's curves failed.
    Curves(AppError),
}

/// Renders the frames of `plan` not kept and writes them to `output` as `frame_NNNNN.EXT`
/// (numbered by index) through a writer thread. `hair_at(engine, i)` puts the hair of frame
/// `i` in place (simulated, or read from a cache) and returns its time; the engine renders
/// it. Kept frames go through `hair_at` too, up to the last frame to render, unless the
/// output's frames are independent.
pub fn export_frames(
    engine: &mut Engine,
    plan: &FramePlan,
    output: &FrameOutput,
    started: Instant,
    hair_at: impl FnMut(&mut Engine, u32) -> Result<f64, AppError>,
) -> Result<(), AppError> {
    let mut curves = match &output.curves {
        Some(c) => Some(CurvesExport::start(
            c,
            engine,
            plan.indices.clone(),
            output.quiet,
        )?),
        None => None,
    };
    let mut writer = FrameWriter::start(output.dir.clone(), output.format);
    let last = plan.last_to_render();
    let free = plan
        .indices
        .clone()
        .zip(&plan.kept)
        .filter(|(i, k)| passes_freely(*i, **k, output, last))
        .count();
    let bar = progress_bar(plan.indices.len(), output.quiet);
    bar.set_position(free as u64);
    bar.reset_eta();
    let (tally, stop) = render_frames(
        engine,
        plan,
        output,
        (&mut writer, curves.as_mut()),
        &bar,
        hair_at,
    );
    bar.finish_and_clear();
    let output_s = writer.finish().map_err(AppError::other)?;
    match stop {
        Some(Stop::Hair(e) | Stop::Curves(e)) => return Err(e),
        Some(Stop::Writer(i)) => {
            return Err(AppError::other(anyhow::anyhow!(
                "frame {i}: the frame writer stopped"
            )));
        }
        None => {}
    }
    if !output.quiet {
        report(&tally, &output_s, plan, output, started);
    }
    curves.map_or(Ok(()), |c| c.finish(output.quiet))
}

/// Whether frame `i` needs no work at all: it is `kept`, and either frames are independent
/// or it comes after `last`, the last frame to render (the simulation stops there).
fn passes_freely(i: u32, kept: bool, output: &FrameOutput, last: Option<u32>) -> bool {
    kept && (output.independent_frames || Some(i) > last)
}

/// The loop over the frames: each frame's hair put in place, then rendered and handed to
/// `writer` and to `curves` (or, for a kept frame, only simulated through), with the progress
/// on `bar`.
fn render_frames(
    engine: &mut Engine,
    plan: &FramePlan,
    output: &FrameOutput,
    (writer, mut curves): (&mut FrameWriter, Option<&mut CurvesExport>),
    bar: &ProgressBar,
    mut hair_at: impl FnMut(&mut Engine, u32) -> Result<f64, AppError>,
) -> (Tally, Option<Stop>) {
    let background = engine.scene.background;
    let frames = plan.indices.len();
    let last = plan.last_to_render();
    let mut tally = Tally::default();
    for (i, &kept) in plan.indices.clone().zip(&plan.kept) {
        if passes_freely(i, kept, output, last) {
            continue;
        }
        let t = match hair_at(engine, i) {
            Ok(t) => t,
            Err(e) => return (tally, Some(Stop::Hair(e))),
        };
        bar.set_message(format!("t = {t:.2} s"));
        if kept {
            tally.simulated_only += 1;
            tally.simulated_only_s += engine.timings.animation_s
                + engine.timings.simulation_s
                + engine.timings.interpolation_s;
            bar.inc(1);
            continue;
        }
        engine.render();
        if tally.rendered == 0 {
            bar.suspend(|| warn_about_first_frame(engine));
        }
        tally.rendered += 1;
        tally.timings.add(&engine.timings);
        if writer.write(engine.framebuffer(), background, i).is_err() {
            return (tally, Some(Stop::Writer(i)));
        }
        if let (Some(c), Some(out)) = (curves.as_deref_mut(), &output.curves)
            && let Err(e) = c.add(engine, out, i)
        {
            return (tally, Some(Stop::Curves(e)));
        }
        bar.inc(1);
        let done = bar.position();
        if !output.quiet && bar.is_hidden() && done.is_multiple_of(30) {
            eprintln!("wisp: frame {done}/{frames} (t = {t:.2} s)");
        }
    }
    (tally, None)
}

/// The progress bar of an export of `len` frames, on stderr: hidden when quiet, and by
/// indicatif when stderr is not a terminal.
fn progress_bar(len: usize, quiet: bool) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(len as u64);
    let style = indicatif::ProgressStyle::with_template(
        "wisp: {pos}/{len} frames, {fps} frames/s, ETA {eta}, {msg} [{wide_bar}]",
    )
    .map(|s| {
        s.progress_chars("=> ").with_key(
            "fps",
            |state: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
                let _ = write!(w, "{:.2}", state.per_sec());
            },
        )
    });
    if let Ok(style) = style {
        bar.set_style(style);
    }
    bar
}

/// The export's summary on stderr: mean stage and output timings per frame, and how many
/// frames were written and kept where.
fn report(
    tally: &Tally,
    output_s: &OutputTimings,
    plan: &FramePlan,
    output: &FrameOutput,
    started: Instant,
) {
    let rendered = tally.rendered;
    print_timings(&tally.timings, rendered, started.elapsed().as_secs_f64());
    let per_frame_ms = |s: f64| s * 1e3 / f64::from(rendered.max(1));
    eprintln!(
        "wisp: output ({}, ms per frame): conversion {:.1}, encoding and writing {:.1} (on the writer thread, beside the next frame)",
        output.format.describe(),
        per_frame_ms(output_s.convert_s),
        per_frame_ms(output_s.write_s)
    );
    let frames = plan.indices.len();
    let shown = output.dir.display();
    let range = if plan.indices.start == 0 {
        String::new()
    } else {
        format!(" ({} to {})", plan.indices.start, plan.indices.end - 1)
    };
    let kept = frames - rendered as usize;
    if kept == 0 {
        eprintln!("wisp: wrote {rendered} frames{range} to {shown}");
        return;
    }
    let through = if tally.simulated_only > 0 {
        format!(
            " ({} of them simulated through, {:.1} ms each)",
            tally.simulated_only,
            tally.simulated_only_s * 1e3 / f64::from(tally.simulated_only)
        )
    } else {
        String::new()
    };
    eprintln!(
        "wisp: wrote {rendered} frames and kept {kept} complete ones{through} of {frames}{range} in {shown}"
    );
}

/// Says on stderr what makes the first frame wrong or empty, instead of writing blank frames
/// silently: render points a light's map cannot hold, hair wider than the map, a picture with
/// nothing but background.
fn warn_about_first_frame(engine: &Engine) {
    for (k, map) in engine.maps().iter().enumerate() {
        let stats = map.stats();
        if stats.skipped > 0 {
            eprintln!(
                "wisp: warning: {} of {} render points are left out of the map of lights[{k}] (not finite, or beyond the range of its cells): they neither cast nor receive that light's hair shadows",
                stats.skipped,
                stats.skipped + stats.samples
            );
        }
    }
    let stats = engine.map_stats();
    if stats.overflow {
        let g = engine.map_geometry();
        eprintln!(
            "wisp: warning: the hair extends beyond the light map ({} cells of {:.1} mm per axis), so far-apart hair shadows itself; the map is sized for hair no longer than the hairstyle's guides",
            g.n,
            g.ds_m * 1e3
        );
    }
    let fb = engine.framebuffer();
    let background = engine.scene.background;
    if fb.color.iter().all(|c| *c == background) {
        eprintln!(
            "wisp: warning: the first frame shows only the background: the head and the hair are out of view"
        );
    }
}

/// Mean per-stage milliseconds per frame, on stderr.
fn print_timings(total: &StageTimings, frames: u32, wall_s: f64) {
    let mean = total.scaled(1.0 / frames.max(1) as f64);
    let parts: Vec<String> = StageTimings::NAMES
        .iter()
        .zip(mean.as_array())
        .map(|(n, v)| format!("{n} {:.1}", v * 1e3))
        .collect();
    eprintln!(
        "wisp: per frame (ms): {} | total {:.1} ms; wall {:.1} s for {} frames",
        parts.join(", "),
        mean.total_s() * 1e3,
        wall_s,
        frames
    );
}
