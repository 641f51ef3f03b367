//! USC-HairSalon `.data` strand files (little endian), the public hair dataset's format:
//! `i32 strand_count`, then each strand as `i32 point_count` followed by `point_count`
//! `f32[3]` points, root first. The dataset's units are metres, Y up.
//!
//! The dataset marks scalp points without hair as strands of 1 point (or 0): they are kept as
//! the file has them, and the groom builder drops and counts them as it does zero-length
//! strands. Every count is checked against the bytes left before anything is allocated, and
//! bytes after the last strand are refused (a file of another format would otherwise pass).

use super::strands::{Bytes, StrandFile, StrandFileError};

/// Parses a `.data` file's bytes; `file` names it in errors.
pub fn parse_hairsalon(bytes: &[u8], file: &str) -> Result<StrandFile, StrandFileError> {
    let r = Bytes { bytes, file };
    let strands = r.u32_at(0, "strand count")? as i32;
    if strands < 1 {
        return Err(r.malformed(
            0,
            format!("the strand count must be at least 1 (got {strands})"),
        ));
    }
    // Each strand takes at least its 4-byte point count.
    r.check_array(4, strands as u64, 4, "strand point counts")?;
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
