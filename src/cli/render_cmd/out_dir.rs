//! The output directory of an export: made ready before the first frame (created, checked
//! writable, what an earlier export left tidied away), and, with `--resume`, searched for the
//! frames already complete on disk (`wisp::output::check_frame`: decoded whole, not trusted by
//! name), which gives the run's [`FramePlan`].

use super::{AppError, FrameOutput};
use anyhow::Context;
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use wisp::output::{FrameDefect, FrameFormat, check_frame};

/// What an export may remove from its output directory before it starts.
#[derive(Clone, Debug, PartialEq)]
pub struct Tidy {
    /// The frames this run writes: their temporary files (of an interrupted run) are removed,
    /// and a non-file in the way of one is an error.
    pub own: std::ops::Range<u32>,
    /// Temporary files of any frame, in any format, are removed (false when other processes
    /// may be writing frames into the same directory: shards).
    pub all_temporaries: bool,
    /// Frames of this run's format numbered this or more are removed (no run of this sequence
    /// writes them).
    pub stale_from: Option<u32>,
}

impl Tidy {
    /// A run that writes frames 0 to `frames − 1` alone: the folder ends up holding exactly
    /// its frames (and any frames of another format, which it leaves alone).
    pub fn whole_run(frames: u32) -> Self {
        Self {
            own: 0..frames,
            all_temporaries: true,
            stale_from: Some(frames),
        }
    }
}

/// Makes `dir` ready for a run's frames of `format`: creates it, checks that files can be
/// written there, and removes what an earlier export left, as `tidy` allows:
/// `frame_NNNNN.EXT.tmp` files of an interrupted run and frames of this format beyond the
/// sequence (which this run would not overwrite). Only files named exactly like wisp's frames
/// are touched, frames of the other formats (`.png` beside `.exr`) are left as they are, and
/// a file another process removed first is not an error (shards tidy the same folder at once).
pub fn prepare_output_dir(
    dir: &Path,
    tidy: &Tidy,
    format: FrameFormat,
    quiet: bool,
) -> Result<(), AppError> {
    let shown = dir.display();
    make_writable_dir(dir, tidy.own.start)?;
    let entries = std::fs::read_dir(dir)
        .with_context(|| format!("--out {shown}: cannot list the directory"))
        .map_err(AppError::input)?;
    let (mut temporaries, mut stale) = (0usize, 0usize);
    for entry in entries.flatten() {
        match tidy_entry(&entry, tidy, format, dir)? {
            Some(Removed::Temporary) => temporaries += 1,
            Some(Removed::Stale) => stale += 1,
            None => {}
        }
    }
    if !quiet && temporaries + stale > 0 {
        let beyond = tidy
            .stale_from
            .map_or(String::new(), |f| format!(" numbered {f} or more"));
        eprintln!(
            "wisp: removed from {shown} what an earlier export left: {stale} frames{beyond}, {temporaries} temporary files"
        );
    }
    Ok(())
}

/// Creates `dir` if missing and checks that a file can be written into it (a probe file
/// named by the process and `tag`, so shards starting at once do not share one, removed at
/// once).
fn make_writable_dir(dir: &Path, tag: u32) -> Result<(), AppError> {
    let shown = dir.display();
    if dir.exists() && !dir.is_dir() {
        return Err(AppError::input(anyhow::anyhow!(
            "--out {shown}: exists and is not a directory"
        )));
    }
    std::fs::create_dir_all(dir)
        .with_context(|| format!("--out {shown}: cannot create the output directory"))
        .map_err(AppError::input)?;
    let probe = dir.join(format!(".wisp-write-test-{}-{tag}", std::process::id()));
    std::fs::write(&probe, b"")
        .with_context(|| format!("--out {shown}: cannot write files into the directory"))
        .map_err(AppError::input)?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// What [`tidy_entry`] removed.
enum Removed {
    /// A frame's temporary file.
    Temporary,
    /// A frame beyond the sequence.
    Stale,
}

/// Removes the directory entry if `tidy` allows it (a frame's temporary file, or a frame of
/// `format` beyond the sequence) and says what it removed. A non-file in the place of one of
/// this run's frames is an error; a file another process removed first is not.
fn tidy_entry(
    entry: &std::fs::DirEntry,
    tidy: &Tidy,
    format: FrameFormat,
    dir: &Path,
) -> Result<Option<Removed>, AppError> {
    let name = entry.file_name();
    let Some(name) = name.to_str() else {
        return Ok(None);
    };
    let Some(FrameName {
        index,
        extension,
        temporary,
    }) = frame_name(name)
    else {
        return Ok(None);
    };
    let is_file = entry.file_type().is_ok_and(|t| t.is_file());
    let own = tidy.own.contains(&index);
    let this_format = extension == format.extension();
    if !temporary && own && this_format {
        if !is_file && !entry.path().is_file() {
            return Err(AppError::input(anyhow::anyhow!(
                "--out {}: {name} is in the way (not a file, so this run cannot replace it)",
                dir.display()
            )));
        }
        return Ok(None);
    }
    let remove = if temporary {
        (own && this_format) || tidy.all_temporaries
    } else {
        this_format && tidy.stale_from.is_some_and(|from| index >= from)
    };
    if !is_file || !remove {
        return Ok(None);
    }
    match std::fs::remove_file(entry.path()) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => {
            return Err(AppError::input(anyhow::anyhow!(
                "{}: cannot remove it: {e}",
                entry.path().display()
            )));
        }
    }
    Ok(Some(if temporary {
        Removed::Temporary
    } else {
        Removed::Stale
    }))
}

