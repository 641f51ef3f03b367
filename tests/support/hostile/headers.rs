//! Strand files whose header declares more strands than a groom may have
//! (`wisp::hairstyle::MAX_STRANDS`), one generator per format, with a body as large as the
//! header says (so only the cap can refuse them) left as a hole in a sparse file: the file is
//! as long as the header claims, yet costs nothing to write. A loader that reads the body
//! before it checks the header reads up to a gigabyte of zeros.

use super::Rng;
use std::path::{Path, PathBuf};
use wisp::hairstyle::MAX_STRANDS;
use wisp::input::strands::MAX_STRAND_FILE_BYTES;

/// One file: its name (the extension picks the reader), its header bytes and its length.
pub struct Oversize {
    pub name: String,
    pub head: Vec<u8>,
    pub len: u64,
    /// The strands the header declares.
    pub strands: u64,
}

impl Oversize {
    /// Writes the file into `dir` as its header followed by a hole up to its length.
    pub fn write(&self, dir: &Path) -> std::io::Result<PathBuf> {
        let path = dir.join(&self.name);
        let file = std::fs::File::create(&path)?;
        std::io::Write::write_all(&mut &file, &self.head)?;
        file.set_len(self.len)?;
        Ok(path)
    }
}

/// The strand counts tried: just over the cap, or far over it (up to what a file under the
/// 1 GiB size cap can hold at `bytes_per_strand`).
fn strand_count(rng: &mut Rng, bytes_per_strand: u64) -> u64 {
    let most = (MAX_STRAND_FILE_BYTES - 4096) / bytes_per_strand;
    if rng.chance(0.5) {
        MAX_STRANDS + 1 + rng.below(1000) as u64
    } else {
        MAX_STRANDS + 1 + rng.below((most - MAX_STRANDS - 1) as usize) as u64
    }
}

fn le(out: &mut [u8], at: usize, v: u32) {
    out[at..at + 4].copy_from_slice(&v.to_le_bytes());
}

/// A TressFX 3.x or 4.x file of 2 vertices a strand.
fn tfx(rng: &mut Rng, version: f32) -> Oversize {
    let (header, offset_at, stride) = if version < 4.0 {
        (wisp::input::tfx::HEADER_3_BYTES, 144, 12)
    } else {
        (wisp::input::tfx::HEADER_4_BYTES, 12, 16)
    };
    let strands = strand_count(rng, 2 * stride);
    let mut head = vec![0u8; header];
    head[0..4].copy_from_slice(&version.to_le_bytes());
    le(&mut head, 4, strands as u32);
    le(&mut head, 8, 2);
    le(&mut head, offset_at, header as u32);
    Oversize {
        name: format!("v{version}.tfx"),
        len: header as u64 + strands * 2 * stride,
        head,
        strands,
    }
}

/// A cyHair file of 2 points a strand (`d_segments` 1, points only).
fn cyhair(rng: &mut Rng) -> Oversize {
    use wisp::input::cyhair::{HAS_POINTS, HEADER_BYTES};
    let strands = strand_count(rng, 24);
    let mut head = vec![0u8; HEADER_BYTES];
    head[0..4].copy_from_slice(b"HAIR");
    le(&mut head, 4, strands as u32);
    le(&mut head, 8, 2 * strands as u32);
    le(&mut head, 12, HAS_POINTS);
    le(&mut head, 16, 1);
    Oversize {
        name: "strands.hair".into(),
        len: HEADER_BYTES as u64 + 24 * strands,
        head,
        strands,
    }
}

/// A binary PLY file with a strand element of per-strand vertex counts, 2 vertices each.
fn ply(rng: &mut Rng) -> Oversize {
    let strands = strand_count(rng, 28);
    let head = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\n\
         property float y\nproperty float z\nelement strand {strands}\n\
         property int vertex_count\nend_header\n",
        2 * strands
    )
    .into_bytes();
    Oversize {
        name: "strands.ply".into(),
        len: head.len() as u64 + 28 * strands,
        head,
        strands,
    }
}

/// A USC-HairSalon file of empty strands (each a point count of 0).
fn hairsalon(rng: &mut Rng) -> Oversize {
    let strands = strand_count(rng, 4);
    Oversize {
        name: "strands.data".into(),
        head: (strands as u32).to_le_bytes().to_vec(),
        len: 4 + 4 * strands,
        strands,
    }
}

/// A file of a format chosen by `rng` (TressFX 3 and 4, cyHair, PLY, USC-HairSalon).
pub fn oversize(rng: &mut Rng) -> Oversize {
    match rng.below(5) {
        0 => tfx(rng, 3.0),
        1 => tfx(rng, 4.0),
        2 => cyhair(rng),
        3 => ply(rng),
        _ => hairsalon(rng),
    }
}
