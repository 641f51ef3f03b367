//! The byte layout of a single-part OpenEXR frame, checked without reading its pixels: the
//! header's attribute records (name, type, size) up to the null byte that ends them, with every
//! attribute OpenEXR requires present once with its type and size; then the offset table; then
//! the chunks, which must lie end to end from the table's end to the file's last byte.
//!
//! The exr crate reads the header's values (and validates them), but fills in a required
//! attribute that is missing or of another type (a `pixelAspectRatio` renamed is read as 1),
//! does not say where the header ends, and stops reading at the last chunk, so a file grown or
//! with bytes appended would pass it. Only the records, the table and each chunk's 8- or
//! 20-byte prefix are read here, so a 4 GB file costs a few KB.

use super::FrameDefect;
use std::io::{BufRead, Read, Seek, SeekFrom};

/// What the exr crate found in the header, which fixes the rest of the layout.
pub(super) struct Layout {
    /// One tiled part (version flag bit 9): the `tiles` attribute is required and chunks start
    /// with four tile coordinates; otherwise scan lines, whose chunks start with a row.
    pub tiled: bool,
    /// Names up to 255 bytes (version flag bit 10) rather than 31.
    pub long_names: bool,
    /// Entries of the offset table (the crate computes it from the data window, the tiles and
    /// the compression).
    pub chunks: usize,
}

/// The attributes every single-part OpenEXR file has (the OpenEXR file layout, "Header
/// Attributes"): name, type, and the value's size in bytes where the type fixes it.
const REQUIRED: [(&[u8], &[u8], Option<i32>); 8] = [
    (b"channels", b"chlist", None),
    (b"compression", b"compression", Some(1)),
    (b"dataWindow", b"box2i", Some(16)),
    (b"displayWindow", b"box2i", Some(16)),
    (b"lineOrder", b"lineOrder", Some(1)),
    (b"pixelAspectRatio", b"float", Some(4)),
    (b"screenWindowCenter", b"v2f", Some(8)),
    (b"screenWindowWidth", b"float", Some(4)),
];

/// Required in a tiled file as well.
const TILES: (&[u8], &[u8], Option<i32>) = (b"tiles", b"tiledesc", Some(9));

/// Bytes before the header: the magic number and the version field.
const PREAMBLE: u64 = 8;

/// Checks the layout of the OpenEXR file `read`, `len` bytes long, whose header the exr crate
/// has read as `layout` (see the module doc).
pub(super) fn check(
    read: &mut (impl BufRead + Seek),
    len: u64,
    layout: &Layout,
) -> Result<(), FrameDefect> {
    let header_end = check_header(read, len, layout)?;
    let table_end = (layout.chunks as u64)
        .checked_mul(8)
        .and_then(|t| t.checked_add(header_end))
        .filter(|&end| end <= len)
        .ok_or_else(|| {
            bad(format!(
                "its offset table of {} chunks runs past the file's end (byte {len})",
                layout.chunks
            ))
        })?;
    let mut offsets = Vec::with_capacity(layout.chunks);
    for _ in 0..layout.chunks {
        offsets.push(u64::from_le_bytes(read_array(read)?));
    }
    check_chunks(read, len, table_end, offsets, layout.tiled)
}

