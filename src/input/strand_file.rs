//! Which reader a strand file needs: the `HAIR` or `ply` signature, else the extension
//! (`.tfx`, `.hair`, `.ply`, `.data`). Kept apart from the readers, which share only
//! [`super::strands`].

use super::ReadError;
use super::strands::{MAX_STRAND_FILE_BYTES, StrandFile, StrandFileError};
use std::io::Read;
use std::path::Path;

/// Extensions of the strand files wisp reads, lower case, with their formats' names.
pub const STRAND_FILE_FORMATS: [(&str, &str); 4] = [
    ("tfx", "TressFX"),
    ("hair", "cyHair"),
    ("ply", "PLY strands"),
    ("data", "USC-HairSalon"),
];

/// Bytes read first to check a strand file's header before its body: every binary header
/// (at most 296 bytes) and a PLY header of ordinary length (a longer one is checked with the
/// body).
const HEADER_PEEK_BYTES: u64 = 64 * 1024;

/// Reads a strand file, choosing the reader by its signature or its extension. The header is
/// read and checked first ([`check_strand_header`]: counts against the caps and the file's
/// size), so a file that declares more strands than a groom may have is refused after reading
/// its first bytes, not its whole body.
pub fn load_strand_file(path: &Path) -> Result<StrandFile, StrandFileError> {
    let file = path.display().to_string();
    let io = |error| StrandFileError::Io {
        file: file.clone(),
        error,
    };
    let limit = MAX_STRAND_FILE_BYTES;
    let too_large = |bytes| {
        io(ReadError::TooLarge {
            bytes,
            limit,
            what: "a strand file",
        })
    };
    let (opened, len) = super::open_regular(path).map_err(io)?;
    if len > limit {
        return Err(too_large(len));
    }
    let mut reader = std::io::BufReader::new(opened).take(limit.saturating_add(1));
    let mut bytes = Vec::new();
    (&mut reader)
        .take(HEADER_PEEK_BYTES)
        .read_to_end(&mut bytes)
        .map_err(|e| io(ReadError::Io(e)))?;
    check_strand_header(&bytes, len.max(bytes.len() as u64), &file)?;
    bytes.reserve_exact((len as usize).saturating_sub(bytes.len()));
    reader
        .read_to_end(&mut bytes)
        .map_err(|e| io(ReadError::Io(e)))?;
    if bytes.len() as u64 > limit {
        return Err(too_large(bytes.len() as u64));
    }
    parse_strand_file(&bytes, &file)
}

/// Checks a strand file's header from its first bytes `head`, for a file of `file_len` bytes:
/// the reader's own checks of its header counts (against the caps, at most
/// [`MAX_STRANDS`](crate::hairstyle::MAX_STRANDS) strands, and against the file's size), made
/// before the body is read. A file of no known format passes (the parse refuses it).
pub fn check_strand_header(head: &[u8], file_len: u64, file: &str) -> Result<(), StrandFileError> {
    match format_of(head, file) {
        Some(Format::Tfx) => super::tfx::check_tfx_header(head, file_len, file),
        Some(Format::CyHair) => super::cyhair::check_cyhair_header(head, file_len, file),
        Some(Format::Ply) => super::ply::check_ply_header(head, file_len, file),
        Some(Format::HairSalon) => super::hairsalon::check_hairsalon_header(head, file_len, file),
        None => Ok(()),
    }
}

/// The strand formats wisp reads.
enum Format {
    Tfx,
    CyHair,
    Ply,
    HairSalon,
}

/// The format of a file starting with `bytes` named `file`: the `HAIR` or `ply` signature,
/// else the extension.
fn format_of(bytes: &[u8], file: &str) -> Option<Format> {
    if bytes.starts_with(b"HAIR") {
        return Some(Format::CyHair);
    }
    if bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n") {
        return Some(Format::Ply);
    }
    match extension(file).as_deref() {
        Some("tfx") => Some(Format::Tfx),
        Some("hair") => Some(Format::CyHair),
        Some("ply") => Some(Format::Ply),
        Some("data") => Some(Format::HairSalon),
        _ => None,
    }
}

/// Parses the bytes of a strand file; `file` names it in errors (its extension picks the
/// reader when the bytes start with neither `HAIR` nor `ply`).
pub fn parse_strand_file(bytes: &[u8], file: &str) -> Result<StrandFile, StrandFileError> {
    match format_of(bytes, file) {
        Some(Format::Tfx) => super::tfx::parse_tfx(bytes, file),
        Some(Format::CyHair) => super::cyhair::parse_cyhair(bytes, file),
        Some(Format::Ply) => super::ply::parse_ply(bytes, file),
        Some(Format::HairSalon) => super::hairsalon::parse_hairsalon(bytes, file),
        None => Err(StrandFileError::UnknownFormat {
            file: file.to_string(),
        }),
    }
}

/// Whether `name` looks like a strand file (by extension): the CLI tells grooms from
/// hairstyle JSON with it.
pub fn is_strand_file_name(name: &str) -> bool {
    extension(name).is_some_and(|e| STRAND_FILE_FORMATS.iter().any(|(x, _)| *x == e))
}

/// The lower-case extension of `name`, if it has one.
fn extension(name: &str) -> Option<String> {
    Path::new(name)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}
