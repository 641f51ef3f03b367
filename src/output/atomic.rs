//! Files written so that nothing half-written ever carries a file's name, and the errors of
//! writing an output file.
//!
//! A file is encoded to `<name>.tmp` in the same directory, flushed and synced, then renamed
//! over `<name>`: rename is atomic within a directory on POSIX, so an interrupted export
//! leaves complete files only, and a failed write leaves `<name>` as it was.

use std::fs::File;
use std::path::{Path, PathBuf};

/// Why an image could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The message carries the cause; it is not also a `source()`, so `{:#}` chains (anyhow)
    /// do not print it twice.
    #[error("{}: {error}", path.display())]
    Io {
        path: PathBuf,
        error: std::io::Error,
    },
    /// The encoder or decoder refused (its message says which format); a failed write is
    /// [`OutputError::Io`].
    #[error("{}: {message}", path.display())]
    Encode { path: PathBuf, message: String },
    #[error("{}: image buffer has {got} samples, expected {expected} for {width}x{height} {channels}", path.display())]
    Size {
        path: PathBuf,
        got: usize,
        expected: usize,
        width: u32,
        height: u32,
        /// The channels each pixel has ("RGB", "RGBA").
        channels: &'static str,
    },
    #[error(
        "{path}: image has {rgb} colours and {alpha} coverage values, expected {width}x{height} of each"
    )]
    PixelCount {
        path: PathBuf,
        rgb: usize,
        alpha: usize,
        width: u32,
        height: u32,
    },
}

/// Writes a file through `<path>.tmp` in the same directory: `write` fills the temporary file
/// and hands it back, which is then synced and renamed over `path` (atomic within a directory
/// on POSIX). On any failure the temporary file is removed and `path` is left as it was.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(File) -> Result<File, OutputError>,
) -> Result<(), OutputError> {
    let mut tmp_name = path.as_os_str().to_owned();
    tmp_name.push(".tmp");
    let tmp = PathBuf::from(tmp_name);
    let io_err = |p: &Path| {
        let p = p.to_path_buf();
        move |error| OutputError::Io { path: p, error }
    };
    let result = (|| {
        let file = File::create(&tmp).map_err(io_err(&tmp))?;
        let file = write(file)?;
        file.sync_all().map_err(io_err(&tmp))?;
        std::fs::rename(&tmp, path).map_err(io_err(path))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}
