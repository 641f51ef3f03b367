//! Which of a groom's captured strands are kept: those with at least 2 points and an arc
//! length above a millionth of the longest strand's. Shorter ones are points at any scale:
//! once placed on the head they vanish or underflow, and the resampling needs a length to
//! divide by. The dropped strands are counted in the report, not refused.

use glam::Vec3;

use super::error::GroomError;
use super::polyline::arc_length;
use crate::hairstyle::MAX_STRANDS;
use crate::input::strands::StrandFile;

/// A strand kept for the groom: its file (index into the files), its index in that file and
/// its points (the file's units and axes, root first).
#[derive(Clone, Copy)]
pub(super) struct Kept<'a> {
    pub(super) file: usize,
    pub(super) strand: usize,
    pub(super) points: &'a [Vec3],
}

/// The strands of `files` kept for the groom, and how many were read. Refuses a strand whose
/// length overflows (coordinates near the float limit), fewer than 3 kept strands (one wisp
/// of 3 guides) and more than [`MAX_STRANDS`]; `names` names all the files in messages.
pub(super) fn keep_strands<'a>(
    files: &'a [(String, StrandFile)],
    names: &str,
) -> Result<(Vec<Kept<'a>>, usize), GroomError> {
    let mut longest_file = 0.0f32;
    for (name, file) in files {
        for (s, pts) in file.strands().enumerate() {
            let len = arc_length(pts);
            if !len.is_finite() {
                return Err(GroomError::Invalid {
                    files: name.clone(),
                    rule: format!(
                        "strand {s}: its length overflows (coordinates near the largest 32-bit float)"
                    ),
                });
            }
            longest_file = longest_file.max(len);
        }
    }
    let mut kept = Vec::new();
    let mut read = 0usize;
    for (f, (_, file)) in files.iter().enumerate() {
        for (s, pts) in file.strands().enumerate() {
            read += 1;
            if pts.len() >= 2 && arc_length(pts) > 1e-6 * longest_file {
                kept.push(Kept {
                    file: f,
                    strand: s,
                    points: pts,
                });
            }
        }
    }
    let count = kept.len();
    let invalid = |rule: String| GroomError::Invalid {
        files: names.to_string(),
        rule,
    };
    if count < 3 {
        return Err(invalid(format!(
            "{count} strands of nonzero length ({read} read): a groom needs at least 3 (one wisp of 3 guides)"
        )));
    }
    if count as u64 > MAX_STRANDS {
        return Err(invalid(format!("{count} strands: at most {MAX_STRANDS}")));
    }
    Ok((kept, read))
}
