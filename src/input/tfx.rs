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
//! layout; counts are checked against the file size before the positions are allocated.

use super::strands::{Bytes, StrandFile, StrandFileError};

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
    if bytes.len() < header {
        return Err(r.malformed(
            bytes.len() as u64,
            format!(
                "the file ends after {} bytes, inside the {header}-byte header of a version {version} .tfx file",
                bytes.len()
            ),
        ));
    }
    let strands = r.u32_at(4, "numHairStrands")?;
    let per = r.u32_at(8, "numVerticesPerStrand")?;
    if strands == 0 {
        return Err(r.malformed(4, "numHairStrands must be at least 1 (got 0)"));
    }
    if !(2..=MAX_VERTICES_PER_STRAND).contains(&per) {
        return Err(r.malformed(
            8,
            format!("numVerticesPerStrand must be in [2, {MAX_VERTICES_PER_STRAND}] (got {per})"),
        ));
    }
    let offset = match r.u32_at(at_offset, "vertex position offset")? {
        0 => header as u32,
        o if (o as usize) < header => {
            return Err(r.malformed(
                at_offset as u64,
                format!("the vertex position offset {o} points inside the {header}-byte header"),
            ));
        }
        o => o,
    };
    let count = strands as u64 * per as u64;
    r.check_array(offset as u64, count, stride as u64, "vertex positions")?;
    let points = r.points(offset as usize, count as usize, stride, "vertex")?;
    Ok(StrandFile {
        points,
        strand_points: vec![per; strands as usize],
        thickness: None,
        colors: None,
    })
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
