//! Render strands in motion out as USD ASCII (`.usda`): one `BasisCurves` prim whose points
//! carry a time sample per frame, so Blender, Houdini or any USD reader plays the hair's
//! motion at the frame rate it was simulated at.
//!
//! [`UsdCurvesWriter`] streams the file: [`UsdCurvesWriter::create`] writes the layer's
//! metadata and the curves' topology, [`UsdCurvesWriter::write_sample`] appends one frame's
//! points as soon as they exist (nothing of earlier frames is held), and
//! [`UsdCurvesWriter::finish`] closes the samples, adds the widths, the colours and the
//! per-frame extents, and renames the file into place. Until then it is `<name>.tmp` in the
//! same directory; dropping the writer unfinished (an error, a stopped export) removes it, so
//! an interrupted export never leaves a half file under the final name.
//!
//! What the file holds:
//! - layer metadata: `metersPerUnit = 1` (wisp's metres), `upAxis = "Y"`, `startTimeCode` and
//!   `endTimeCode` (the first and last sample), `timeCodesPerSecond` and `framesPerSecond`
//!   (the frame rate, so one time code is one frame), `defaultPrim = "hair"`;
//! - `def BasisCurves "hair"`: `type = "linear"` (the polylines wisp draws), `wrap =
//!   "nonperiodic"`, `curveVertexCounts` (every curve has the strands' points per strand, root
//!   first), `points.timeSamples` (world positions in metres), `extent.timeSamples` (each
//!   frame's bounds grown by half the widest width), `widths` and optionally
//!   `primvars:displayColor` (linear RGB), both per vertex and not time-sampled: the values
//!   the caller gives at the end (wisp gives those of the first frame it rendered).
//!
//! Numbers are written with the fewest digits that read back as the same `f32` (Rust's
//! shortest round-trip formatting; exponent notation below 1e-4 and from 1e7), so a reader
//! parsing them as `float` gets the engine's values bit for bit. A point costs about
//! [`BYTES_PER_POINT_SAMPLE`] bytes per frame (`(x, y, z), ` with 9 to 11 characters a
//! coordinate): the `smooth` hairstyle's 3,350 strands of 31 points on the embedded dance
//! make 4.06 MB a frame (39.1 bytes a point), about 1 GB for the dance's 240-frame loop; the
//! widths and colours add about 55 bytes a point once. [`estimated_bytes`] gives the figure
//! before a run.

use std::fmt::Write as _;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use glam::Vec3;
use rayon::prelude::*;

use crate::output::OutputError;

/// About how many bytes one point of one time sample takes in the file, rounded up from the
/// 39.1 measured on `smooth` and the embedded dance (coordinates in metres of a head near
/// the origin).
pub const BYTES_PER_POINT_SAMPLE: u64 = 40;

/// The file's estimated size in bytes for `points` render points over `samples` frames.
pub fn estimated_bytes(points: u64, samples: u64) -> u64 {
    points
        .saturating_mul(samples)
        .saturating_mul(BYTES_PER_POINT_SAMPLE)
}

/// Why a curves file could not be written.
#[derive(Debug, thiserror::Error)]
pub enum UsdError {
    #[error(transparent)]
    Output(#[from] OutputError),
    #[error("{}: {rule}", path.display())]
    Invalid { path: PathBuf, rule: String },
}

/// The time line of the file: the first and last time codes (frames), and how many there are
/// per second (the frame rate).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeCodes {
    pub start: f64,
    pub end: f64,
    pub per_second: f64,
}

/// The curves' topology: every curve has the same number of points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CurveShape {
    pub curves: usize,
    pub points_per_curve: usize,
}

impl CurveShape {
    pub fn points(&self) -> usize {
        self.curves * self.points_per_curve
    }
}

/// What [`UsdCurvesWriter::finish`] adds after the samples: per-vertex widths in metres and,
/// if given, per-vertex linear RGB colours.
#[derive(Clone, Copy, Debug)]
pub struct CurvesLook<'a> {
    pub widths_m: &'a [f32],
    pub colors: Option<&'a [Vec3]>,
}

