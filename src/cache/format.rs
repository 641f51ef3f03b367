//! The byte layout of a simulation cache (version 1, little-endian) and its header.
//!
//! ```text
//! header
//!   0   8   magic "WISPSIM\0"
//!   8   4   version (u32, 1)
//!  12   4   header bytes (u32): this header with its names and checksum
//!  16   4   frames (u32, 1..=100,000)
//!  20   4   guide particles per record (u32)
//!  24   4   particles per guide (u32, 2..=257)
//!  28   4   frames per second (f32, (0, 1000])
//!  32   8   time of frame 0, seconds (f64, finite, >= 0)
//!  40   8   settle time before frame 0, seconds (f64, finite, >= 0)
//!  48  32   hairstyle digest (SHA-256, see `digest`)
//!  80  32   motion digest (SHA-256)
//! 112  12   light direction of the simulation's light map (3 × f32, unit)
//! 124   4   cells per axis of that map (u32, 4..=1024)
//! 128   1   flags: 1 simulated, 2 self-collision, 4 head and body in the map
//! 129   1   hairstyle name length n (u8)
//! 130   1   motion label length m (u8)
//! 131   1   0
//! 132   n   hairstyle name (UTF-8)
//! 132+n m   motion label (UTF-8)
//!  ...  4   CRC-32 of every header byte before it
//! records, `frames + 1` of them, each `8 + 12 · particles + 4` bytes
//!   0   8   time, seconds (f64)
//!   8  12p  positions (3 × f32 metres per particle, guide-major)
//!   .   4   CRC-32 of the record index (u64) followed by the record's bytes before it
//! ```

use super::digest::Digest;
use super::error::CacheError;
use glam::Vec3;

/// Largest number of frames a cache holds (as `wisp render --frames`).
pub const MAX_FRAMES: u32 = 100_000;
/// First bytes of every cache.
pub const MAGIC: [u8; 8] = *b"WISPSIM\0";
/// The version this build writes and reads.
pub const VERSION: u32 = 1;
/// Bytes of the header before its names.
pub const FIXED_HEADER_BYTES: usize = 132;
/// Bytes of a checksum.
pub const CHECKSUM_BYTES: usize = 4;
/// Bytes of a record's time.
pub const TIME_BYTES: usize = 8;
/// Bytes of one stored position.
pub const POSITION_BYTES: usize = 12;
/// Most particles per guide (`hairstyle::MAX_GUIDE_LINKS` + 1).
pub const MAX_POINTS_PER_GUIDE: u32 = crate::hairstyle::MAX_GUIDE_LINKS + 1;
/// Most guide particles per record: three guides per wisp at the hairstyle limits.
pub const MAX_PARTICLES: u64 = 3 * crate::hairstyle::MAX_WISPS as u64 * MAX_POINTS_PER_GUIDE as u64;
/// Longest stored name, bytes.
pub const MAX_NAME_BYTES: usize = 255;
/// Flag bits.
const FLAG_SIMULATED: u8 = 1;
const FLAG_SELF_COLLISION: u8 = 2;
const FLAG_SOLIDS: u8 = 4;

/// Byte offsets of the header's fields (for tools and tests that edit a cache).
pub mod offset {
    pub const VERSION: usize = 8;
    pub const HEADER_BYTES: usize = 12;
    pub const FRAMES: usize = 16;
    pub const PARTICLES: usize = 20;
    pub const POINTS_PER_GUIDE: usize = 24;
    pub const FPS: usize = 28;
    pub const START_S: usize = 32;
    pub const SETTLE_S: usize = 40;
    pub const HAIRSTYLE_DIGEST: usize = 48;
    pub const MOTION_DIGEST: usize = 80;
    pub const LIGHT_DIR: usize = 112;
    pub const MAP_RES: usize = 124;
    pub const FLAGS: usize = 128;
    pub const NAME_LEN: usize = 129;
    pub const LABEL_LEN: usize = 130;
    pub const RESERVED: usize = 131;
}

