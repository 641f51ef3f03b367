//! Captured hair strands read from a file: the common result of the groom readers
//! ([`super::tfx`], [`super::cyhair`], [`super::ply`], [`super::hairsalon`]) and their typed
//! error.
//!
//! Every reader checks each count in a header against the file's size before it allocates
//! (a header may declare 4 billion strands in a 300-byte file), refuses non-finite
//! coordinates, and names the file, the byte offset (the element, for PLY) and the rule in its
//! error. Strands are
//! kept as the file has them (units and axes of the file, root first); zero-length strands are
//! kept too (they are not malformed) and dropped later by the groom builder, which counts them.

use super::ReadError;
use glam::Vec3;

/// Largest strand file read, in bytes (1 GB: 50,000 strands of 100 points are 60 MB).
pub const MAX_STRAND_FILE_BYTES: u64 = 1 << 30;

/// Strands as a file holds them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StrandFile {
    /// Points of every strand, root first, strand after strand (the file's units and axes).
    pub points: Vec<Vec3>,
    /// Number of points of each strand (sums to `points.len()`).
    pub strand_points: Vec<u32>,
    /// Thickness (diameter) per point in the file's units, when the file has it.
    pub thickness: Option<Vec<f32>>,
    /// Linear RGB colour per point, when the file has it.
    pub colors: Option<Vec<Vec3>>,
}

impl StrandFile {
    pub fn strand_count(&self) -> usize {
        self.strand_points.len()
    }
    /// The points of each strand, in order.
    pub fn strands(&self) -> impl Iterator<Item = &[Vec3]> + '_ {
        let mut at = 0usize;
        self.strand_points.iter().map(move |&n| {
            let s = &self.points[at..at + n as usize];
            at += n as usize;
            s
        })
    }
}

/// Why a strand file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum StrandFileError {
    /// The file could not be read (missing, not a regular file, over the size cap).
    #[error("{file}: {error}")]
    Io { file: String, error: ReadError },
    /// The bytes break a rule of the format at `offset`.
    #[error("{file}: byte {offset}: {rule}")]
    Malformed {
        file: String,
        offset: u64,
        rule: String,
    },
    /// A PLY file whose header the PLY reader refuses (`rule` is its message).
    #[error("{file}: not a PLY file wisp can read: {rule}")]
    PlyHeader { file: String, rule: String },
    /// A PLY file whose `element` (as the header names it) breaks `rule`.
    #[error("{file}: PLY element `{element}`: {rule}")]
    Ply {
        file: String,
        element: String,
        rule: String,
    },
    /// None of the strand formats (by extension or by the `HAIR` and `ply` signatures).
    #[error(
        "{file}: not a strand file: expected a TressFX `.tfx`, a cyHair `.hair`, a PLY `.ply` or a USC-HairSalon `.data` file"
    )]
    UnknownFormat { file: String },
}

/// Little-endian reads that fail with the offset and the field being read.
pub(crate) struct Bytes<'a> {
    pub bytes: &'a [u8],
    pub file: &'a str,
}

impl Bytes<'_> {
    pub fn malformed(&self, offset: u64, rule: impl Into<String>) -> StrandFileError {
        StrandFileError::Malformed {
            file: self.file.to_string(),
            offset,
            rule: rule.into(),
        }
    }
    pub fn u32_at(&self, offset: usize, field: &str) -> Result<u32, StrandFileError> {
        match self.bytes.get(offset..offset + 4) {
            Some(b) => Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            None => Err(self.malformed(
                offset as u64,
                format!(
                    "the file ends ({} bytes) inside the header field `{field}`",
                    self.bytes.len()
                ),
            )),
        }
    }
    pub fn f32_at(&self, offset: usize, field: &str) -> Result<f32, StrandFileError> {
        self.u32_at(offset, field).map(f32::from_bits)
    }
    /// Checks that `count` items of `item_bytes` starting at `offset` lie inside the file,
    /// without overflow; `what` names the array.
    pub fn check_array(
        &self,
        offset: u64,
        count: u64,
        item_bytes: u64,
        what: &str,
    ) -> Result<(), StrandFileError> {
        self.check_array_within(self.bytes.len() as u64, offset, count, item_bytes, what)
    }
    /// [`Self::check_array`] in a file of `len` bytes, of which `self.bytes` may hold only the
    /// first (a header checked before the body is read).
    pub fn check_array_within(
        &self,
        len: u64,
        offset: u64,
        count: u64,
        item_bytes: u64,
        what: &str,
    ) -> Result<(), StrandFileError> {
        let end = count
            .checked_mul(item_bytes)
            .and_then(|b| b.checked_add(offset));
        match end {
            Some(end) if end <= len => Ok(()),
            _ => Err(self.malformed(
                offset,
                format!(
                    "{what}: {count} items of {item_bytes} bytes from byte {offset} need more than the file's {len} bytes"
                ),
            )),
        }
    }
    /// Reads `count` finite 3-vectors with a stride of `stride` bytes from `offset` (the
    /// range must have been checked).
    pub fn points(
        &self,
        offset: usize,
        count: usize,
        stride: usize,
        what: &str,
    ) -> Result<Vec<Vec3>, StrandFileError> {
        let mut out = Vec::with_capacity(count);
        for i in 0..count {
            let at = offset + i * stride;
            let b = &self.bytes[at..at + 12];
            let f = |k: usize| f32::from_le_bytes([b[k], b[k + 1], b[k + 2], b[k + 3]]);
            let p = Vec3::new(f(0), f(4), f(8));
            if !p.is_finite() {
                return Err(self.malformed(
                    at as u64,
                    format!("{what} {i} is not finite ({p}): every coordinate must be a number"),
                ));
            }
            out.push(p);
        }
        Ok(out)
    }
    /// Reads `count` f32 from `offset` (range checked by the caller).
    pub fn floats(&self, offset: usize, count: usize) -> Vec<f32> {
        self.bytes[offset..offset + 4 * count]
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect()
    }
}
