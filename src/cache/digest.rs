//! Digests that tie a cache to the hairstyle and motion it was simulated with (SHA-256).
//!
//! - **Hairstyle**: the validated hairstyle as JSON (`serde_json` of [`Hairstyle`], every
//!   field, defaults filled in), so the same hairstyle written with other spacing, field order
//!   or omitted defaults has the same digest, and any change of a value (geometry, dynamics,
//!   fibre, seed, name) gives another.
//! - **Motion**: the motion as the hair sees it: the clip's name, length and speed, and the
//!   head transform and body spheres sampled at 240 Hz over one loop of the clip (at most
//!   [`MAX_MOTION_SAMPLES`] samples, evenly spread over longer loops). It pins the file, the
//!   clip, the head joint, the fit and the speed together, whatever path the file is read
//!   from. Two motions equal at every sample but different between them would share a digest;
//!   the simulation's 240 Hz steps would then see nearly the same motion.

use crate::hairstyle::Hairstyle;
use crate::motion::{Motion, Pose};
use sha2::{Digest as _, Sha256};

/// Pose samples per second of the motion digest.
pub const MOTION_SAMPLE_RATE_HZ: f64 = 240.0;
/// Most pose samples in a motion digest (a loop of about 7 minutes at 240 Hz; longer loops
/// are sampled more sparsely). About 0.1 s of sampling.
pub const MAX_MOTION_SAMPLES: u64 = 100_000;

/// A SHA-256 digest.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Digest(pub [u8; 32]);

impl Digest {
    /// The first 12 hexadecimal digits, enough to tell digests apart in a message.
    pub fn short(&self) -> String {
        self.0[..6].iter().map(|b| format!("{b:02x}")).collect()
    }
}

impl std::fmt::Display for Digest {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for b in self.0 {
            write!(f, "{b:02x}")?;
        }
        Ok(())
    }
}

impl std::fmt::Debug for Digest {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Digest({})", self.short())
    }
}

/// Digest of a hairstyle (see the module doc).
pub fn hairstyle_digest(style: &Hairstyle) -> Digest {
    let mut h = Sha256::new();
    h.update(b"wisp hairstyle digest 1\0");
    match serde_json::to_vec(style) {
        Ok(json) => h.update(&json),
        // Not reached for a validated hairstyle (its numbers are finite); still a digest.
        Err(_) => h.update(format!("{style:?}").as_bytes()),
    }
    Digest(h.finalize().into())
}

/// Digest of a motion (see the module doc).
pub fn motion_digest(motion: &Motion) -> Digest {
    let mut h = Sha256::new();
    h.update(b"wisp motion digest 1\0");
    h.update(motion.clip_name().as_bytes());
    h.update([0]);
    h.update(motion.duration_s().to_le_bytes());
    h.update(motion.speed().to_le_bytes());
    let loop_s = motion.duration_s() as f64 / (motion.speed() as f64).abs();
    let samples = if loop_s.is_finite() && loop_s > 0.0 {
        ((loop_s * MOTION_SAMPLE_RATE_HZ).ceil() as u64).clamp(1, MAX_MOTION_SAMPLES)
    } else {
        0
    };
    h.update(samples.to_le_bytes());
    let mut pose = Pose::default();
    for k in 0..=samples {
        let t_s = if samples == 0 {
            0.0
        } else {
            loop_s * k as f64 / samples as f64
        };
        motion.sample_into(t_s as f32, &mut pose);
        for v in pose.head.to_cols_array() {
            h.update(v.to_le_bytes());
        }
        h.update((pose.spheres.len() as u64).to_le_bytes());
        for s in &pose.spheres {
            for v in s.center.to_array() {
                h.update(v.to_le_bytes());
            }
            h.update(s.radius_m.to_le_bytes());
        }
    }
    Digest(h.finalize().into())
}

#[cfg(test)]
mod tests;