/// A file name of wisp's frames, taken apart.
#[derive(Debug, PartialEq)]
struct FrameName<'a> {
    index: u32,
    /// `png` or `exr`.
    extension: &'a str,
    /// `.tmp`: the temporary name a frame is written under before its rename.
    temporary: bool,
}

/// `frame_00012.png` -> 12, png; `frame_00012.exr.tmp` -> 12, exr, temporary; anything else
/// (another extension, fewer than five digits) -> None.
fn frame_name(name: &str) -> Option<FrameName<'_>> {
    let rest = name.strip_prefix("frame_")?;
    let (rest, temporary) = match rest.strip_suffix(".tmp") {
        Some(r) => (r, true),
        None => (rest, false),
    };
    let (digits, extension) = rest.split_once('.')?;
    if !matches!(extension, "png" | "exr")
        || digits.len() < 5
        || !digits.bytes().all(|b| b.is_ascii_digit())
    {
        return None;
    }
    digits.parse().ok().map(|index| FrameName {
        index,
        extension,
        temporary,
    })
}

/// `DIR/frame_00012.png` (or `.exr`).
fn frame_path(dir: &Path, format: FrameFormat, index: u32) -> PathBuf {
    dir.join(format.file_name(index))
}

/// The frames of `indices` in `dir`, each with whether it is complete (`Ok`) or why not
/// (missing, cut short, corrupt, another size or format), checked in parallel.
fn find_complete_frames(
    dir: &Path,
    indices: std::ops::Range<u32>,
    format: FrameFormat,
    width: u32,
    height: u32,
) -> Vec<Result<(), FrameDefect>> {
    indices
        .into_par_iter()
        .map(|i| check_frame(&frame_path(dir, format, i), format, width, height))
        .collect()
}

/// The frames of a run and which of them `--resume` keeps.
#[derive(Clone, Debug, PartialEq)]
pub struct FramePlan {
    /// The run's frames, by number.
    pub indices: std::ops::Range<u32>,
    /// Per frame of `indices`: already complete on disk, kept.
    pub kept: Vec<bool>,
}

impl FramePlan {
    /// Frames to render.
    pub fn to_render(&self) -> usize {
        self.kept.iter().filter(|k| !**k).count()
    }

    /// Every frame is kept.
    pub fn nothing_to_render(&self) -> bool {
        self.to_render() == 0
    }

    /// The last frame to render (no frame after it needs the simulation).
    pub(super) fn last_to_render(&self) -> Option<u32> {
        self.indices
            .clone()
            .zip(&self.kept)
            .rev()
            .find(|(_, k)| !**k)
            .map(|(i, _)| i)
    }
}

/// Most frames whose defect `--resume` names one by one.
const DEFECTS_NAMED: usize = 10;

/// The frames of `indices` to render: all of them, or with `--resume` those not already
/// complete in the output directory (`width` x `height`, the output's format). Says on stderr
/// which frames on disk are kept, and which are rendered again and why (cut short, corrupt,
/// another size or format), unless quiet.
pub fn plan_frames(
    output: &FrameOutput,
    indices: std::ops::Range<u32>,
    width: u32,
    height: u32,
) -> FramePlan {
    let n = indices.len();
    if !output.resume {
        return FramePlan {
            indices,
            kept: vec![false; n],
        };
    }
    let checks = find_complete_frames(&output.dir, indices.clone(), output.format, width, height);
    let kept: Vec<bool> = checks.iter().map(Result::is_ok).collect();
    let plan = FramePlan { indices, kept };
    if output.quiet {
        return plan;
    }
    let defective: Vec<(u32, &FrameDefect)> = plan
        .indices
        .clone()
        .zip(&checks)
        .filter_map(|(i, c)| match c {
            Err(FrameDefect::Missing) | Ok(()) => None,
            Err(d) => Some((i, d)),
        })
        .collect();
    for (i, d) in defective.iter().take(DEFECTS_NAMED) {
        eprintln!(
            "wisp: --resume: {} {d}; rendering it again",
            output.format.file_name(*i)
        );
    }
    if defective.len() > DEFECTS_NAMED {
        eprintln!(
            "wisp: --resume: and {} more frames to render again",
            defective.len() - DEFECTS_NAMED
        );
    }
    let kept_n = n - plan.to_render();
    if plan.nothing_to_render() {
        eprintln!(
            "wisp: --resume: all {n} frames are already complete in {}; nothing to render",
            output.dir.display()
        );
        return plan;
    }
    let last = plan.last_to_render();
    let simulated_through = plan
        .indices
        .clone()
        .zip(&plan.kept)
        .filter(|(i, k)| **k && Some(*i) < last)
        .count();
    let through = if simulated_through > 0 && !output.independent_frames {
        format!(
            " (the simulation runs through the {simulated_through} kept frames before the last one to render)"
        )
    } else {
        String::new()
    };
    eprintln!(
        "wisp: --resume: {kept_n} of {n} frames are already complete in {} and kept; rendering {} ({} of them again){through}",
        output.dir.display(),
        plan.to_render(),
        defective.len()
    );
    plan
}

#[cfg(test)]
mod tests;
