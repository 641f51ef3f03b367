//! Cem Yuksel's cyHair `.hair` strand files (little endian), read defensively.
//!
//! Layout (`../shared/data/README.md`, and the format's public description on Yuksel's hair
//! model page): a 128-byte header — `"HAIR"`, `u32 hair_count`, `u32 point_count`,
//! `u32 arrays` (bits: 1 segments, 2 points, 4 thickness, 8 transparency, 16 colours),
//! `u32 d_segments`, `f32 d_thickness`, `f32 d_transparency`, `f32[3] d_color`, `char[88]
//! info` — then each present array in this order: `u16 segments[hair_count]`,
//! `f32 points[3·point_count]`, `f32 thickness[point_count]`, `f32 transparency[point_count]`,
//! `f32 colors[3·point_count]`. A strand has `segments + 1` points; a file without the
//! segments array uses `d_segments` for every strand; missing arrays take the header's
//! defaults. The writer is `crate::export::cyhair`, which shares these constants.
//!
//! The sizes of all present arrays are added up (in u64, so a hostile count cannot overflow)
//! and compared with the file size before any array is allocated.

use super::strands::{Bytes, StrandFile, StrandFileError};
use glam::Vec3;

/// Size of the header in bytes.
pub const HEADER_BYTES: usize = 128;
/// Size of the header's free-text `info` field, the header's last 88 bytes.
pub const INFO_BYTES: usize = 88;
/// Bits of the header's `arrays` field.
pub const HAS_SEGMENTS: u32 = 1;
pub const HAS_POINTS: u32 = 2;
pub const HAS_THICKNESS: u32 = 4;
pub const HAS_TRANSPARENCY: u32 = 8;
pub const HAS_COLORS: u32 = 16;
/// Most points a file may declare: refuses a hostile header before anything is allocated.
pub const MAX_POINTS: u32 = 100_000_000;

/// The header's free text (up to the first NUL), for a file at least a header long.
pub fn info_of(bytes: &[u8]) -> String {
    let info = bytes
        .get(HEADER_BYTES - INFO_BYTES..HEADER_BYTES)
        .unwrap_or(&[]);
    let end = info.iter().position(|b| *b == 0).unwrap_or(info.len());
    String::from_utf8_lossy(&info[..end]).into_owned()
}

/// Parses a `.hair` file's bytes; `file` names it in errors.
pub fn parse_cyhair(bytes: &[u8], file: &str) -> Result<StrandFile, StrandFileError> {
    let r = Bytes { bytes, file };
    if bytes.len() < HEADER_BYTES {
        return Err(r.malformed(
            bytes.len() as u64,
            format!(
                "the file ends after {} bytes, inside the {HEADER_BYTES}-byte cyHair header",
                bytes.len()
            ),
        ));
    }
    if &bytes[..4] != b"HAIR" {
        return Err(r.malformed(0, "a cyHair file starts with the signature \"HAIR\""));
    }
    let hairs = r.u32_at(4, "hair_count")?;
    let pts = r.u32_at(8, "point_count")?;
    let arrays = r.u32_at(12, "arrays")?;
    let d_segments = r.u32_at(16, "d_segments")?;
    let d_thickness = r.f32_at(20, "d_thickness")?;
    let d_color = Vec3::new(
        r.f32_at(28, "d_color")?,
        r.f32_at(32, "d_color")?,
        r.f32_at(36, "d_color")?,
    );
    if arrays & HAS_POINTS == 0 {
        return Err(r.malformed(
            12,
            format!("arrays = {arrays:#x} has no points array (bit 2): the file holds no strands"),
        ));
    }
    if hairs == 0 {
        return Err(r.malformed(4, "hair_count must be at least 1 (got 0)"));
    }
    if pts > MAX_POINTS {
        return Err(r.malformed(
            8,
            format!("point_count {pts} is over the limit of {MAX_POINTS} points"),
        ));
    }
    let (h, n) = (hairs as u64, pts as u64);
    let mut need = HEADER_BYTES as u64 + 12 * n;
    for (bit, size) in [
        (HAS_SEGMENTS, 2 * h),
        (HAS_THICKNESS, 4 * n),
        (HAS_TRANSPARENCY, 4 * n),
        (HAS_COLORS, 12 * n),
    ] {
        if arrays & bit != 0 {
            need += size;
        }
    }
    if (bytes.len() as u64) < need {
        return Err(r.malformed(
            bytes.len() as u64,
            format!(
                "the file has {} bytes, but the header announces {need} ({hairs} strands, {pts} points, arrays {arrays:#x})",
                bytes.len()
            ),
        ));
    }
    // From here every array lies inside the file.
    let mut at = HEADER_BYTES;
    let strand_points: Vec<u32> = if arrays & HAS_SEGMENTS != 0 {
        let s = bytes[at..at + 2 * hairs as usize]
            .chunks_exact(2)
            .map(|b| u32::from(u16::from_le_bytes([b[0], b[1]])) + 1)
            .collect();
        at += 2 * hairs as usize;
        s
    } else {
        if d_segments > u32::from(u16::MAX) {
            return Err(r.malformed(
                16,
                format!("d_segments {d_segments} is over 65535 (segments are u16)"),
            ));
        }
        vec![d_segments + 1; hairs as usize]
    };
    let total: u64 = strand_points.iter().map(|&p| p as u64).sum();
    if total != n {
        return Err(r.malformed(
            if arrays & HAS_SEGMENTS != 0 { HEADER_BYTES as u64 } else { 16 },
            format!("the strands' segments + 1 add up to {total} points, the header says point_count {pts}"),
        ));
    }
    let points = r.points(at, pts as usize, 12, "point")?;
    at += 12 * pts as usize;
    let finite = |vals: &[f32], start: usize, what: &str| -> Result<(), StrandFileError> {
        match vals.iter().position(|v| !v.is_finite() || *v < 0.0) {
            Some(i) => Err(r.malformed(
                (start + 4 * i) as u64,
                format!(
                    "{what} of point {i} must be a finite number >= 0 (got {})",
                    vals[i]
                ),
            )),
            None => Ok(()),
        }
    };
    let thickness = if arrays & HAS_THICKNESS != 0 {
        let t = r.floats(at, pts as usize);
        finite(&t, at, "thickness")?;
        at += 4 * pts as usize;
        t
    } else {
        if !(d_thickness.is_finite() && d_thickness >= 0.0) {
            return Err(r.malformed(
                20,
                format!("d_thickness must be a finite number >= 0 (got {d_thickness})"),
            ));
        }
        vec![d_thickness; pts as usize]
    };
    if arrays & HAS_TRANSPARENCY != 0 {
        finite(&r.floats(at, pts as usize), at, "transparency")?;
        at += 4 * pts as usize;
    }
    let colors = if arrays & HAS_COLORS != 0 {
        Some(r.points(at, pts as usize, 12, "colour")?)
    } else if d_color.is_finite() {
        Some(vec![d_color; pts as usize])
    } else {
        None
    };
    Ok(StrandFile {
        points,
        strand_points,
        thickness: Some(thickness),
        colors,
    })
}