/// Reads the header's attribute records from after the version field to the null byte that
/// ends them, checking that each required attribute appears once with its type and size; the
/// byte where the header ends.
fn check_header(
    read: &mut (impl BufRead + Seek),
    len: u64,
    layout: &Layout,
) -> Result<u64, FrameDefect> {
    let max_name = if layout.long_names { 255 } else { 31 };
    let mut required: Vec<_> = REQUIRED.to_vec();
    if layout.tiled {
        required.push(TILES);
    }
    let mut seen = vec![false; required.len()];
    read.seek(SeekFrom::Start(PREAMBLE)).map_err(io)?;
    loop {
        let name = read_name(read, max_name, "attribute name")?;
        if name.is_empty() {
            break;
        }
        let kind = read_name(read, max_name, "attribute type")?;
        let size = i32::from_le_bytes(read_array(read)?);
        let shown = name.escape_ascii();
        let at = read.stream_position().map_err(io)?;
        if size < 0 || at + size as u64 > len {
            return Err(bad(format!(
                "its header's attribute `{shown}` claims {size} bytes, past the file's end (byte {len})"
            )));
        }
        if let Some(i) = required.iter().position(|r| r.0 == name.as_slice()) {
            let (_, want_kind, want_size) = required[i];
            if kind != want_kind || want_size.is_some_and(|s| s != size) {
                return Err(bad(format!(
                    "its header's attribute `{shown}` is of type `{}` ({size} bytes); OpenEXR requires `{}`",
                    kind.escape_ascii(),
                    want_kind.escape_ascii()
                )));
            }
            if std::mem::replace(&mut seen[i], true) {
                return Err(bad(format!("its header has attribute `{shown}` twice")));
            }
        }
        read.seek_relative(i64::from(size)).map_err(io)?;
    }
    if let Some(i) = seen.iter().position(|s| !s) {
        let (name, kind, _) = required[i];
        return Err(bad(format!(
            "its header has no `{}` attribute of type `{}`, which OpenEXR requires",
            name.escape_ascii(),
            kind.escape_ascii()
        )));
    }
    read.stream_position().map_err(io)
}

/// Checks that the chunks at `offsets` lie end to end from `table_end` to `len`, from each
/// chunk's prefix (its tile coordinates or row, then its data size).
fn check_chunks(
    read: &mut (impl BufRead + Seek),
    len: u64,
    table_end: u64,
    offsets: Vec<u64>,
    tiled: bool,
) -> Result<(), FrameDefect> {
    let prefix: u64 = if tiled { 20 } else { 8 };
    let mut order: Vec<(u64, usize)> = offsets.into_iter().zip(0..).collect();
    order.sort_unstable();
    let mut expected = table_end;
    for (offset, index) in order {
        if offset != expected {
            return Err(bad(format!(
                "chunk {index} starts at byte {offset}, not at byte {expected} where the one before it ends"
            )));
        }
        if offset + prefix > len {
            return Err(bad(format!(
                "chunk {index} at byte {offset} runs past the file's end (byte {len})"
            )));
        }
        read.seek(SeekFrom::Start(offset + prefix - 4))
            .map_err(io)?;
        let size = i32::from_le_bytes(read_array(read)?);
        let end = offset + prefix + size.max(0) as u64;
        if size < 0 || end > len {
            return Err(bad(format!(
                "chunk {index} at byte {offset} claims {size} bytes, past the file's end (byte {len})"
            )));
        }
        expected = end;
    }
    if expected == len {
        Ok(())
    } else {
        Err(FrameDefect::Trailing { end: expected, len })
    }
}

/// A null-terminated name of at most `max` bytes, without its null (empty: the header's end).
fn read_name(read: &mut impl BufRead, max: u64, what: &str) -> Result<Vec<u8>, FrameDefect> {
    let mut name = Vec::new();
    read.by_ref()
        .take(max + 1)
        .read_until(0, &mut name)
        .map_err(io)?;
    if name.pop() != Some(0) {
        return Err(bad(format!(
            "its header has an {what} over {max} bytes or cut short: `{}`",
            name.escape_ascii()
        )));
    }
    Ok(name)
}

/// `N` bytes, or the file's end as a defect.
fn read_array<const N: usize>(read: &mut impl Read) -> Result<[u8; N], FrameDefect> {
    let mut bytes = [0; N];
    read.read_exact(&mut bytes).map_err(io)?;
    Ok(bytes)
}

fn bad(message: String) -> FrameDefect {
    FrameDefect::Undecodable(format!("OpenEXR: {message}"))
}

fn io(e: std::io::Error) -> FrameDefect {
    FrameDefect::Undecodable(format!("OpenEXR: {e}"))
}
