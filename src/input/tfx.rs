//! AMD TressFX `.tfx` strand files, the 3.x and 4.x layouts (little endian).
//!
//! - 3.x (the shared ponytail, version 3.0): a 296-byte header — `f32 version`,
//!   `u32 numGuideHairStrands`, `u32 numVerticesPerStrand`, `u32 followPerGuide`,
//!   `u32 bothEndsImmovable`, `u32 reserved[31]`, then six `u32` offsets (vertices, thickness,
//!   strand UV, vertex colour, guide, vertex UV) at byte 144 and `u32 reserved[32]`. Positions
//!   are `f32[3]` per vertex at the vertices offset (0 means right after the header).
//! - 4.x (version 4.0 and later): a 160-byte header — `f32 version`, `u32 numHairStrands`,
//!   `u32 numVerticesPerStrand`, then `u32` offsets of the vertex positions, strand UV, vertex
//!   UV, strand thickness and vertex colour, and `u32 reserved[32]`. Positions are `f32[4]`
//!   (x, y, z and an inverse mass, ignored) per vertex.
//!
//! Every strand has `numVerticesPerStrand` vertices, root first. The version field picks the
//! layout; the strand count is checked against the most a groom may have, and the counts
//! against the file size, from the header alone (`check_tfx_header`, before the body is read).

use super::strands::{Bytes, StrandFile, StrandFileError};
use crate::hairstyle::MAX_STRANDS;

/// Size of the 3.x header in bytes.
pub const HEADER_3_BYTES: usize = 296;
/// Size of the 4.x header in bytes.
pub const HEADER_4_BYTES: usize = 160;
/// Byte offset of the 3.x vertices offset (after version, 4 counts and `reserved[31]`).
const OFFSET_3_VERTICES: usize = 4 * 5 + 4 * 31;
/// Byte offset of the 4.x vertex-position offset.
const OFFSET_4_VERTICES: usize = 12;
/// Most vertices per strand accepted (TressFX itself uses 4 to 64).
pub const MAX_VERTICES_PER_STRAND: u32 = 4096;

/// Parses a `.tfx` file's bytes; `file` names it in errors.
pub fn parse_tfx(bytes: &[u8], file: &str) -> Result<StrandFile, StrandFileError> {
    let r = Bytes { bytes, file };
    let h = Header::read(&r, bytes.len() as u64)?;
    let count = h.strands as u64 * h.per as u64;
    let points = r.points(h.offset as usize, count as usize, h.stride, "vertex")?;
    Ok(StrandFile {
        points,
        strand_points: vec![h.per; h.strands as usize],
        thickness: None,
        colors: None,
    })
}

/// Checks the header of a `.tfx` file of `file_len` bytes from its first bytes `head` (at
/// least the header, or the whole file): the counts against the caps and the file's size, so
/// a file that declares more than a groom may hold is refused before its body is read.
pub fn check_tfx_header(head: &[u8], file_len: u64, file: &str) -> Result<(), StrandFileError> {
    Header::read(&Bytes { bytes: head, file }, file_len).map(|_| ())
}

/// The header fields the reader uses, checked.
struct Header {
    strands: u32,
    per: u32,
    /// Byte offset of the vertex positions.
    offset: u32,
    /// Bytes per vertex position (12 in 3.x, 16 in 4.x).
    stride: usize,
}

