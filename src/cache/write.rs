//! Writing a cache as the frames are simulated: the header first, then one record per call,
//! into `NAME.tmp` beside the cache, renamed to `NAME` once every record is written and
//! synced. An interrupted run leaves the temporary file only, never a cache that looks whole.

use super::error::CacheError;
use super::format::CacheHeader;
use super::state;
use crate::sim::SimState;
use glam::Vec3;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// A cache being written. Records go in order: the settled state, then frames 0, 1, ...
pub struct CacheWriter {
    file: BufWriter<File>,
    path: PathBuf,
    temporary: PathBuf,
    header: CacheHeader,
    /// Records written so far.
    written: u64,
    /// One record's bytes (reused).
    record: Vec<u8>,
}

impl CacheWriter {
    /// Creates `path.tmp` and writes the header. `path` must not be a directory or anything
    /// but a regular file (writing over a device would replace it), and its folder must exist.
    pub fn create(path: &Path, header: CacheHeader) -> Result<Self, CacheError> {
        let name = path.display().to_string();
        let bad = |reason: &str| CacheError::BadOutput {
            file: name.clone(),
            reason: reason.to_string(),
        };
        match std::fs::metadata(path) {
            Ok(m) if m.is_dir() => return Err(bad("is a directory, not a file name")),
            Ok(m) if !m.is_file() => {
                return Err(bad(
                    "exists and is not a regular file (a device or a pipe); choose a file name",
                ));
            }
            _ => {}
        }
        let Some(file_name) = path.file_name() else {
            return Err(bad("has no file name"));
        };
        let mut tmp_name = file_name.to_os_string();
        tmp_name.push(".tmp");
        let temporary = path.with_file_name(tmp_name);
        let write_err = |error| CacheError::Write {
            file: name.clone(),
            error,
        };
        let file = File::create(&temporary).map_err(|e| {
            if e.kind() == std::io::ErrorKind::NotFound {
                bad("its folder does not exist")
            } else {
                write_err(e)
            }
        })?;
        let mut file = BufWriter::new(file);
        file.write_all(&header.encode()).map_err(write_err)?;
        Ok(Self {
            file,
            path: path.to_path_buf(),
            temporary,
            header,
            written: 0,
            record: Vec::new(),
        })
    }

    /// The header being written.
    pub fn header(&self) -> &CacheHeader {
        &self.header
    }

    /// Appends the next record: the guide state of `state` (its `positions`, the only field
    /// rendering reads) at frame time `frame_time_s` (the time the frame is rendered at, not
    /// the simulation's last step instant). The first call stores the settled state at time
    /// 0, the following ones frames 0, 1, ...
    pub fn write_sim_state(
        &mut self,
        frame_time_s: f64,
        state: &SimState,
    ) -> Result<(), CacheError> {
        self.write_positions(frame_time_s, &state.positions)
    }

    /// Appends the next record from positions (as [`CacheWriter::write_sim_state`]).
    pub fn write_positions(
        &mut self,
        frame_time_s: f64,
        positions: &[Vec3],
    ) -> Result<(), CacheError> {
        let name = || self.path.display().to_string();
        if positions.len() != self.header.particles as usize {
            return Err(CacheError::Invalid {
                file: name(),
                reason: format!(
                    "record {} has {} particles, the header says {}",
                    self.written,
                    positions.len(),
                    self.header.particles
                ),
            });
        }
        if self.written > self.header.frames as u64 {
            return Err(CacheError::Invalid {
                file: name(),
                reason: format!(
                    "the header promises {} frames; no more records fit",
                    self.header.frames
                ),
            });
        }
        state::encode(self.written, frame_time_s, positions, &mut self.record);
        self.file
            .write_all(&self.record)
            .map_err(|error| CacheError::Write {
                file: name(),
                error,
            })?;
        self.written += 1;
        Ok(())
    }

    /// Records written so far (the settled state counts as one).
    pub fn records_written(&self) -> u64 {
        self.written
    }

    /// Flushes and syncs the file and renames it into place; fails if a record is missing.
    pub fn finish(self) -> Result<(), CacheError> {
        let name = self.path.display().to_string();
        let want = self.header.frames as u64 + 1;
        if self.written != want {
            return Err(CacheError::Invalid {
                file: name,
                reason: format!(
                    "{} of {want} records written (the settled state and {} frames)",
                    self.written, self.header.frames
                ),
            });
        }
        let write_err = |error| CacheError::Write {
            file: name.clone(),
            error,
        };
        let file = self
            .file
            .into_inner()
            .map_err(|e| write_err(e.into_error()))?;
        file.sync_all().map_err(write_err)?;
        drop(file);
        std::fs::rename(&self.temporary, &self.path).map_err(write_err)
    }
}
