//! One record: the guide state of one frame as bytes, and back.
//!
//! A record stores what rendering reads of a [`SimState`](crate::sim::SimState): its
//! `positions`, bit for bit, with the frame's time (see the module doc of [`super`] for why
//! that is enough). It reads no other field of the simulation's state, so the simulation's
//! internals can change without touching the format; a new field that rendering needs would
//! be a new format version.

use super::format::{CHECKSUM_BYTES, POSITION_BYTES, TIME_BYTES, record_bytes};
use glam::Vec3;

/// Writes record `index` (time and positions, checksum last) into `out`, replacing its
/// contents.
pub(super) fn encode(index: u64, time_s: f64, positions: &[Vec3], out: &mut Vec<u8>) {
    out.clear();
    out.reserve(record_bytes(positions.len() as u64) as usize);
    out.extend_from_slice(&time_s.to_le_bytes());
    for p in positions {
        out.extend_from_slice(&p.x.to_le_bytes());
        out.extend_from_slice(&p.y.to_le_bytes());
        out.extend_from_slice(&p.z.to_le_bytes());
    }
    let crc = checksum(index, out);
    out.extend_from_slice(&crc.to_le_bytes());
}

/// Why a record's bytes were refused.
#[derive(Debug, PartialEq)]
pub(super) enum RecordError {
    /// The stored checksum (first) differs from the bytes' (second).
    Checksum(u32, u32),
    /// Particle `index` has a coordinate that is not a finite number.
    NotFinite(usize, Vec3),
}

/// Reads a record's time and positions (into `positions`, one per 12 bytes) after checking
/// its checksum and that every coordinate is finite. `bytes` is one whole record.
pub(super) fn decode(
    index: u64,
    bytes: &[u8],
    positions: &mut Vec<Vec3>,
) -> Result<f64, RecordError> {
    let body_len = bytes.len().saturating_sub(CHECKSUM_BYTES);
    let (body, tail) = bytes.split_at(body_len);
    let stored = u32::from_le_bytes(tail.try_into().unwrap_or([0; 4]));
    let actual = checksum(index, body);
    if stored != actual {
        return Err(RecordError::Checksum(stored, actual));
    }
    let (time, coords) = body.split_at(TIME_BYTES.min(body.len()));
    let time_s = f64::from_le_bytes(time.try_into().unwrap_or([0; 8]));
    positions.clear();
    for (i, c) in coords.chunks_exact(POSITION_BYTES).enumerate() {
        let f = |k: usize| f32::from_le_bytes([c[k], c[k + 1], c[k + 2], c[k + 3]]);
        let p = Vec3::new(f(0), f(4), f(8));
        if !p.is_finite() {
            return Err(RecordError::NotFinite(i, p));
        }
        positions.push(p);
    }
    Ok(time_s)
}

/// CRC-32 of the record index (u64) followed by `body`: a record copied to another place in
/// the file fails its check.
fn checksum(index: u64, body: &[u8]) -> u32 {
    let mut h = crc32fast::Hasher::new();
    h.update(&index.to_le_bytes());
    h.update(body);
    h.finalize()
}

#[cfg(test)]
mod tests;