impl Header {
    /// Reads the header from `r` (the file's first bytes at least) of a file of `file_len`
    /// bytes: the version, at least 1 and at most [`MAX_STRANDS`] strands (the most a groom
    /// may have), 2 to [`MAX_VERTICES_PER_STRAND`] vertices each, and the positions inside the
    /// file.
    fn read(r: &Bytes, file_len: u64) -> Result<Header, StrandFileError> {
        let version = r.f32_at(0, "version")?;
        if !(version.is_finite() && (1.0..100.0).contains(&version)) {
            return Err(r.malformed(
                0,
                format!("version must be a TressFX version number in [1, 100) (got {version}): not a .tfx file?"),
            ));
        }
        let (header, at_offset, stride) = if version < 4.0 {
            (HEADER_3_BYTES, OFFSET_3_VERTICES, 12)
        } else {
            (HEADER_4_BYTES, OFFSET_4_VERTICES, 16)
        };
        if file_len < header as u64 || r.bytes.len() < header {
            return Err(r.malformed(
                file_len,
                format!(
                    "the file ends after {file_len} bytes, inside the {header}-byte header of a version {version} .tfx file"
                ),
            ));
        }
        let strands = r.u32_at(4, "numHairStrands")?;
        let per = r.u32_at(8, "numVerticesPerStrand")?;
        if strands == 0 {
            return Err(r.malformed(4, "numHairStrands must be at least 1 (got 0)"));
        }
        if strands as u64 > MAX_STRANDS {
            return Err(r.malformed(
                4,
                format!("numHairStrands {strands} is over the limit of {MAX_STRANDS} strands a groom may have"),
            ));
        }
        if !(2..=MAX_VERTICES_PER_STRAND).contains(&per) {
            return Err(r.malformed(
                8,
                format!(
                    "numVerticesPerStrand must be in [2, {MAX_VERTICES_PER_STRAND}] (got {per})"
                ),
            ));
        }
        let offset = match r.u32_at(at_offset, "vertex position offset")? {
            0 => header as u32,
            o if (o as usize) < header => {
                return Err(r.malformed(
                    at_offset as u64,
                    format!(
                        "the vertex position offset {o} points inside the {header}-byte header"
                    ),
                ));
            }
            o => o,
        };
        let count = strands as u64 * per as u64;
        r.check_array_within(
            file_len,
            offset as u64,
            count,
            stride as u64,
            "vertex positions",
        )?;
        Ok(Header {
            strands,
            per,
            offset,
            stride,
        })
    }
}

/// Bytes of a version 3.0 `.tfx` file holding `strands` (each of the same vertex count,
/// positions right after the header): a writer for tests and examples.
pub fn encode_tfx3(strands: &[Vec<glam::Vec3>]) -> Vec<u8> {
    let per = strands.first().map_or(0, |s| s.len()) as u32;
    let mut out = vec![0u8; HEADER_3_BYTES];
    out[0..4].copy_from_slice(&3.0f32.to_le_bytes());
    out[4..8].copy_from_slice(&(strands.len() as u32).to_le_bytes());
    out[8..12].copy_from_slice(&per.to_le_bytes());
    out[OFFSET_3_VERTICES..OFFSET_3_VERTICES + 4]
        .copy_from_slice(&(HEADER_3_BYTES as u32).to_le_bytes());
    for p in strands.iter().flatten() {
        for v in p.to_array() {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    out
}

/// Bytes of a version 4.0 `.tfx` file (FLOAT4 positions, inverse mass 1 except 0 at roots).
pub fn encode_tfx4(strands: &[Vec<glam::Vec3>]) -> Vec<u8> {
    let per = strands.first().map_or(0, |s| s.len()) as u32;
    let mut out = vec![0u8; HEADER_4_BYTES];
    out[0..4].copy_from_slice(&4.0f32.to_le_bytes());
    out[4..8].copy_from_slice(&(strands.len() as u32).to_le_bytes());
    out[8..12].copy_from_slice(&per.to_le_bytes());
    out[12..16].copy_from_slice(&(HEADER_4_BYTES as u32).to_le_bytes());
    for s in strands {
        for (i, p) in s.iter().enumerate() {
            for v in p.to_array() {
                out.extend_from_slice(&v.to_le_bytes());
            }
            let inv_mass: f32 = if i == 0 { 0.0 } else { 1.0 };
            out.extend_from_slice(&inv_mass.to_le_bytes());
        }
    }
    out
}
