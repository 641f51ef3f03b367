//! `render --curves FILE.usda`: the render strands of every rendered frame written beside the
//! images as USD curves with a time sample per frame (`wisp::export::usd`).
//!
//! The file is opened before the first frame (so a path that cannot be written fails at
//! once), its size is estimated there (a warning above [`WARN_BYTES`]), each rendered
//! frame's points are appended as soon as the frame is drawn, and the file is renamed into
//! place after the last one. The widths and the colours are those of the first frame: every
//! point shaded (`Engine::shade`, after the frame's image is drawn, so the image does not
//! change). Frame `i` at `start_s + i / fps` seconds has the time code `start_s · fps + i`,
//! with `fps` time codes a second.

use crate::cli::AppError;
use glam::Vec3;
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::time::Instant;
use wisp::engine::Engine;
use wisp::export::usd::{CurveShape, CurvesLook, TimeCodes, UsdCurvesWriter, estimated_bytes};

/// Above this estimated size, the run says so before it starts.
pub const WARN_BYTES: u64 = 2_000_000_000;

/// `--curves`: a file name ending in `.usda` or `.usd` (both written as USD ASCII).
pub fn parse_curves_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    let ext = path
        .extension()
        .and_then(OsStr::to_str)
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("usda" | "usd") => Ok(path),
        Some("abc") => Err(
            "Alembic is not written; give a .usda file (USD ASCII curves, which Blender and Houdini import)"
                .into(),
        ),
        Some("usdc" | "usdz") => Err(
            "only USD ASCII is written; give a .usda file (usdcat converts it to .usdc)".into(),
        ),
        _ => Err("the curves are written as USD ASCII; give a file ending in .usda (or .usd)".into()),
    }
}

/// Where the curves go and the time line of the run's frames.
#[derive(Clone, Debug)]
pub struct CurvesOutput {
    pub path: PathBuf,
    /// Frames per second (one time code per frame).
    pub fps: f64,
    /// Time of frame 0, seconds of the motion.
    pub start_s: f64,
}

impl CurvesOutput {
    /// Refuses, before any work, a file whose directory does not exist (the file is
    /// created there once the hair is in place).
    pub fn check_dir(&self) -> Result<(), AppError> {
        let dir = match self.path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        if dir.is_dir() {
            return Ok(());
        }
        Err(AppError::input(anyhow::anyhow!(
            "--curves {}: the directory {} does not exist",
            self.path.display(),
            dir.display()
        )))
    }

    /// The time code of frame `i`.
    fn time_code(&self, i: u32) -> f64 {
        self.start_s * self.fps + f64::from(i)
    }
}

/// A curves file being written during an export.
pub struct CurvesExport {
    writer: UsdCurvesWriter,
    path: PathBuf,
    /// The first frame's widths and colours (every point shaded), once it is rendered.
    look: Option<(Vec<f32>, Vec<Vec3>)>,
    frames: u32,
    spent_s: f64,
}

impl CurvesExport {
    /// Opens `out`'s file for frames `indices` of strands shaped like `engine`'s, warning on
    /// stderr (unless `quiet`) when it is estimated above [`WARN_BYTES`].
    pub fn start(
        out: &CurvesOutput,
        engine: &Engine,
        indices: std::ops::Range<u32>,
        quiet: bool,
    ) -> Result<Self, AppError> {
        let strands = engine.strands();
        let shape = CurveShape {
            curves: strands.strand_count(),
            points_per_curve: strands.points_per_strand,
        };
        let bytes = estimated_bytes(shape.points() as u64, indices.len() as u64);
        if !quiet && bytes > WARN_BYTES {
            eprintln!(
                "wisp: warning: --curves {}: about {:.1} GB ({} frames of {} strands × {} points); fewer --frames or a smaller hairstyle make it smaller",
                out.path.display(),
                bytes as f64 * 1e-9,
                indices.len(),
                shape.curves,
                shape.points_per_curve
            );
        }
        let time = TimeCodes {
            start: out.time_code(indices.start),
            end: out.time_code(indices.end.saturating_sub(1).max(indices.start)),
            per_second: out.fps,
        };
        let doc = format!(
            "wisp {}: render strands of \"{}\", metres, root first, one time code per frame",
            env!("CARGO_PKG_VERSION"),
            engine.style.name
        );
        let writer = UsdCurvesWriter::create(&out.path, shape, time, &doc)
            .map_err(|e| AppError::input(curves_error(&out.path, e)))?;
        Ok(Self {
            writer,
            path: out.path.clone(),
            look: None,
            frames: 0,
            spent_s: 0.0,
        })
    }

    /// Appends frame `i`'s render strands (`engine` has just rendered it); the first frame's
    /// widths and colours are kept for the end.
    pub fn add(&mut self, engine: &mut Engine, out: &CurvesOutput, i: u32) -> Result<(), AppError> {
        let started = Instant::now();
        if self.look.is_none() {
            engine.shade();
            self.look = Some((engine.widths_m().to_vec(), engine.colors().to_vec()));
        }
        self.writer
            .write_sample(out.time_code(i), &engine.strands().positions)
            .map_err(|e| AppError::other(curves_error(&self.path, e)))?;
        self.frames += 1;
        self.spent_s += started.elapsed().as_secs_f64();
        Ok(())
    }

    /// Closes the file and renames it into place; says on stderr (unless `quiet`) what it
    /// wrote and what it cost.
    pub fn finish(self, quiet: bool) -> Result<(), AppError> {
        let started = Instant::now();
        let (widths_m, colors) = self.look.unwrap_or_default();
        let look = CurvesLook {
            widths_m: &widths_m,
            colors: Some(&colors),
        };
        let bytes = self
            .writer
            .finish(look)
            .map_err(|e| AppError::other(curves_error(&self.path, e)))?;
        let spent_s = self.spent_s + started.elapsed().as_secs_f64();
        if !quiet {
            let frames = f64::from(self.frames.max(1));
            eprintln!(
                "wisp: wrote the curves of {} frames to {}: {:.1} MB ({:.2} MB and {:.1} ms a frame)",
                self.frames,
                self.path.display(),
                bytes as f64 * 1e-6,
                bytes as f64 * 1e-6 / frames,
                spent_s * 1e3 / frames
            );
        }
        Ok(())
    }
}

/// A curves error, naming the flag (the library's message names the file).
fn curves_error(path: &Path, e: wisp::export::usd::UsdError) -> anyhow::Error {
    anyhow::Error::new(e).context(format!("--curves {}", path.display()))
}
