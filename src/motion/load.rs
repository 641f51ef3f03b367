//! glTF loading (placeholder).

use super::{Motion, MotionError, MotionOptions};
use std::path::Path;

pub(crate) fn from_bytes(
    _bytes: &[u8],
    name: &str,
    _base_dir: Option<&Path>,
    _opts: &MotionOptions,
) -> Result<Motion, MotionError> {
    Err(MotionError::Invalid {
        file: name.to_string(),
        reason: "loader not written yet".to_string(),
    })
}
