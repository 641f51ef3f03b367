//! Why a cache could not be read or written ([`CacheError`]). Every message names the file;
//! a refused input also names the field and the rule, or what differs from the run that wants
//! to render it and what to do. Only a failed write is not the input's fault (exit code 2 on
//! the command line for the others).

use crate::input::ReadError;

/// Why a cache could not be read or written. Every message names the file.
#[derive(Debug, thiserror::Error)]
pub enum CacheError {
    /// The file could not be opened or read (missing, a directory, a device, an I/O error).
    #[error("{file}: {error}")]
    Read {
        /// File name.
        file: String,
        /// What went wrong.
        error: ReadError,
    },
    /// The file breaks the format: the field and the rule.
    #[error("{file}: {reason}")]
    Invalid {
        /// File name.
        file: String,
        /// What is wrong, naming the field.
        reason: String,
    },
    /// A valid cache made for another hairstyle, motion or hair model.
    #[error("{file}: {reason}")]
    Mismatch {
        /// File name.
        file: String,
        /// What differs, and what to do.
        reason: String,
    },
    /// The output path cannot hold a cache (a directory, a device, a missing folder).
    #[error("{file}: {reason}")]
    BadOutput {
        /// File name.
        file: String,
        /// Why.
        reason: String,
    },
    /// Writing failed (disk full, permissions).
    #[error("{file}: cannot write: {error}")]
    Write {
        /// File name.
        file: String,
        /// The cause.
        error: std::io::Error,
    },
}

impl CacheError {
    /// True when the error is the input's fault (exit code 2 on the command line): anything
    /// but a failed write.
    pub fn is_bad_input(&self) -> bool {
        !matches!(self, CacheError::Write { .. })
    }
}
