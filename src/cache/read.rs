//! Reading a cache: the header is checked against the file's size and against the run that
//! wants to render it before any record is read; records are then read one at a time, by
//! seeking (fixed-size records), each checked before its positions are handed out.

use super::digest::{Digest, hairstyle_digest, motion_digest};
use super::error::CacheError;
use super::format::{self, CHECKSUM_BYTES, CacheHeader, FIXED_HEADER_BYTES};
use super::state::{self, RecordError};
use crate::hairstyle::Hairstyle;
use crate::input::{ReadError, open_regular, printable};
use crate::motion::{Motion, Pose};
use glam::Vec3;
use std::fs::File;
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

/// What the run that reads a cache needs it to be.
#[derive(Clone, Debug, PartialEq)]
pub struct Expected {
    /// The hairstyle's name and digest.
    pub hairstyle_name: String,
    pub hairstyle_digest: Digest,
    /// The motion's label (for messages) and digest.
    pub motion_label: String,
    pub motion_digest: Digest,
    /// Guide particles per frame and per guide.
    pub particles: u32,
    pub points_per_guide: u32,
    /// Farthest a particle may be from the head centre, metres: twice the reach of the
    /// longest hair from the farthest root (head size + 2 × longest guide). Rigid links keep
    /// every valid state well within it.
    pub max_distance_m: f32,
}

impl Expected {
    /// What a run with `style` and `motion` (described by `motion_label` in messages) needs.
    pub fn new(style: &Hairstyle, motion: &Motion, motion_label: &str) -> Self {
        let points_per_guide = style.guides.links + 1;
        Self {
            hairstyle_name: style.name.clone(),
            hairstyle_digest: hairstyle_digest(style),
            motion_label: motion_label.to_string(),
            motion_digest: motion_digest(motion),
            particles: (3 * style.wisps.count as u64 * points_per_guide as u64).min(u32::MAX as u64)
                as u32,
            points_per_guide,
            max_distance_m: style.head_size_m() + 2.0 * style.max_length_m(),
        }
    }
}

/// An open, checked cache.
pub struct CacheReader {
    file: File,
    name: String,
    header: CacheHeader,
    header_bytes: u64,
    record_bytes: u64,
    max_distance_m: f32,
    /// One record's bytes, and its positions (allocated at the first read).
    bytes: Vec<u8>,
    positions: Vec<Vec3>,
    pose: Pose,
}

impl CacheReader {
    /// Opens `path` and checks its header: format, checksum, field ranges, the file's size
    /// against the header's counts (before anything is allocated from them), and that the
    /// cache was made for `expected`'s hairstyle and motion.
    pub fn open(path: &Path, expected: &Expected) -> Result<Self, CacheError> {
        let name = path.display().to_string();
        let read_err = |error| CacheError::Read {
            file: name.clone(),
            error,
        };
        let bad = |reason: String| CacheError::Invalid {
            file: name.clone(),
            reason,
        };
        let (mut file, len) = open_regular(path).map_err(read_err)?;
        let io = |e: std::io::Error| read_err(ReadError::Io(e));
        // The fixed part says how long the whole header is (at most 514 + 132 bytes).
        let mut head = Vec::new();
        (&mut file)
            .take((FIXED_HEADER_BYTES + CHECKSUM_BYTES) as u64)
            .read_to_end(&mut head)
            .map_err(io)?;
        let header_bytes = format::parse_fixed(&head, len, &name)?;
        if header_bytes > head.len() {
            let mut rest = vec![0u8; header_bytes - head.len()];
            file.read_exact(&mut rest).map_err(io)?;
            head.extend_from_slice(&rest);
        }
        let header = CacheHeader::decode(&head, &name)?;
        let want = header.file_bytes();
        if len != want {
            let records =
                (len.saturating_sub(header_bytes as u64)) as f64 / header.record_bytes() as f64;
            return Err(bad(format!(
                "{}: the file has {len} bytes, but its header ({} frames of {} particles) needs {want} (it holds {records:.2} records of {} bytes)",
                if len < want { "truncated" } else { "too long" },
                header.frames,
                header.particles,
                header.record_bytes()
            )));
        }
        check_made_for(&header, expected, &name)?;
        Ok(Self {
            file,
            name,
            header_bytes: header_bytes as u64,
            record_bytes: header.record_bytes(),
            header,
            max_distance_m: expected.max_distance_m,
            bytes: Vec::new(),
            positions: Vec::new(),
            pose: Pose::default(),
        })
    }

    /// The checked header.
    pub fn header(&self) -> &CacheHeader {
        &self.header
    }

