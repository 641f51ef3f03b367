//! Why a motion could not be loaded ([`MotionError`]). Every message names the file, and each
//! variant the part of the file or the option at fault, so a user can find what to fix.

/// Most items listed in one message (a broken file can have thousands of problems, a rig
/// hundreds of joints).
const MAX_LISTED: usize = 8;

/// Why a motion could not be loaded. Every message names the file.
#[derive(Debug, thiserror::Error)]
pub enum MotionError {
    /// The file could not be read (missing, not a regular file, over
    /// [`MAX_FILE_BYTES`](super::MAX_FILE_BYTES)).
    #[error("{file}: {error}")]
    Io {
        /// File name.
        file: String,
        /// What went wrong.
        error: crate::input::ReadError,
    },
    /// Not glTF at all (neither the GLB magic nor JSON).
    #[error("{file}: not a glTF 2.0 file: {reason}")]
    NotGltf {
        /// File name.
        file: String,
        /// What was found.
        reason: String,
    },
    /// A .glb shorter than its header or chunks say.
    #[error("{file}: truncated .glb: {reason}")]
    Truncated {
        /// File name.
        file: String,
        /// What is missing.
        reason: String,
    },
    /// glTF that breaks the specification or uses something unsupported.
    #[error("{file}: invalid glTF: {reason}")]
    Invalid {
        /// File name.
        file: String,
        /// What is wrong.
        reason: String,
    },
    /// A buffer could not be resolved (unsupported URI, missing file, bad base64).
    #[error("{file}: buffer {index}: {reason}")]
    Buffer {
        /// File name.
        file: String,
        /// Buffer index.
        index: usize,
        /// What is wrong.
        reason: String,
    },
    /// The file has no animation clip.
    #[error("{file}: the glTF has no animations (a motion needs at least one clip)")]
    NoAnimations {
        /// File name.
        file: String,
    },
    /// The requested clip does not exist.
    #[error("{file}: no clip named {requested:?}; clips: {}", short_list(available.iter().cloned(), ", "))]
    UnknownClip {
        /// File name.
        file: String,
        /// Requested name.
        requested: String,
        /// Names of the clips in the file (unnamed ones as `#index`).
        available: Vec<String>,
    },
    /// A requested joint (head or body sphere) does not exist, or no head joint was found.
    #[error("{file}: {role}: no joint {requested}; joints (index name): {available}")]
    UnknownJoint {
        /// File name.
        file: String,
        /// Which joint was asked for ("head joint", "body sphere joint").
        role: String,
        /// What was asked for (a quoted name, an index, or "named like \"head\"").
        requested: String,
        /// The joints, as "index name" pairs separated by commas.
        available: String,
    },
    /// A clip's tracks are malformed (key counts, non-increasing times, non-finite values).
    #[error("{file}: clip {clip:?}: {reason}")]
    BadClip {
        /// File name.
        file: String,
        /// Clip name.
        clip: String,
        /// What is wrong.
        reason: String,
    },
    /// An option is out of range (speed not finite, fit scale not positive, ...).
    #[error("{file}: invalid option: {reason}")]
    BadOption {
        /// File name.
        file: String,
        /// What is wrong.
        reason: String,
    },
}

/// A file that breaks the glTF specification or uses something unsupported: `reason` says
/// which part and rule.
pub(crate) fn invalid(file: &str, reason: impl Into<String>) -> MotionError {
    MotionError::Invalid {
        file: file.to_string(),
        reason: reason.into(),
    }
}

/// "a; b; c (and 12 more)": the first few items of a long list.
pub(crate) fn short_list(items: impl ExactSizeIterator<Item = String>, sep: &str) -> String {
    let total = items.len();
    let shown: Vec<String> = items.take(MAX_LISTED).collect();
    let mut s = shown.join(sep);
    if total > shown.len() {
        s.push_str(&format!(" (and {} more)", total - shown.len()));
    }
    s
}
