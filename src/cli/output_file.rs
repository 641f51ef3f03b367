//! Output files named by a flag (`--screenshot`, `--json`, `--skin-image`): checked before any
//! work, so a run of minutes does not end on a path that could never be written.

use super::AppError;
use std::path::Path;

/// Checks, before any work, that `path` can be an output file: not a directory, in a folder
/// that exists. `flag` names the option in the message.
pub fn check_output_file(flag: &str, path: &Path) -> Result<(), AppError> {
    let shown = path.display();
    if path.is_dir() {
        return Err(AppError::input(anyhow::anyhow!(
            "{flag} {shown}: is a directory, not a file name"
        )));
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !parent.is_dir() {
        return Err(AppError::input(anyhow::anyhow!(
            "{flag} {shown}: the folder {} does not exist",
            parent.display()
        )));
    }
    Ok(())
}
