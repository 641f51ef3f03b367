//! Damaged frames in a `--resume` folder: a frame as wisp writes it (8-bit PNG, 16-bit PNG,
//! OpenEXR) with one defect that decoding the pixels alone does not reveal: a chunk's CRC
//! wrong, bytes after the image's end, the file grown (`truncate -s 4G`), a required EXR header
//! attribute renamed or retyped, an EXR chunk that does not start where the one before ends.
//! The named cases are the issue's; [`generated`] draws more from a seed.
//!
//! Where a damage sits is found here from the file's own structure (PNG chunks, EXR attribute
//! records and offset table), written out for the tests rather than taken from `wisp`, so the
//! tests do not trust the code they check.

use super::Rng;
use std::path::Path;

/// The kind of a frame file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    Png,
    Exr,
}

/// One defect.
#[derive(Clone, Debug)]
pub enum Damage {
    /// The byte at `at` XOR `mask` (nonzero).
    Flip { at: usize, mask: u8 },
    /// These bytes appended after the file's end.
    Append(Vec<u8>),
    /// The file extended to `len` bytes with a hole (sparse, as `truncate -s` does): nothing is
    /// written, so a 4 GiB frame costs no disk.
    Grow(u64),
}

/// What a refusal of the damage must say.
#[derive(Clone, Debug, PartialEq)]
pub enum Expect {
    /// `FrameDefect::Trailing` with the image ending at the original length and the file at
    /// this length.
    Trailing { len: u64 },
    /// `FrameDefect::Undecodable` whose message contains this text.
    Undecodable(String),
}

impl Damage {
    /// Applies the damage to the file at `path`.
    pub fn apply(&self, path: &Path) {
        match self {
            Damage::Flip { at, mask } => {
                let mut bytes = std::fs::read(path).expect("read frame");
                bytes[*at] ^= mask;
                std::fs::write(path, bytes).expect("write frame");
            }
            Damage::Append(tail) => {
                use std::io::Write;
                let mut f = std::fs::OpenOptions::new()
                    .append(true)
                    .open(path)
                    .expect("open frame");
                f.write_all(tail).expect("append");
            }
            Damage::Grow(len) => {
                let f = std::fs::OpenOptions::new()
                    .write(true)
                    .open(path)
                    .expect("open frame");
                f.set_len(*len).expect("set_len");
            }
        }
    }
}

/// 4 GiB: the issue's `truncate -s 4G`.
pub const FOUR_GIB: u64 = 4 << 30;

/// The cases and their kin for a frame of `kind` whose bytes are `bytes`, each with a
/// name and what its refusal must say.
pub fn named(kind: Kind, bytes: &[u8]) -> Vec<(String, Damage, Expect)> {
    let len = bytes.len() as u64;
    let junk = b"junk after the end".to_vec();
    let mut cases = vec![
        (
            "18 bytes of junk appended".to_string(),
            Damage::Append(junk.clone()),
            Expect::Trailing {
                len: len + junk.len() as u64,
            },
        ),
        (
            "one zero byte appended".to_string(),
            Damage::Append(vec![0]),
            Expect::Trailing { len: len + 1 },
        ),
        (
            "grown to 4 GiB".to_string(),
            Damage::Grow(FOUR_GIB),
            Expect::Trailing { len: FOUR_GIB },
        ),
        (
            "a copy of itself appended".to_string(),
            Damage::Append(bytes.to_vec()),
            Expect::Trailing { len: 2 * len },
        ),
    ];
    match kind {
        Kind::Png => {
            for (ty, at) in png_chunks(bytes) {
                let name = String::from_utf8_lossy(&ty).into_owned();
                // The first byte of the chunk's data (or of its CRC when it has none). The
                // decoder inflates IDAT as it reads it, so there the zlib header fails before
                // the CRC is reached.
                let says = if &ty == b"IDAT" { "PNG: " } else { "CRC" };
                cases.push((
                    format!("one bit flipped in the {name} chunk"),
                    Damage::Flip {
                        at: at + 8,
                        mask: 1,
                    },
                    Expect::Undecodable(says.into()),
                ));
            }
        }
        Kind::Exr => {
            for (name, at) in exr_required_names(bytes) {
                let shown = String::from_utf8_lossy(&name).into_owned();
                // Last letter's case flipped: `pixelAspectRatio` -> `pixelAspectRatiO`.
                cases.push((
                    format!("attribute {shown} renamed"),
                    Damage::Flip {
                        at: at + name.len() - 1,
                        mask: 0x20,
                    },
                    // The exr crate names the five it requires itself ("missing or invalid
                    // data window attribute"), `exr_layout` the rest.
                    Expect::Undecodable("attribute".into()),
                ));
            }
            let (table, chunks) = exr_offset_table(bytes);
            cases.push((
                "the first chunk's offset one byte on".to_string(),
                Damage::Flip { at: table, mask: 1 },
                Expect::Undecodable("chunk".into()),
            ));
            cases.push((
                "the last chunk's data size one more".to_string(),
                Damage::Flip {
                    at: exr_last_chunk_size_at(bytes, table, chunks),
                    mask: 1,
                },
                Expect::Undecodable("chunk".into()),
            ));
        }
    }
    cases
}