/// What a cache says about the run that made it.
#[derive(Clone, Debug, PartialEq)]
pub struct CacheHeader {
    /// Frames stored (the settled state is stored besides them).
    pub frames: u32,
    /// Guide particles per frame.
    pub particles: u32,
    /// Particles per guide (links + 1).
    pub points_per_guide: u32,
    /// Frame rate, frames per second.
    pub fps: f32,
    /// Time of frame 0 in seconds of the motion (after wrapping into one loop).
    pub start_s: f64,
    /// Seconds the hair settled with the head at the first pose before time 0.
    pub settle_s: f64,
    /// Digest of the hairstyle ([`super::hairstyle_digest`]).
    pub hairstyle_digest: Digest,
    /// Digest of the motion ([`super::motion_digest`]).
    pub motion_digest: Digest,
    /// Light direction of the `simulate` run (unit; informational: the motion does not depend on it).
    pub light_dir: Vec3,
    /// Map cells per axis of the `simulate` run (informational).
    pub map_res: u32,
    /// The guides were simulated (false: carried rigidly in their rest pose).
    pub simulated: bool,
    /// Density-based self-collision was on.
    pub self_collision: bool,
    /// The `simulate` run drew the head and body (informational).
    pub draw_solids: bool,
    /// The hairstyle's name, for messages.
    pub hairstyle_name: String,
    /// What the motion was (clip, file, speed), for messages.
    pub motion_label: String,
}

impl CacheHeader {
    /// Time of frame `index` in seconds: `start_s + index / fps`, computed as `wisp render`
    /// computes it, so a frame rendered from the cache samples the motion at the same instant.
    pub fn frame_time_s(&self, index: u32) -> f64 {
        self.start_s + index as f64 / self.fps as f64
    }

    /// Bytes of one record.
    pub fn record_bytes(&self) -> u64 {
        record_bytes(self.particles as u64)
    }

    /// Bytes of the header as written (names included).
    pub fn header_bytes(&self) -> usize {
        FIXED_HEADER_BYTES
            + truncated(&self.hairstyle_name).len()
            + truncated(&self.motion_label).len()
            + CHECKSUM_BYTES
    }

    /// Bytes of the whole file: the header and `frames + 1` records.
    pub fn file_bytes(&self) -> u64 {
        self.header_bytes() as u64 + (self.frames as u64 + 1) * self.record_bytes()
    }

    /// The header's bytes, checksum last.
    pub fn encode(&self) -> Vec<u8> {
        let name = truncated(&self.hairstyle_name).as_bytes();
        let label = truncated(&self.motion_label).as_bytes();
        let mut b = Vec::with_capacity(self.header_bytes());
        b.extend_from_slice(&MAGIC);
        b.extend_from_slice(&VERSION.to_le_bytes());
        b.extend_from_slice(&(self.header_bytes() as u32).to_le_bytes());
        b.extend_from_slice(&self.frames.to_le_bytes());
        b.extend_from_slice(&self.particles.to_le_bytes());
        b.extend_from_slice(&self.points_per_guide.to_le_bytes());
        b.extend_from_slice(&self.fps.to_le_bytes());
        b.extend_from_slice(&self.start_s.to_le_bytes());
        b.extend_from_slice(&self.settle_s.to_le_bytes());
        b.extend_from_slice(&self.hairstyle_digest.0);
        b.extend_from_slice(&self.motion_digest.0);
        for c in self.light_dir.to_array() {
            b.extend_from_slice(&c.to_le_bytes());
        }
        b.extend_from_slice(&self.map_res.to_le_bytes());
        let flags = (FLAG_SIMULATED * self.simulated as u8)
            | (FLAG_SELF_COLLISION * self.self_collision as u8)
            | (FLAG_SOLIDS * self.draw_solids as u8);
        b.extend_from_slice(&[flags, name.len() as u8, label.len() as u8, 0]);
        debug_assert_eq!(b.len(), FIXED_HEADER_BYTES);
        b.extend_from_slice(name);
        b.extend_from_slice(label);
        let crc = crc32fast::hash(&b);
        b.extend_from_slice(&crc.to_le_bytes());
        b
    }