/// A `.usda` file of curves being written, one time sample at a time (see the module doc).
pub struct UsdCurvesWriter {
    path: PathBuf,
    tmp: PathBuf,
    out: Option<BufWriter<File>>,
    shape: CurveShape,
    time: TimeCodes,
    /// Each sample's time code and bounds (min, max), in order.
    samples: Vec<(f64, Vec3, Vec3)>,
}

impl UsdCurvesWriter {
    /// Creates `<path>.tmp` and writes the layer metadata (`doc` is a free-text description)
    /// and the curves' topology. Curves need at least 2 points; the time codes must be finite
    /// with `start ≤ end` and a positive rate.
    pub fn create(
        path: &Path,
        shape: CurveShape,
        time: TimeCodes,
        doc: &str,
    ) -> Result<Self, UsdError> {
        let invalid = |rule: String| UsdError::Invalid {
            path: path.into(),
            rule,
        };
        if shape.points_per_curve < 2 {
            return Err(invalid(format!(
                "a curve needs at least 2 points (got {})",
                shape.points_per_curve
            )));
        }
        let TimeCodes {
            start,
            end,
            per_second,
        } = time;
        if !(start.is_finite() && end.is_finite() && start <= end) {
            return Err(invalid(format!(
                "the time codes must be finite with start ≤ end (got {start} to {end})"
            )));
        }
        if !(per_second.is_finite() && per_second > 0.0) {
            return Err(invalid(format!(
                "time codes per second must be a positive number (got {per_second})"
            )));
        }
        let tmp = temporary_path(path);
        let file = File::create(&tmp).map_err(|error| OutputError::Io {
            path: tmp.clone(),
            error,
        })?;
        let mut writer = Self {
            path: path.into(),
            tmp,
            out: Some(BufWriter::with_capacity(1 << 20, file)),
            shape,
            time,
            samples: Vec::new(),
        };
        let header = header_text(shape, time, doc);
        writer.put(&header)?;
        Ok(writer)
    }

    /// Appends the curves' points at `time_code` (metres, curve after curve, root first):
    /// exactly the shape's point count, all finite, time codes increasing from sample to
    /// sample.
    pub fn write_sample(&mut self, time_code: f64, points: &[Vec3]) -> Result<(), UsdError> {
        self.check_sample(time_code, points)
            .map_err(|rule| UsdError::Invalid {
                path: self.path.clone(),
                rule,
            })?;
        // Formatted in parallel pieces, written in order: the same bytes on any thread count.
        let pieces: Vec<(String, Vec3, Vec3)> = points
            .par_chunks(POINTS_PER_PIECE)
            .map(format_points)
            .collect();
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        self.put(&format!("        {time_code}: ["))?;
        for (k, (text, piece_lo, piece_hi)) in pieces.iter().enumerate() {
            lo = lo.min(*piece_lo);
            hi = hi.max(*piece_hi);
            if k > 0 {
                self.put(", ")?;
            }
            self.put(text)?;
        }
        self.put("],\n")?;
        self.samples.push((time_code, lo, hi));
        Ok(())
    }

    /// Why a sample cannot be written, if it cannot.
    fn check_sample(&self, time_code: f64, points: &[Vec3]) -> Result<(), String> {
        if points.len() != self.shape.points() {
            return Err(format!(
                "time code {time_code}: {} points, the curves have {} ({} × {})",
                points.len(),
                self.shape.points(),
                self.shape.curves,
                self.shape.points_per_curve
            ));
        }
        if let Some(k) = points.iter().position(|p| !p.is_finite()) {
            return Err(format!(
                "time code {time_code}: point {k} is not finite ({})",
                points[k]
            ));
        }
        match self.samples.last() {
            _ if !time_code.is_finite() => Err(format!("time code {time_code} is not finite")),
            Some((last, ..)) if time_code <= *last => Err(format!(
                "time code {time_code} does not come after the previous sample's {last}"
            )),
            _ => Ok(()),
        }
    }

