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
//! metres: cyHair's thickness is a diameter); it reads any file of this layout, so the
//! exporter's output can be checked and real `.hair` models loaded.

use std::io::Write;
use std::path::{Path, PathBuf};

use glam::Vec3;

use crate::output::{OutputError, write_atomically};

const HEADER_BYTES: usize = 128;
const INFO_BYTES: usize = 88;
const HAS_SEGMENTS: u32 = 1;
const HAS_POINTS: u32 = 2;
const HAS_THICKNESS: u32 = 4;
const HAS_TRANSPARENCY: u32 = 8;
const HAS_COLORS: u32 = 16;
/// Most points a file may declare: refuses a hostile header before anything is allocated.
pub const MAX_POINTS: u32 = 100_000_000;

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
    let invalid = |rule: String| CyHairError::Invalid {
        path: path.into(),
        rule,
    };
    if !(2..=usize::from(u16::MAX) + 1).contains(&points_per_strand) {
        return Err(invalid(format!(
            "points per strand must be in [2, 65536] (got {points_per_strand})"
        )));
    }
    if !points.len().is_multiple_of(points_per_strand) || points.len() > MAX_POINTS as usize {
        return Err(invalid(format!(
            "{} points do not make whole strands of {points_per_strand} (or exceed {MAX_POINTS})",
            points.len()
        )));
    }
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(invalid(format!("point {i} is not finite ({})", points[i])));
    }
    if !(thickness.is_finite() && thickness >= 0.0) {
        return Err(invalid(format!(
            "thickness must be finite and >= 0 (got {thickness})"
        )));
    }
    let strands = points.len() / points_per_strand;
    let mut header = Vec::with_capacity(HEADER_BYTES);
    header.extend_from_slice(b"HAIR");
    for v in [
        strands as u32,
        points.len() as u32,
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

/// Reads a `.hair` file; missing arrays take the header's defaults (`d_segments`,
/// `d_thickness`). A file without points, with counts that do not add up, or shorter than
/// its header says, is refused with the rule it breaks.
pub fn read_hair(path: &Path) -> Result<CyHair, CyHairError> {
    let bytes = std::fs::read(path).map_err(|source| CyHairError::Read {
        path: path.into(),
        source,
    })?;
    let invalid = |rule: String| CyHairError::Invalid {
        path: path.into(),
        rule,
    };
    if bytes.len() < HEADER_BYTES || &bytes[..4] != b"HAIR" {
        return Err(invalid(
            "not a cyHair file (no 128-byte header starting with \"HAIR\")".into(),
        ));
    }
    let u32_at =
        |o: usize| u32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]);
    let f32_at = |o: usize| f32::from_bits(u32_at(o));
    let (hair_count, point_count, arrays, d_segments) =
        (u32_at(4), u32_at(8), u32_at(12), u32_at(16));
    let d_thickness = f32_at(20);
    if arrays & HAS_POINTS == 0 {
        return Err(invalid("the file has no points array".into()));
    }
    if point_count > MAX_POINTS || hair_count > point_count {
        return Err(invalid(format!(
            "{hair_count} strands and {point_count} points: at most {MAX_POINTS} points and \
             no more strands than points"
        )));
    }
    let (hairs, pts) = (hair_count as usize, point_count as usize);
    let mut need = HEADER_BYTES + 12 * pts;
    for (bit, per_item) in [
        (HAS_SEGMENTS, 2 * hairs),
        (HAS_THICKNESS, 4 * pts),
        (HAS_TRANSPARENCY, 4 * pts),
        (HAS_COLORS, 12 * pts),
    ] {
        if arrays & bit != 0 {
            need += per_item;
        }
    }
    if bytes.len() < need {
        return Err(invalid(format!(
            "{} bytes, but the header announces {need}",
            bytes.len()
        )));
    }
    let mut at = HEADER_BYTES;
    let segments: Vec<u16> = if arrays & HAS_SEGMENTS != 0 {
        let s = bytes[at..at + 2 * hairs]
            .chunks_exact(2)
            .map(|b| u16::from_le_bytes([b[0], b[1]]))
            .collect();
        at += 2 * hairs;
        s
    } else {
        let d = u16::try_from(d_segments)
            .map_err(|_| invalid(format!("d_segments {d_segments} exceeds 65535")))?;
        vec![d; hairs]
    };
    let total: usize = segments.iter().map(|s| usize::from(*s) + 1).sum();
    if total != pts {
        return Err(invalid(format!(
            "the strands' segments + 1 add up to {total} points, the header says {pts}"
        )));
    }
    let points: Vec<Vec3> = bytes[at..at + 12 * pts]
        .chunks_exact(12)
        .map(|b| {
            let f = |k: usize| f32::from_le_bytes([b[k], b[k + 1], b[k + 2], b[k + 3]]);
            Vec3::new(f(0), f(4), f(8))
        })
        .collect();
    at += 12 * pts;
    let thickness = if arrays & HAS_THICKNESS != 0 {
        bytes[at..at + 4 * pts]
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect()
    } else {
        vec![d_thickness; pts]
    };
    let info_bytes = &bytes[40..HEADER_BYTES];
    let end = info_bytes
        .iter()
        .position(|b| *b == 0)
        .unwrap_or(INFO_BYTES);
    Ok(CyHair {
        segments,
        points,
        thickness,
        info: String::from_utf8_lossy(&info_bytes[..end]).into_owned(),
    })
}
