//! Cem Yuksel's cyHair `.hair` format: strands as polylines with per-point thickness.
//!
//! Layout (little endian; `../shared/data/README.md`): a 128-byte header — `"HAIR"`,
//! `u32 hair_count`, `u32 point_count`, `u32 arrays` (bits: 1 segments, 2 points, 4 thickness,
//! 8 transparency, 16 colours), `u32 d_segments`, `f32 d_thickness`, `f32 d_transparency`,
//! `f32[3] d_color`, `char[88] info` — then each present array: `u16 segments[hair_count]`,
//! `f32 points[3·point_count]`, `f32 thickness[point_count]`, `f32
//! transparency[point_count]`, `f32 colors[3·point_count]`. A strand has `segments + 1`
//! points; a file without the segments array uses `d_segments` for every strand.
//!
//! wisp writes segments, points (metres, root first) and thickness (the fibre diameter in
//! metres: cyHair's thickness is a diameter). Reading is the groom reader's
//! (`crate::input::cyhair`, which owns the layout constants); [`read_hair`] wraps it so the
//! exporter's output can be checked.

use std::io::Write;
use std::path::{Path, PathBuf};

use glam::Vec3;

use crate::output::{OutputError, write_atomically};

pub use crate::input::cyhair::MAX_POINTS;
use crate::input::cyhair::{HAS_POINTS, HAS_SEGMENTS, HAS_THICKNESS, HEADER_BYTES, INFO_BYTES};

/// Strands read from or written to a `.hair` file.
#[derive(Clone, Debug, PartialEq)]
pub struct CyHair {
    /// Segments per strand (points − 1), one entry per strand.
    pub segments: Vec<u16>,
    /// Points of every strand in order, root first (the units of the file; wisp writes metres).
    pub points: Vec<Vec3>,
    /// Thickness (diameter) per point.
    pub thickness: Vec<f32>,
    /// The header's free-text field, up to 88 bytes.
    pub info: String,
}

/// Why a `.hair` file could not be written or read.
#[derive(Debug, thiserror::Error)]
pub enum CyHairError {
    #[error("{path}: {rule}")]
    Invalid { path: PathBuf, rule: String },
    #[error("{path}: cannot read: {source}")]
    Read {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error(transparent)]
    Write(#[from] OutputError),
}

/// Writes equally long strands (`points.len()` a multiple of `points_per_strand`, every point
/// finite) with one thickness for every point. Atomic: `<path>.tmp`, then rename.
pub fn write_hair(
    path: &Path,
    points: &[Vec3],
    points_per_strand: usize,
    thickness: f32,
    info: &str,
) -> Result<(), CyHairError> {
    check_strands(points, points_per_strand, thickness).map_err(|rule| CyHairError::Invalid {
        path: path.into(),
        rule,
    })?;
    let strands = points.len() / points_per_strand;
    let header = header(strands, points.len(), points_per_strand, thickness, info);
    write_atomically(path, |file| {
        let io = |error| OutputError::Io {
            path: path.into(),
            error,
        };
        let mut w = std::io::BufWriter::new(file);
        w.write_all(&header).map_err(io)?;
        let seg = ((points_per_strand - 1) as u16).to_le_bytes();
        for _ in 0..strands {
            w.write_all(&seg).map_err(io)?;
        }
        for p in points {
            for v in p.to_array() {
                w.write_all(&v.to_le_bytes()).map_err(io)?;
            }
        }
        let t = thickness.to_le_bytes();
        for _ in points {
            w.write_all(&t).map_err(io)?;
        }
        w.into_inner().map_err(|e| io(e.into_error()))
    })?;
    Ok(())
}

/// The rule `points` (strands of `points_per_strand`) and `thickness` break, if any: 2 to
/// 65,536 points a strand (the segment count is a `u16`), whole strands, at most
/// [`MAX_POINTS`], every point finite, a finite thickness ≥ 0.
fn check_strands(points: &[Vec3], points_per_strand: usize, thickness: f32) -> Result<(), String> {
    if !(2..=usize::from(u16::MAX) + 1).contains(&points_per_strand) {
        return Err(format!(
            "points per strand must be in [2, 65536] (got {points_per_strand})"
        ));
    }
    if !points.len().is_multiple_of(points_per_strand) || points.len() > MAX_POINTS as usize {
        return Err(format!(
            "{} points do not make whole strands of {points_per_strand} (or exceed {MAX_POINTS})",
            points.len()
        ));
    }
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(format!("point {i} is not finite ({})", points[i]));
    }
    if !(thickness.is_finite() && thickness >= 0.0) {
        return Err(format!(
            "thickness must be finite and >= 0 (got {thickness})"
        ));
    }
    Ok(())
}

/// The 128-byte header (module doc) of `strands` strands of `points_per_strand` points,
/// `points` in all, with segments, points and thickness present, the default thickness
/// `thickness`, transparency 0, colour white, and `info` cut to 87 bytes (NUL-terminated).
fn header(
    strands: usize,
    points: usize,
    points_per_strand: usize,
    thickness: f32,
    info: &str,
) -> Vec<u8> {
    let mut header = Vec::with_capacity(HEADER_BYTES);
    header.extend_from_slice(b"HAIR");
    for v in [
        strands as u32,
        points as u32,
        HAS_SEGMENTS | HAS_POINTS | HAS_THICKNESS,
        (points_per_strand - 1) as u32,
    ] {
        header.extend_from_slice(&v.to_le_bytes());
    }
    for v in [thickness, 0.0, 1.0, 1.0, 1.0] {
        header.extend_from_slice(&v.to_le_bytes());
    }
    let mut text = [0u8; INFO_BYTES];
    let info = info.as_bytes();
    let n = info.len().min(INFO_BYTES - 1);
    text[..n].copy_from_slice(&info[..n]);
    header.extend_from_slice(&text);
    debug_assert_eq!(header.len(), HEADER_BYTES);
    header
}

/// Reads a `.hair` file with the groom reader ([`crate::input::cyhair::parse_cyhair`]):
/// missing arrays take the header's defaults; a file without points, with counts that do not
/// add up, or shorter than its header says, is refused with the offset and rule it breaks.
pub fn read_hair(path: &Path) -> Result<CyHair, CyHairError> {
    let file = path.display().to_string();
    let bytes = crate::input::read_capped(
        path,
        crate::input::strands::MAX_STRAND_FILE_BYTES,
        "a cyHair file",
    )
    .map_err(|e| CyHairError::Invalid {
        path: path.into(),
        rule: e.to_string(),
    })?;
    let strands =
        crate::input::cyhair::parse_cyhair(&bytes, &file).map_err(|e| CyHairError::Invalid {
            path: path.into(),
            rule: e.to_string(),
        })?;
    Ok(CyHair {
        segments: strands
            .strand_points
            .iter()
            .map(|&p| (p - 1) as u16)
            .collect(),
        thickness: strands.thickness.unwrap_or_default(),
        points: strands.points,
        info: crate::input::cyhair::info_of(&bytes),
    })
}