    /// Closes the samples, writes the extents, `look`'s widths (one per point, finite, ≥ 0)
    /// and colours, syncs, and renames the file into place. The samples must span the time
    /// codes given to [`UsdCurvesWriter::create`] exactly. Returns the file's size in bytes.
    pub fn finish(mut self, look: CurvesLook) -> Result<u64, UsdError> {
        self.check_finish(&look).map_err(|rule| UsdError::Invalid {
            path: self.path.clone(),
            rule,
        })?;
        let half_width = look.widths_m.iter().fold(0.0f32, |a, w| a.max(*w)) * 0.5;
        let text = closing_text(&self.samples, half_width, &look);
        self.put(&text)?;
        let io = |path: &Path| {
            let path = path.to_path_buf();
            move |error| OutputError::Io { path, error }
        };
        let Some(out) = self.out.take() else {
            return Ok(0);
        };
        let file = out
            .into_inner()
            .map_err(|e| io(&self.tmp)(e.into_error()))?;
        file.sync_all().map_err(io(&self.tmp))?;
        let bytes = file.metadata().map_err(io(&self.tmp))?.len();
        std::fs::rename(&self.tmp, &self.path).map_err(io(&self.path))?;
        Ok(bytes)
    }

    /// Why the file cannot be closed with `look`, if it cannot.
    fn check_finish(&self, look: &CurvesLook) -> Result<(), String> {
        let points = self.shape.points();
        let (Some(first), Some(last)) = (self.samples.first(), self.samples.last()) else {
            return Err("no time sample was written".into());
        };
        if first.0 != self.time.start || last.0 != self.time.end {
            return Err(format!(
                "the time samples span {} to {}, the header says {} to {}",
                first.0, last.0, self.time.start, self.time.end
            ));
        }
        if look.widths_m.len() != points {
            return Err(format!(
                "{} widths for {points} points",
                look.widths_m.len()
            ));
        }
        if let Some(k) = look
            .widths_m
            .iter()
            .position(|w| !(w.is_finite() && *w >= 0.0))
        {
            return Err(format!(
                "width {k} must be finite and ≥ 0 (got {})",
                look.widths_m[k]
            ));
        }
        match look.colors {
            Some(c) if c.len() != points => Err(format!("{} colours for {points} points", c.len())),
            Some(c) if c.iter().any(|c| !c.is_finite()) => Err("a colour is not finite".into()),
            _ => Ok(()),
        }
    }

    /// Appends `text` to the temporary file.
    fn put(&mut self, text: &str) -> Result<(), UsdError> {
        let Some(out) = self.out.as_mut() else {
            return Ok(());
        };
        out.write_all(text.as_bytes()).map_err(|error| {
            UsdError::from(OutputError::Io {
                path: self.tmp.clone(),
                error,
            })
        })
    }
}