    /// Reads and checks a header from `bytes`, the first bytes of a file: at least the whole
    /// header (its length is known from [`parse_fixed`]), or the whole file when it is shorter.
    /// The checks run in the order of the layout: the fixed part, the checksum, each field's
    /// range, the flags and reserved byte, the names.
    pub fn decode(bytes: &[u8], file: &str) -> Result<CacheHeader, CacheError> {
        let bad = |reason: String| CacheError::Invalid {
            file: file.to_string(),
            reason,
        };
        let header_bytes = parse_fixed(bytes, bytes.len() as u64, file)?;
        if bytes.len() < header_bytes {
            return Err(bad(format!(
                "truncated: the header is {header_bytes} bytes, the file has {}",
                bytes.len()
            )));
        }
        check_checksum(&bytes[..header_bytes]).map_err(bad)?;
        let mut header = Self::read_fields(bytes);
        header.check_ranges().map_err(bad)?;
        check_flags(bytes).map_err(bad)?;
        (header.hairstyle_name, header.motion_label) = read_names(bytes).map_err(bad)?;
        Ok(header)
    }

    /// The header's fields as stored (names left empty), from bytes that hold the fixed part.
    fn read_fields(bytes: &[u8]) -> CacheHeader {
        let f32_at = |at: usize| f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap_or([0; 4]));
        let f64_at = |at: usize| f64::from_le_bytes(bytes[at..at + 8].try_into().unwrap_or([0; 8]));
        let digest_at = |at: usize| Digest(bytes[at..at + 32].try_into().unwrap_or([0; 32]));
        let flags = bytes[offset::FLAGS];
        CacheHeader {
            frames: u32_at(bytes, offset::FRAMES),
            particles: u32_at(bytes, offset::PARTICLES),
            points_per_guide: u32_at(bytes, offset::POINTS_PER_GUIDE),
            fps: f32_at(offset::FPS),
            start_s: f64_at(offset::START_S),
            settle_s: f64_at(offset::SETTLE_S),
            hairstyle_digest: digest_at(offset::HAIRSTYLE_DIGEST),
            motion_digest: digest_at(offset::MOTION_DIGEST),
            light_dir: Vec3::new(
                f32_at(offset::LIGHT_DIR),
                f32_at(offset::LIGHT_DIR + 4),
                f32_at(offset::LIGHT_DIR + 8),
            ),
            map_res: u32_at(bytes, offset::MAP_RES),
            simulated: flags & FLAG_SIMULATED != 0,
            self_collision: flags & FLAG_SELF_COLLISION != 0,
            draw_solids: flags & FLAG_SOLIDS != 0,
            hairstyle_name: String::new(),
            motion_label: String::new(),
        }
    }

    /// Every numeric field in its range (the layout's table); the error names the field.
    fn check_ranges(&self) -> Result<(), String> {
        let (frames, particles, points_per_guide) =
            (self.frames, self.particles, self.points_per_guide);
        let (fps, light_dir, map_res) = (self.fps, self.light_dir, self.map_res);
        if !(1..=MAX_FRAMES).contains(&frames) {
            return Err(format!("frames is {frames}, outside 1..={MAX_FRAMES}"));
        }
        if !(2..=MAX_POINTS_PER_GUIDE).contains(&points_per_guide) {
            return Err(format!(
                "particles per guide is {points_per_guide}, outside 2..={MAX_POINTS_PER_GUIDE}"
            ));
        }
        if particles == 0
            || particles as u64 > MAX_PARTICLES
            || !particles.is_multiple_of(points_per_guide)
        {
            return Err(format!(
                "particles is {particles}: it must be a whole number of guides of {points_per_guide} particles, at most {MAX_PARTICLES}"
            ));
        }
        if !(fps.is_finite() && fps > 0.0 && fps <= 1000.0) {
            return Err(format!("fps is {fps}, outside (0, 1000]"));
        }
        for (name, v) in [("start time", self.start_s), ("settle time", self.settle_s)] {
            if !(v.is_finite() && (0.0..=1e9).contains(&v)) {
                return Err(format!("{name} is {v} s, outside [0, 1e9]"));
            }
        }
        if !(light_dir.is_finite() && (light_dir.length() - 1.0).abs() < 1e-3) {
            return Err(format!("light direction is {light_dir}, not a unit vector"));
        }
        if !(4..=1024).contains(&map_res) {
            return Err(format!("map resolution is {map_res}, outside 4..=1024"));
        }
        Ok(())
    }
}

