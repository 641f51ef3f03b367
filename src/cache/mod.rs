//! Simulation caches: the guide particles of every frame of a run, written once by `wisp
//! simulate` and rendered any number of times, in any frame range, by any number of machines.
//!
//! # What a cache holds, and why that is enough
//! A frame's picture depends on the simulation only through the guide particles' world
//! positions (`SimState::positions`): interpolation, the light map, shading and raster are
//! functions of those positions, of the motion's pose at the frame's time (sampled again from
//! the motion, which the cache's motion digest pins) and of the scene (light, camera, shader,
//! size). The camera that follows the head is framed once on the hair as it settled at time 0,
//! so the cache stores that settled state as well. A cache therefore stores, per frame, the
//! frame's time and every guide particle's position as the f32 bits the simulation left, and
//! [`Engine::set_guide_state`](crate::engine::Engine::set_guide_state) puts them back: a frame
//! rendered from the cache is the same bytes as the frame rendered in one run (tested in
//! `tests/lib/cache.rs` and, through the binary and the local shard runner, `tests/cli/deploy.rs`).
//! The simulation is deterministic for any thread count, so it does not matter how many
//! threads simulated or render.
//!
//! Not stored: the integrator's velocities, the positions before the last step and the step
//! clock. A cache replays a simulation; it does not resume one.
//!
//! What the simulation itself depended on is recorded in the header: the hairstyle and motion
//! (as digests, so a cache is refused for another hairstyle or motion with a message saying
//! which) and the frame times. The motion does not depend on the light, the map or the image:
//! self-collision reads the simulator's own density grid (`sim::density`), so rendering with
//! another light, camera, shader, map size or image size gives the bytes a single run with
//! those flags gives. The header also records the light direction, map resolution and solids
//! of the `simulate` run, for the record (format version 1 keeps them).
//!
//! # Format (version 1, little-endian)
//! A header ([`format::CacheHeader`], its own CRC-32 last), then `frames + 1` records of the
//! same size: record 0 is the settled state at time 0, record `k + 1` is frame `k`. A record
//! is the frame time (f64 seconds), `particles` positions (3 × f32 metres, guide-major as
//! `GuideSet::rest`) and a CRC-32 of the record index and the record. Fixed-size records let a
//! shard seek straight to its frames; the file's size must equal what the header's counts
//! imply, which is checked before anything is allocated from those counts. See
//! [`format`](mod@format) for the byte layout.
//!
//! # Checks on reading
//! Everything a hostile or damaged file can say is checked, and refused with the file name,
//! the field and the rule ([`CacheError`]): the magic and version, the header's checksum,
//! counts against the file's size, ranges of every header field, each record's checksum (a
//! flipped byte anywhere is caught), each record's time against the header's frame times,
//! and each position: finite, and within twice the reach of hair from the head at that
//! frame ([`CacheReader::read_frame`]).

pub mod digest;
mod error;
pub mod format;
mod read;
mod state;
mod write;

pub use digest::{Digest, hairstyle_digest, motion_digest};
pub use error::CacheError;
pub use format::{CacheHeader, MAX_FRAMES};
pub use read::{CacheReader, Expected};
pub use write::CacheWriter;
