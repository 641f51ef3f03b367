//! Reading input files defensively, for every loader (hairstyles, scene files, motions, strand
//! files, simulation caches).
//!
//! A file is examined before it is opened: directories, devices (`/dev/zero`), named pipes
//! and sockets are refused with a message saying what they are (opening a FIFO would block,
//! reading `/dev/zero` would never end), and a regular file larger than the loader's cap is
//! refused from its size alone, so no loader ever allocates more than its cap for the raw
//! bytes. The read itself is bounded too (`take(cap + 1)`), so a file that grows between the
//! check and the read is still caught.
//!
//! [`json`] holds the strict JSON reading shared by the JSON formats; [`tfx`], [`cyhair`],
//! [`ply`] and [`hairsalon`] read captured strands ([`strands`]) for groom import;
//! [`strand_file`] picks the reader; [`tfxmesh`] reads the mesh a TressFX groom was made on.
//! [`printable`] makes a name from a file safe to print.

pub mod cyhair;
pub mod hairsalon;
pub mod json;
pub mod ply;
mod printable;
pub mod strand_file;
pub mod strands;
pub mod tfx;
pub mod tfxmesh;

pub use printable::printable;

use std::io::Read;
use std::path::Path;

/// Why an input file could not be read. The message does not repeat the file name: the
/// loader's own error names it.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The operating system refused (missing file, no permission, ...).
    #[error("cannot read: {0}")]
    Io(std::io::Error),
    /// A directory, device, named pipe or socket.
    #[error("is {kind}, not a regular file")]
    NotAFile {
        /// What the path is ("a directory", "a character device (like /dev/zero)", ...).
        kind: &'static str,
    },
    /// Larger than the loader accepts.
    #[error("is {}, over the {} limit for {what}", human_bytes(*bytes), human_bytes(*limit))]
    TooLarge {
        /// Size of the file in bytes.
        bytes: u64,
        /// The cap in bytes.
        limit: u64,
        /// What kind of file was expected ("a hairstyle file", ...).
        what: &'static str,
    },
}

/// What a path that is not a regular file is, for messages.
fn kind_of(ft: &std::fs::FileType) -> &'static str {
    if ft.is_dir() {
        return "a directory";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if ft.is_char_device() {
            return "a character device (like /dev/zero or a terminal)";
        }
        if ft.is_block_device() {
            return "a block device";
        }
        if ft.is_fifo() {
            return "a named pipe (FIFO)";
        }
        if ft.is_socket() {
            return "a socket";
        }
    }
    "not a regular file"
}

/// Opens `path` for reading if it is a regular file (symbolic links are followed), and
/// returns it with its length in bytes. For formats read piece by piece (a simulation cache is
/// read one frame at a time, so its size has no cap): the caller checks what it reads against
/// the returned length before allocating.
pub fn open_regular(path: &Path) -> Result<(std::fs::File, u64), ReadError> {
    // Stat before opening: opening a FIFO blocks until a writer appears.
    let meta = std::fs::metadata(path).map_err(ReadError::Io)?;
    if !meta.file_type().is_file() {
        return Err(ReadError::NotAFile {
            kind: kind_of(&meta.file_type()),
        });
    }
    let file = std::fs::File::open(path).map_err(ReadError::Io)?;
    // The path may have been replaced between the two calls: check what was opened.
    let opened = file.metadata().map_err(ReadError::Io)?;
    if !opened.file_type().is_file() {
        return Err(ReadError::NotAFile {
            kind: kind_of(&opened.file_type()),
        });
    }
    Ok((file, opened.len()))
}

/// Reads the whole of `path` if it is a regular file of at most `limit` bytes (symbolic links
/// are followed). `what` names the expected content in the size message ("a hairstyle file").
pub fn read_capped(path: &Path, limit: u64, what: &'static str) -> Result<Vec<u8>, ReadError> {
    let too_large = |bytes: u64| ReadError::TooLarge { bytes, limit, what };
    // Refused from its size alone, before a byte is read.
    let (file, len) = open_regular(path)?;
    if len > limit {
        return Err(too_large(len));
    }
    let mut bytes = Vec::with_capacity(len.min(limit) as usize);
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(ReadError::Io)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// A byte count for people: "512 B", "1.5 KB", "17.9 GB" (powers of 1000, as disk sizes).
pub fn human_bytes(bytes: u64) -> String {
    const UNITS: [&str; 6] = ["B", "KB", "MB", "GB", "TB", "PB"];
    let mut v = bytes as f64;
    let mut unit = 0;
    while v >= 1000.0 && unit + 1 < UNITS.len() {
        v /= 1000.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{bytes} B")
    } else {
        format!("{v:.1} {}", UNITS[unit])
    }
}

#[cfg(test)]
mod tests;
