//! Which reader a strand file needs: the `HAIR` or `ply` signature, else the extension
//! (`.tfx`, `.hair`, `.ply`, `.data`). Kept apart from the readers, which share only
//! [`super::strands`].

use super::strands::{MAX_STRAND_FILE_BYTES, StrandFile, StrandFileError};
use std::path::Path;

/// Extensions of the strand files wisp reads, lower case, with their formats' names.
pub const STRAND_FILE_FORMATS: [(&str, &str); 4] = [
    ("tfx", "TressFX"),
    ("hair", "cyHair"),
    ("ply", "PLY strands"),
    ("data", "USC-HairSalon"),
];

/// Reads a strand file, choosing the reader by its signature or its extension.
pub fn load_strand_file(path: &Path) -> Result<StrandFile, StrandFileError> {
    let file = path.display().to_string();
    let bytes =
        super::read_capped(path, MAX_STRAND_FILE_BYTES, "a strand file").map_err(|error| {
            StrandFileError::Io {
                file: file.clone(),
                error,
            }
        })?;
    parse_strand_file(&bytes, &file)
}

/// Parses the bytes of a strand file; `file` names it in errors (its extension picks the
/// reader when the bytes start with neither `HAIR` nor `ply`).
pub fn parse_strand_file(bytes: &[u8], file: &str) -> Result<StrandFile, StrandFileError> {
    if bytes.starts_with(b"HAIR") {
        return super::cyhair::parse_cyhair(bytes, file);
    }
    if bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n") {
        return super::ply::parse_ply(bytes, file);
    }
    match extension(file).as_deref() {
        Some("tfx") => super::tfx::parse_tfx(bytes, file),
        Some("hair") => super::cyhair::parse_cyhair(bytes, file),
        Some("ply") => super::ply::parse_ply(bytes, file),
        Some("data") => super::hairsalon::parse_hairsalon(bytes, file),
        _ => Err(StrandFileError::UnknownFormat {
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