impl Drop for UsdCurvesWriter {
    /// An unfinished file is removed: only [`UsdCurvesWriter::finish`] gives it its name.
    fn drop(&mut self) {
        if self.out.take().is_some() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// Points a sample's text is formatted in at a time, one piece per task.
const POINTS_PER_PIECE: usize = 4096;

/// `points` as `(x, y, z), (x, y, z)…`, and their bounds (min, max).
fn format_points(points: &[Vec3]) -> (String, Vec3, Vec3) {
    let mut s = String::with_capacity(points.len() * BYTES_PER_POINT_SAMPLE as usize);
    let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for (k, p) in points.iter().enumerate() {
        lo = lo.min(*p);
        hi = hi.max(*p);
        if k > 0 {
            s.push_str(", ");
        }
        push_vec3(&mut s, *p);
    }
    (s, lo, hi)
}

/// `<path>.tmp`, beside `path`.
fn temporary_path(path: &Path) -> PathBuf {
    let mut name = path.as_os_str().to_owned();
    name.push(".tmp");
    PathBuf::from(name)
}

/// The layer's metadata, the prim's opening and topology, and the opening of the points'
/// time samples.
fn header_text(shape: CurveShape, time: TimeCodes, doc: &str) -> String {
    let mut s = String::new();
    let _ = write!(
        s,
        "#usda 1.0\n(\n    defaultPrim = \"hair\"\n    doc = \"{}\"\n    endTimeCode = {}\n    \
         framesPerSecond = {}\n    metersPerUnit = 1\n    startTimeCode = {}\n    \
         timeCodesPerSecond = {}\n    upAxis = \"Y\"\n)\n\n",
        escaped(doc),
        time.end,
        time.per_second,
        time.start,
        time.per_second
    );
    s.push_str("def BasisCurves \"hair\"\n{\n    uniform token type = \"linear\"\n");
    s.push_str("    uniform token wrap = \"nonperiodic\"\n    int[] curveVertexCounts = [");
    for k in 0..shape.curves {
        if k > 0 {
            s.push_str(", ");
        }
        let _ = write!(s, "{}", shape.points_per_curve);
    }
    s.push_str("]\n    point3f[] points.timeSamples = {\n");
    s
}

/// What follows the last sample: the end of the points' samples, the extents, widths and
/// colours, and the end of the prim.
fn closing_text(samples: &[(f64, Vec3, Vec3)], half_width_m: f32, look: &CurvesLook) -> String {
    let mut s = String::from("    }\n    float3[] extent.timeSamples = {\n");
    let grow = Vec3::splat(half_width_m);
    for (t, lo, hi) in samples {
        let _ = write!(s, "        {t}: [");
        push_vec3(&mut s, *lo - grow);
        s.push_str(", ");
        push_vec3(&mut s, *hi + grow);
        s.push_str("],\n");
    }
    s.push_str("    }\n    float[] widths = [");
    for (k, w) in look.widths_m.iter().enumerate() {
        if k > 0 {
            s.push_str(", ");
        }
        push_f32(&mut s, *w);
    }
    s.push_str("] (\n        interpolation = \"vertex\"\n    )\n");
    if let Some(colors) = look.colors {
        s.push_str("    color3f[] primvars:displayColor = [");
        for (k, c) in colors.iter().enumerate() {
            if k > 0 {
                s.push_str(", ");
            }
            push_vec3(&mut s, *c);
        }
        s.push_str("] (\n        interpolation = \"vertex\"\n    )\n");
    }
    s.push_str("}\n");
    s
}

/// `(x, y, z)`.
fn push_vec3(s: &mut String, v: Vec3) {
    s.push('(');
    push_f32(s, v.x);
    s.push_str(", ");
    push_f32(s, v.y);
    s.push_str(", ");
    push_f32(s, v.z);
    s.push(')');
}

/// `v` with the fewest digits that read back as `v`: plain decimals from 1e-4 to 1e7 (and 0),
/// exponent notation outside, so no number needs dozens of zeros.
fn push_f32(s: &mut String, v: f32) {
    let a = v.abs();
    let _ = if a == 0.0 || (1e-4..1e7).contains(&a) {
        write!(s, "{v}")
    } else {
        write!(s, "{v:e}")
    };
}

/// `text` as the inside of a USD string literal: backslashes, quotes and line breaks escaped.
fn escaped(text: &str) -> String {
    text.replace('\\', "\\\\")
        .replace('"', "\\\"")
        .replace('\n', "\\n")
        .replace('\r', "\\r")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_bit_for_bit() {
        // Decimal, exponent and boundary cases of push_f32's two notations.
        for v in [
            0.0f32,
            -0.0,
            1.0,
            0.1,
            -0.123_456_79,
            1e-4,
            9.999e-5,
            1.2e-9,
            f32::MIN_POSITIVE,
            1e7,
            f32::MAX,
        ] {
            let mut s = String::new();
            push_f32(&mut s, v);
            let back: f32 = s.parse().unwrap();
            assert_eq!(back.to_bits(), v.to_bits(), "{v} written as {s}");
            assert!(s.len() <= 15, "{v} written as {s}: {} characters", s.len());
        }
    }

    #[test]
    fn doc_text_is_escaped() {
        assert_eq!(escaped("a \"b\" \\ c\nd"), "a \\\"b\\\" \\\\ c\\nd");
    }
}