/// A damage drawn from `rng` for a frame of `kind`: for a PNG, one bit of any byte (the
/// signature, a chunk's length, type, data or CRC: every byte is covered), or bytes appended,
/// or the file grown; for an OpenEXR file, one bit of a byte of its structure (a required
/// attribute's name, type or size field, the header's end, the offset table, a chunk's size
/// field), or bytes appended, or the file grown. Pixel data of an OpenEXR file is left alone:
/// it has no checksum.
pub fn generated(rng: &mut Rng, kind: Kind, bytes: &[u8]) -> Damage {
    let len = bytes.len() as u64;
    match rng.below(4) {
        0 => Damage::Append(
            (0..1 + rng.below(64))
                .map(|_| rng.next_u64() as u8)
                .collect(),
        ),
        1 => Damage::Grow(len + 1 + rng.next_u64() % FOUR_GIB),
        _ => {
            let at = match kind {
                Kind::Png => rng.below(bytes.len()),
                Kind::Exr => *rng.pick(&exr_structure(bytes)),
            };
            Damage::Flip {
                at,
                mask: 1 << rng.below(8),
            }
        }
    }
}

/// Each PNG chunk's type and the offset of its length field.
pub fn png_chunks(bytes: &[u8]) -> Vec<([u8; 4], usize)> {
    let mut at = 8;
    let mut chunks = Vec::new();
    while at + 12 <= bytes.len() {
        let n = u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
        chunks.push((bytes[at + 4..at + 8].try_into().unwrap(), at));
        at += 12 + n;
    }
    chunks
}

/// The required attributes of a single-part OpenEXR header (the OpenEXR file layout).
const REQUIRED: [&[u8]; 9] = [
    b"channels",
    b"compression",
    b"dataWindow",
    b"displayWindow",
    b"lineOrder",
    b"pixelAspectRatio",
    b"screenWindowCenter",
    b"screenWindowWidth",
    b"tiles",
];

/// One attribute record of an OpenEXR header: its name and where its name and its size field
/// start (the type name lies between them).
struct Record {
    name: Vec<u8>,
    name_at: usize,
    size_at: usize,
}

/// The header's attribute records, and the offset just past the header's terminating null.
fn exr_attributes(bytes: &[u8]) -> (Vec<Record>, usize) {
    let mut at = 8;
    let mut records = Vec::new();
    let nul = |from: usize| from + bytes[from..].iter().position(|&b| b == 0).unwrap();
    while bytes[at] != 0 {
        let name_end = nul(at);
        let type_end = nul(name_end + 1);
        let size = i32::from_le_bytes(bytes[type_end + 1..type_end + 5].try_into().unwrap());
        records.push(Record {
            name: bytes[at..name_end].to_vec(),
            name_at: at,
            size_at: type_end + 1,
        });
        at = type_end + 5 + size as usize;
    }
    (records, at + 1)
}

/// Each required attribute present in the header and the offset of its name.
pub fn exr_required_names(bytes: &[u8]) -> Vec<(Vec<u8>, usize)> {
    exr_attributes(bytes)
        .0
        .into_iter()
        .filter(|r| REQUIRED.contains(&r.name.as_slice()))
        .map(|r| (r.name, r.name_at))
        .collect()
}

/// The offset table's start and its number of entries (chunks lie end to end after it, as
/// wisp writes them, so the entries are the bytes up to the smallest offset).
pub fn exr_offset_table(bytes: &[u8]) -> (usize, usize) {
    let table = exr_attributes(bytes).1;
    let first = u64::from_le_bytes(bytes[table..table + 8].try_into().unwrap()) as usize;
    (table, (first - table) / 8)
}

/// The offset of the data size field of the chunk that ends the file (tiled: after four
/// 4-byte tile coordinates).
fn exr_last_chunk_size_at(bytes: &[u8], table: usize, chunks: usize) -> usize {
    let offsets = (0..chunks)
        .map(|i| u64::from_le_bytes(bytes[table + 8 * i..table + 8 * i + 8].try_into().unwrap()));
    offsets.max().unwrap() as usize + 16
}

/// Every byte of an OpenEXR file's structure: each required attribute's name, type and size
/// field, the header's terminating null, the offset table, and each chunk's size field.
fn exr_structure(bytes: &[u8]) -> Vec<usize> {
    let (records, header_end) = exr_attributes(bytes);
    let mut at: Vec<usize> = records
        .iter()
        .filter(|r| REQUIRED.contains(&r.name.as_slice()))
        .flat_map(|r| r.name_at..r.size_at + 4)
        .collect();
    at.push(header_end - 1);
    let (table, chunks) = exr_offset_table(bytes);
    at.extend(table..table + 8 * chunks);
    for i in 0..chunks {
        let offset =
            u64::from_le_bytes(bytes[table + 8 * i..table + 8 * i + 8].try_into().unwrap());
        at.extend(offset as usize + 16..offset as usize + 20);
    }
    at
}
