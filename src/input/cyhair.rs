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
//! The strand count is checked against the most a groom may have, and the sizes of all
//! present arrays are added up (in u64, so a hostile count cannot overflow) and compared with
//! the file size, from the header alone (`check_cyhair_header`, before the body is read).

use super::strands::{Bytes, StrandFile, StrandFileError};
use crate::hairstyle::MAX_STRANDS;
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
    let h = Header::read(&r)?;
    h.check_file_size(&r, bytes.len() as u64)?;
    // From here every array lies inside the file.
    let pts = h.points as usize;
    let mut at = HEADER_BYTES;
    let strand_points = h.strand_points(&r, &mut at)?;
    let points = r.points(at, pts, 12, "point")?;
    at += 12 * pts;
    let thickness = if h.arrays & HAS_THICKNESS != 0 {
        let t = r.floats(at, pts);
        check_non_negative(&r, &t, at, "thickness")?;
        at += 4 * pts;
        t
    } else {
        if !(h.d_thickness.is_finite() && h.d_thickness >= 0.0) {
            return Err(r.malformed(
                20,
                format!(
                    "d_thickness must be a finite number >= 0 (got {})",
                    h.d_thickness
                ),
            ));
        }
        vec![h.d_thickness; pts]
    };
    if h.arrays & HAS_TRANSPARENCY != 0 {
        check_non_negative(&r, &r.floats(at, pts), at, "transparency")?;
        at += 4 * pts;
    }
    let colors = if h.arrays & HAS_COLORS != 0 {
        Some(r.points(at, pts, 12, "colour")?)
    } else if h.d_color.is_finite() {
        Some(vec![h.d_color; pts])
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

/// Checks the header of a `.hair` file of `file_len` bytes from its first bytes `head` (at
/// least the header, or the whole file): the counts against the caps and the file's size, so
/// a file that declares more than a groom may hold is refused before its body is read.
pub fn check_cyhair_header(head: &[u8], file_len: u64, file: &str) -> Result<(), StrandFileError> {
    let r = Bytes { bytes: head, file };
    Header::read(&r)?.check_file_size(&r, file_len)
}

/// The header fields the reader uses.
struct Header {
    hairs: u32,
    points: u32,
    arrays: u32,
    d_segments: u32,
    d_thickness: f32,
    d_color: Vec3,
}

impl Header {
    /// Reads the header and checks its counts: the signature, a points array, at least one
    /// strand and at most [`MAX_POINTS`] points.
    fn read(r: &Bytes) -> Result<Self, StrandFileError> {
        let bytes = r.bytes;
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
        let h = Header {
            hairs: r.u32_at(4, "hair_count")?,
            points: r.u32_at(8, "point_count")?,
            arrays: r.u32_at(12, "arrays")?,
            d_segments: r.u32_at(16, "d_segments")?,
            d_thickness: r.f32_at(20, "d_thickness")?,
            d_color: Vec3::new(
                r.f32_at(28, "d_color")?,
                r.f32_at(32, "d_color")?,
                r.f32_at(36, "d_color")?,
            ),
        };
        if h.arrays & HAS_POINTS == 0 {
            return Err(r.malformed(
                12,
                format!(
                    "arrays = {:#x} has no points array (bit 2): the file holds no strands",
                    h.arrays
                ),
            ));
        }
        if h.hairs == 0 {
            return Err(r.malformed(4, "hair_count must be at least 1 (got 0)"));
        }
        if h.hairs as u64 > MAX_STRANDS {
            return Err(r.malformed(
                4,
                format!(
                    "hair_count {} is over the limit of {MAX_STRANDS} strands a groom may have",
                    h.hairs
                ),
            ));
        }
        if h.points > MAX_POINTS {
            return Err(r.malformed(
                8,
                format!(
                    "point_count {} is over the limit of {MAX_POINTS} points",
                    h.points
                ),
            ));
        }
        Ok(h)
    }

    /// Refuses a file of `len` bytes shorter than the header and the arrays it announces
    /// (sizes added in u64, so no count can overflow).
    fn check_file_size(&self, r: &Bytes, len: u64) -> Result<(), StrandFileError> {
        let (h, n) = (self.hairs as u64, self.points as u64);
        let mut need = HEADER_BYTES as u64 + 12 * n;
        for (bit, size) in [
            (HAS_SEGMENTS, 2 * h),
            (HAS_THICKNESS, 4 * n),
            (HAS_TRANSPARENCY, 4 * n),
            (HAS_COLORS, 12 * n),
        ] {
            if self.arrays & bit != 0 {
                need += size;
            }
        }
        if len < need {
            return Err(r.malformed(
                len,
                format!(
                    "the file has {len} bytes, but the header announces {need} ({} strands, {} points, arrays {:#x})",
                    self.hairs,
                    self.points,
                    self.arrays
                ),
            ));
        }
        Ok(())
    }

    /// Points per strand: `segments + 1` from the segments array at `*at` (moved past it), or
    /// `d_segments + 1` for every strand; they must add up to `point_count`.
    fn strand_points(&self, r: &Bytes, at: &mut usize) -> Result<Vec<u32>, StrandFileError> {
        let hairs = self.hairs as usize;
        let has_segments = self.arrays & HAS_SEGMENTS != 0;
        let strand_points: Vec<u32> = if has_segments {
            let s = r.bytes[*at..*at + 2 * hairs]
                .chunks_exact(2)
                .map(|b| u32::from(u16::from_le_bytes([b[0], b[1]])) + 1)
                .collect();
            *at += 2 * hairs;
            s
        } else {
            if self.d_segments > u32::from(u16::MAX) {
                return Err(r.malformed(
                    16,
                    format!(
                        "d_segments {} is over 65535 (segments are u16)",
                        self.d_segments
                    ),
                ));
            }
            vec![self.d_segments + 1; hairs]
        };
        let total: u64 = strand_points.iter().map(|&p| p as u64).sum();
        if total != self.points as u64 {
            return Err(r.malformed(
                if has_segments { HEADER_BYTES as u64 } else { 16 },
                format!(
                    "the strands' segments + 1 add up to {total} points, the header says point_count {}",
                    self.points
                ),
            ));
        }
        Ok(strand_points)
    }
}

/// Refuses a value of the per-point array `vals` (at byte `start`, named `what`) that is not
/// a finite number >= 0.
fn check_non_negative(
    r: &Bytes,
    vals: &[f32],
    start: usize,
    what: &str,
) -> Result<(), StrandFileError> {
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
}