/// Refuses a header (`header`, checksum last) whose stored CRC-32 differs from its bytes'.
fn check_checksum(header: &[u8]) -> Result<(), String> {
    let body = &header[..header.len() - CHECKSUM_BYTES];
    let stored = u32_at(header, header.len() - CHECKSUM_BYTES);
    let actual = crc32fast::hash(body);
    if stored != actual {
        return Err(format!(
            "header checksum is {stored:#010x}, the header's bytes give {actual:#010x}: the file is damaged"
        ));
    }
    Ok(())
}

/// Refuses unknown flag bits and a reserved byte that is not 0.
fn check_flags(bytes: &[u8]) -> Result<(), String> {
    let flags = bytes[offset::FLAGS];
    if flags & !(FLAG_SIMULATED | FLAG_SELF_COLLISION | FLAG_SOLIDS) != 0 {
        return Err(format!("flags byte is {flags:#04x}, with unknown bits set"));
    }
    if bytes[offset::RESERVED] != 0 {
        return Err(format!(
            "reserved byte {} is {}, not 0",
            offset::RESERVED,
            bytes[offset::RESERVED]
        ));
    }
    Ok(())
}

/// The hairstyle name and motion label, each UTF-8, after the fixed part.
fn read_names(bytes: &[u8]) -> Result<(String, String), String> {
    let (name_len, label_len) = (
        bytes[offset::NAME_LEN] as usize,
        bytes[offset::LABEL_LEN] as usize,
    );
    let text = |at: usize, len: usize, what: &str| {
        String::from_utf8(bytes[at..at + len].to_vec())
            .map_err(|_| format!("the {what} is not UTF-8"))
    };
    Ok((
        text(FIXED_HEADER_BYTES, name_len, "hairstyle name")?,
        text(FIXED_HEADER_BYTES + name_len, label_len, "motion label")?,
    ))
}

/// Checks the fixed part of a header (magic, version, length) in `bytes`, the start of a file
/// of `file_len` bytes, and returns the header's length in bytes.
pub fn parse_fixed(bytes: &[u8], file_len: u64, file: &str) -> Result<usize, CacheError> {
    let bad = |reason: String| CacheError::Invalid {
        file: file.to_string(),
        reason,
    };
    if bytes.len() < MAGIC.len() || bytes[..MAGIC.len()] != MAGIC {
        return Err(bad(
            "not a wisp simulation cache (it does not start with WISPSIM; make one with `wisp simulate`)"
                .into(),
        ));
    }
    if bytes.len() < FIXED_HEADER_BYTES + CHECKSUM_BYTES {
        return Err(bad(format!(
            "truncated: {file_len} bytes, shorter than a cache header ({} bytes)",
            FIXED_HEADER_BYTES + CHECKSUM_BYTES
        )));
    }
    let version = u32_at(bytes, offset::VERSION);
    if version != VERSION {
        return Err(bad(format!(
            "version is {version}; this wisp reads version {VERSION} (simulate again with this wisp)"
        )));
    }
    let header_bytes = u32_at(bytes, offset::HEADER_BYTES) as usize;
    let names = bytes[offset::NAME_LEN] as usize + bytes[offset::LABEL_LEN] as usize;
    if header_bytes != FIXED_HEADER_BYTES + names + CHECKSUM_BYTES {
        return Err(bad(format!(
            "header length is {header_bytes} bytes, but its names need {}",
            FIXED_HEADER_BYTES + names + CHECKSUM_BYTES
        )));
    }
    if header_bytes as u64 > file_len {
        return Err(bad(format!(
            "truncated: the header is {header_bytes} bytes, the file has {file_len}"
        )));
    }
    Ok(header_bytes)
}

/// Bytes of a record of `particles` positions.
pub fn record_bytes(particles: u64) -> u64 {
    (TIME_BYTES + CHECKSUM_BYTES) as u64 + particles * POSITION_BYTES as u64
}

/// The longest prefix of `s` of at most [`MAX_NAME_BYTES`] bytes that ends on a character.
fn truncated(s: &str) -> &str {
    let mut end = s.len().min(MAX_NAME_BYTES);
    while !s.is_char_boundary(end) {
        end -= 1;
    }
    &s[..end]
}

fn u32_at(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap_or([0; 4]))
}

#[cfg(test)]
mod tests;
