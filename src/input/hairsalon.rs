//! USC-HairSalon `.data` strand files (little endian), the public hair dataset's format:
//! `i32 strand_count`, then each strand as `i32 point_count` followed by `point_count`
//! `f32[3]` points, root first. The dataset's units are metres, Y up.
//!
//! The dataset marks scalp points without hair as strands of 1 point (or 0): they are kept as
//! the file has them, and the groom builder drops and counts them as it does zero-length
//! strands. The strand count is checked against the most a groom may have and the file's
//! size from the header alone (`check_hairsalon_header`, before the body is read); every
//! count is checked against the bytes left before anything is allocated, and
//! bytes after the last strand are refused (a file of another format would otherwise pass).

use super::strands::{Bytes, StrandFile, StrandFileError};
use crate::hairstyle::MAX_STRANDS;

/// Parses a `.data` file's bytes; `file` names it in errors.
pub fn parse_hairsalon(bytes: &[u8], file: &str) -> Result<StrandFile, StrandFileError> {
    let r = Bytes { bytes, file };
    let strands = strand_count(&r, bytes.len() as u64)?;
    let mut strand_points = Vec::with_capacity(strands as usize);
    let mut points = Vec::new();
    let mut at = 4usize;
    for s in 0..strands as usize {
        let n = r.u32_at(at, "point count")? as i32;
        if n < 0 {
            return Err(r.malformed(
                at as u64,
                format!("strand {s}: the point count must be at least 0 (got {n})"),
            ));
        }
        at += 4;
        r.check_array(at as u64, n as u64, 12, &format!("strand {s}'s points"))?;
        points.extend(r.points(at, n as usize, 12, &format!("strand {s}: point"))?);
        at += 12 * n as usize;
        strand_points.push(n as u32);
    }
    if at != bytes.len() {
        return Err(r.malformed(
            at as u64,
            format!(
                "{} bytes follow the last of the {strands} strands: a .data file ends with its last point",
                bytes.len() - at
            ),
        ));
    }
    Ok(StrandFile {
        points,
        strand_points,
        thickness: None,
        colors: None,
    })
}

/// Checks the header of a `.data` file of `file_len` bytes from its first bytes `head`: the
/// strand count against the most a groom may have and the file's size, so a file that
/// declares more than a groom may hold is refused before its body is read.
pub fn check_hairsalon_header(
    head: &[u8],
    file_len: u64,
    file: &str,
) -> Result<(), StrandFileError> {
    strand_count(&Bytes { bytes: head, file }, file_len).map(|_| ())
}

/// The strand count at the start of `r`, in a file of `file_len` bytes: at least 1, at most
/// [`MAX_STRANDS`], and each strand's 4-byte point count inside the file.
fn strand_count(r: &Bytes, file_len: u64) -> Result<i32, StrandFileError> {
    let strands = r.u32_at(0, "strand count")? as i32;
    if strands < 1 {
        return Err(r.malformed(
            0,
            format!("the strand count must be at least 1 (got {strands})"),
        ));
    }
    if strands as u64 > MAX_STRANDS {
        return Err(r.malformed(
            0,
            format!("the strand count {strands} is over the limit of {MAX_STRANDS} strands a groom may have"),
        ));
    }
    // Each strand takes at least its 4-byte point count.
    r.check_array_within(file_len, 4, strands as u64, 4, "strand point counts")?;
    Ok(strands)
}