    /// The settled guide state at time 0 (what the camera is framed on).
    pub fn read_settled(&mut self, motion: &Motion) -> Result<&[Vec3], CacheError> {
        self.read_record(0, 0.0, "the settled state", motion)
    }

    /// The guide particles of frame `index` (at [`CacheHeader::frame_time_s`]), after checking
    /// the record's checksum, its time, and every position: finite and within
    /// [`Expected::max_distance_m`] of the head centre of `motion` at that time.
    pub fn read_frame(&mut self, index: u32, motion: &Motion) -> Result<&[Vec3], CacheError> {
        if index >= self.header.frames {
            return Err(CacheError::Invalid {
                file: self.name.clone(),
                reason: format!(
                    "frame {index} was asked for; the cache holds frames 0 to {}",
                    self.header.frames - 1
                ),
            });
        }
        let t_s = self.header.frame_time_s(index);
        self.read_record(index as u64 + 1, t_s, &format!("frame {index}"), motion)
    }

    fn read_record(
        &mut self,
        record: u64,
        want_time_s: f64,
        what: &str,
        motion: &Motion,
    ) -> Result<&[Vec3], CacheError> {
        let name = &self.name;
        let bad = |reason: String| CacheError::Invalid {
            file: name.clone(),
            reason: format!("{what}: {reason}"),
        };
        // The size check in `open` bounds this allocation by the file's size.
        self.bytes.resize(self.record_bytes as usize, 0);
        let at = self.header_bytes + record * self.record_bytes;
        let read = self
            .file
            .seek(SeekFrom::Start(at))
            .and_then(|_| self.file.read_exact(&mut self.bytes));
        if let Err(e) = read {
            return Err(if e.kind() == std::io::ErrorKind::UnexpectedEof {
                bad("truncated while it was read (the file shrank)".into())
            } else {
                CacheError::Read {
                    file: name.clone(),
                    error: ReadError::Io(e),
                }
            });
        }
        let time_s = match state::decode(record, &self.bytes, &mut self.positions) {
            Ok(t) => t,
            Err(RecordError::Checksum(stored, actual)) => {
                return Err(bad(format!(
                    "checksum is {stored:#010x}, the record's bytes give {actual:#010x}: the file is damaged"
                )));
            }
            Err(RecordError::NotFinite(i, p)) => {
                return Err(bad(format!(
                    "particle {i} is at {p}, not a finite position"
                )));
            }
        };
        if time_s.to_bits() != want_time_s.to_bits() {
            return Err(bad(format!(
                "its time is {time_s} s, the header's time for it is {want_time_s} s"
            )));
        }
        motion.sample_into(want_time_s as f32, &mut self.pose);
        let head = Vec3::from(self.pose.head.translation);
        let limit = self.max_distance_m;
        if let Some((i, p)) = self.positions.iter().enumerate().find(|(_, p)| {
            let d = p.distance(head);
            d.is_nan() || d > limit
        }) {
            return Err(bad(format!(
                "particle {i} is at {p}, {:.3} m from the head centre, farther than hair can reach ({limit:.3} m)",
                p.distance(head)
            )));
        }
        Ok(&self.positions)
    }
}

/// Refuses a cache made for another hairstyle, motion or guide layout, saying which.
fn check_made_for(h: &CacheHeader, e: &Expected, file: &str) -> Result<(), CacheError> {
    let mismatch = |reason: String| CacheError::Mismatch {
        file: file.to_string(),
        reason,
    };
    if h.hairstyle_digest != e.hairstyle_digest {
        return Err(mismatch(format!(
            "was simulated for hairstyle \"{}\" (digest {}), not for this hairstyle \"{}\" (digest {}); render it with the hairstyle it was made for, or simulate this one",
            printable(&h.hairstyle_name),
            h.hairstyle_digest.short(),
            printable(&e.hairstyle_name),
            e.hairstyle_digest.short()
        )));
    }
    if h.motion_digest != e.motion_digest {
        return Err(mismatch(format!(
            "was simulated with motion {} (digest {}), not with this motion, {} (digest {}); render it with the motion flags it was made with (--animation, --clip, --head-joint, --speed, --still), or simulate this motion",
            printable(&h.motion_label),
            h.motion_digest.short(),
            printable(&e.motion_label),
            e.motion_digest.short()
        )));
    }
    if h.particles != e.particles || h.points_per_guide != e.points_per_guide {
        return Err(mismatch(format!(
            "holds {} guide particles of {} per guide, this hairstyle has {} of {} (the cache was made by a wisp that builds guides differently: simulate again)",
            h.particles, h.points_per_guide, e.particles, e.points_per_guide
        )));
    }
    Ok(())
}
