//! Reading a hairstyle: a file (at most [`MAX_FILE_BYTES`], UTF-8, a leading byte-order mark
//! skipped), JSON text, or an embedded preset (`smooth`, `curly`, and `dense` generated from
//! `smooth`). Parsing is strict ([`crate::input::json::from_str`]) and every style is
//! validated, so a [`HairstyleError`] names the file, the field path and the rule.

use super::spec::Hairstyle;
use crate::input::{self, ReadError};
use std::path::Path;

/// The default hairstyle, embedded in the binary.
pub const SMOOTH_JSON: &str = include_str!("../../hairstyles/smooth.json");
/// The curly preset, embedded too.
pub const CURLY_JSON: &str = include_str!("../../hairstyles/curly.json");

/// Largest hairstyle file read, in bytes (a hairstyle is a few dozen numbers; the presets are
/// about 1 KB).
pub const MAX_FILE_BYTES: u64 = 1 << 20;
/// Why a hairstyle could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum HairstyleError {
    /// The file could not be read (missing, not a regular file, over [`MAX_FILE_BYTES`]).
    #[error("{file}: {error}")]
    Io { file: String, error: ReadError },
    #[error("{file}: field `{field}`: {message}")]
    Parse {
        file: String,
        field: String,
        message: String,
    },
    #[error("{file}: field `{field}`: {rule}")]
    Invalid {
        file: String,
        field: String,
        rule: String,
    },
}

impl Hairstyle {
    /// Reads and validates a hairstyle file (at most [`MAX_FILE_BYTES`], UTF-8, a leading
    /// byte-order mark is skipped).
    pub fn load(path: &Path) -> Result<Self, HairstyleError> {
        let file = path.display().to_string();
        let bytes =
            input::read_capped(path, MAX_FILE_BYTES, "a hairstyle file").map_err(|error| {
                HairstyleError::Io {
                    file: file.clone(),
                    error,
                }
            })?;
        Self::from_bytes(&bytes, &file)
    }

    /// Parses and validates the bytes of a hairstyle file; `file` names it in errors.
    pub fn from_bytes(bytes: &[u8], file: &str) -> Result<Self, HairstyleError> {
        let text = input::json::decode_text(bytes).map_err(|e| HairstyleError::Parse {
            file: file.to_string(),
            field: e.field,
            message: e.message,
        })?;
        Self::from_json(text, file)
    }

    /// The embedded default (`smooth`).
    pub fn default_smooth() -> Self {
        Self::from_json(SMOOTH_JSON, "<embedded smooth.json>").expect("embedded hairstyle is valid")
    }

    /// The `dense` preset, generated from `smooth` (no file): Bertails 2005's scale of one
    /// fibre per render strand, 653 render strands per wisp (87,502 strands) of 14 points
    /// (1.14 M segments). The heavy scene of the speed benchmarks.
    pub fn dense() -> Self {
        let mut style = Self::default_smooth();
        style.name = "dense".into();
        style.wisps.strands_per_wisp = 653;
        style.strands.points = 14;
        style.strands.fibers_per_strand = 1.0;
        style
            .validate()
            .map_err(|(field, rule)| format!("{field}: {rule}"))
            .expect("the dense preset is valid");
        style
    }

    /// The embedded `curly` preset.
    pub fn default_curly() -> Self {
        Self::from_json(CURLY_JSON, "<embedded curly.json>").expect("embedded hairstyle is valid")
    }

    /// Parses and validates JSON text; `file` names the source in errors. Parsing is strict
    /// ([`input::json::from_str`]): no array for an object, no number beyond `f32`, no text
    /// after the object.
    pub fn from_json(text: &str, file: &str) -> Result<Self, HairstyleError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let style: Hairstyle = input::json::from_str(text).map_err(|e| HairstyleError::Parse {
            file: file.to_string(),
            field: e.field,
            message: e.message,
        })?;
        style
            .validate()
            .map_err(|(field, rule)| HairstyleError::Invalid {
                file: file.to_string(),
                field,
                rule,
            })?;
        Ok(style)
    }
}
