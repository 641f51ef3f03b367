//! Which reader a strand file needs: the `HAIR` signature, else the extension (`.tfx`,
//! `.hair`). Kept apart from the readers, which share only [`super::strands`].

use super::strands::{MAX_STRAND_FILE_BYTES, StrandFile, StrandFileError};
use std::path::Path;

/// Reads a strand file, choosing the reader by the `HAIR` signature or the `.tfx` extension.
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

/// Parses the bytes of a strand file; `file` names it in errors (its extension picks TressFX
/// when the bytes do not start with `HAIR`).
pub fn parse_strand_file(bytes: &[u8], file: &str) -> Result<StrandFile, StrandFileError> {
    if bytes.starts_with(b"HAIR") {
        return super::cyhair::parse_cyhair(bytes, file);
    }
    if file.to_ascii_lowercase().ends_with(".tfx") {
        return super::tfx::parse_tfx(bytes, file);
    }
    if file.to_ascii_lowercase().ends_with(".hair") {
        return super::cyhair::parse_cyhair(bytes, file);
    }
    Err(StrandFileError::UnknownFormat {
        file: file.to_string(),
    })
}

/// Whether `name` looks like a strand file (by extension): the CLI tells grooms from
/// hairstyle JSON with it.
pub fn is_strand_file_name(name: &str) -> bool {
    let l = name.to_ascii_lowercase();
    l.ends_with(".tfx") || l.ends_with(".hair")
}
