//! Simulation caches for the hostile tests: a small valid seed made by simulating a tiny
//! hairstyle on the dance, the expectations that go with it, and edits that keep every
//! checksum valid (`reseal`), so that the checks behind the checksums are reached too.

use super::Rng;
use super::mutate::FLOATS;
use std::sync::OnceLock;
use wisp::cache::format::{
    CHECKSUM_BYTES, FIXED_HEADER_BYTES, POSITION_BYTES, TIME_BYTES, offset, record_bytes,
};
use wisp::cache::{CacheHeader, CacheWriter, Expected};
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

/// Frames in the seed cache.
pub const SEED_FRAMES: u32 = 3;

/// A hairstyle with only the required fields (4 wisps of 3 links: 48 guide particles).
pub const SEED_HAIRSTYLE: &str = r#"{"name": "min", "head": {"radii_m": [0.08, 0.1, 0.09]},
 "scalp": {"max_polar_deg": 100, "front_polar_deg": 50},
 "wisps": {"count": 4, "radius_m": 0.01, "strands_per_wisp": 2},
 "guides": {"links": 3, "length_m": 0.1}, "strands": {"points": 4, "fibers_per_strand": 10}}"#;

/// What the seed's motion flags are called in its header.
pub const SEED_MOTION_LABEL: &str = "the embedded dance";

pub fn seed_style() -> Hairstyle {
    Hairstyle::from_json(SEED_HAIRSTYLE, "seed.json").expect("seed hairstyle")
}

/// What a run with the seed's hairstyle and the dance expects of a cache.
pub fn expected() -> Expected {
    static E: OnceLock<Expected> = OnceLock::new();
    E.get_or_init(|| Expected::new(&seed_style(), &Motion::default_dance(), SEED_MOTION_LABEL))
        .clone()
}

/// The engine configuration the seed is simulated with (and small renders of it use).
pub fn seed_config() -> EngineConfig {
    {
        let mut config = EngineConfig::sized(24, 24);
        config.simulation.settle_s = 0.5;
        config
    }
}

/// Writes a cache of `frames` frames of `style` on `motion` from `start_s` at 30 fps to
/// `path`, simulating as `wisp simulate` does.
pub fn simulate_to(
    path: &std::path::Path,
    style: Hairstyle,
    motion: Motion,
    label: &str,
    config: EngineConfig,
    frames: u32,
    start_s: f64,
) {
    let e = Expected::new(&style, &motion, label);
    let header = CacheHeader {
        frames,
        particles: e.particles,
        points_per_guide: e.points_per_guide,
        fps: 30.0,
        start_s,
        settle_s: config.simulation.settle_s,
        hairstyle_digest: e.hairstyle_digest,
        motion_digest: e.motion_digest,
        light_dir: config.scene.lights[0].travel().unwrap_or(glam::Vec3::NEG_Y),
        map_res: wisp::engine::map_geometry(&style, &config.hair_map).n,
        simulated: config.simulation.simulate,
        self_collision: config.simulation.self_collision,
        draw_solids: config.scene.draw_solids,
        hairstyle_name: style.name.clone(),
        motion_label: label.to_string(),
    };
    let mut w = CacheWriter::create(path, header.clone()).expect("create cache");
    let mut engine = Engine::new(style, motion, config);
    w.write_sim_state(0.0, &engine.simulation.state)
        .expect("settled");
    engine.run_up_to(start_s);
    for i in 0..frames {
        let t = header.frame_time_s(i);
        engine.advance(t);
        engine.build_map();
        w.write_sim_state(t, &engine.simulation.state)
            .expect("frame");
    }
    w.finish().expect("finish cache");
}

/// The bytes of the seed cache (made once per test binary).
pub fn seed() -> Vec<u8> {
    static SEED: OnceLock<Vec<u8>> = OnceLock::new();
    SEED.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("wisp-cache-seed-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("seed dir");
        let path = dir.join("seed.wcache");
        simulate_to(
            &path,
            seed_style(),
            Motion::default_dance(),
            SEED_MOTION_LABEL,
            seed_config(),
            SEED_FRAMES,
            0.0,
        );
        let bytes = std::fs::read(&path).expect("read seed");
        let _ = std::fs::remove_dir_all(&dir);
        bytes
    })
    .clone()
}

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

fn put(b: &mut [u8], at: usize, v: &[u8]) {
    if let Some(dst) = b.get_mut(at..at + v.len()) {
        dst.copy_from_slice(v);
    }
}

/// Header length and record length as the (possibly edited) header says, when they fit.
fn layout(b: &[u8]) -> Option<(usize, usize)> {
    let header = u32_at(b, offset::HEADER_BYTES)? as usize;
    let particles = u32_at(b, offset::PARTICLES)? as u64;
    let record = record_bytes(particles);
    if header < CHECKSUM_BYTES || header > b.len() || record > b.len() as u64 {
        return Some((header.min(b.len()), 0));
    }
    Some((header, record as usize))
}

/// Recomputes the header's checksum and that of every whole record, as the header lays them
/// out. Bytes that do not fit the layout are left alone.
pub fn reseal(b: &mut [u8]) {
    let Some((header, record)) = layout(b) else {
        return;
    };
    if header >= CHECKSUM_BYTES && header <= b.len() {
        let crc = crc32fast::hash(&b[..header - CHECKSUM_BYTES]);
        put(b, header - CHECKSUM_BYTES, &crc.to_le_bytes());
    }
    if record == 0 {
        return;
    }
    let mut k = 0u64;
    let mut at = header;
    while at + record <= b.len() {
        let mut h = crc32fast::Hasher::new();
        h.update(&k.to_le_bytes());
        h.update(&b[at..at + record - CHECKSUM_BYTES]);
        let crc = h.finalize();
        put(b, at + record - CHECKSUM_BYTES, &crc.to_le_bytes());
        at += record;
        k += 1;
    }
}

/// Byte offset of record `k` of the seed layout (0: the settled state, k: frame k − 1).
pub fn record_at(b: &[u8], k: usize) -> Option<(usize, usize)> {
    let (header, record) = layout(b)?;
    (record > 0).then_some((header + k * record, record))
}

/// One edit of a cache that a damaged or hostile file could carry, checksums resealed after
/// it; returns what was done.
pub fn mutate(rng: &mut Rng, b: &mut Vec<u8>) -> String {
    const WORDS: [u32; 12] = [
        0,
        1,
        2,
        3,
        255,
        257,
        65_535,
        100_000,
        100_001,
        u32::MAX,
        u32::MAX / 12,
        1 << 31,
    ];
    let records = (SEED_FRAMES + 1) as usize;
    let what = match rng.below(9) {
        0 => {
            let (name, at) = *rng.pick(&[
                ("version", offset::VERSION),
                ("header bytes", offset::HEADER_BYTES),
                ("frames", offset::FRAMES),
                ("particles", offset::PARTICLES),
                ("particles per guide", offset::POINTS_PER_GUIDE),
                ("map resolution", offset::MAP_RES),
            ]);
            let w = *rng.pick(&WORDS);
            put(b, at, &w.to_le_bytes());
            format!("header {name} = {w}")
        }
        1 => {
            let (name, at, wide) = *rng.pick(&[
                ("fps", offset::FPS, false),
                ("start", offset::START_S, true),
                ("settle", offset::SETTLE_S, true),
                ("light x", offset::LIGHT_DIR, false),
                ("light y", offset::LIGHT_DIR + 4, false),
            ]);
            let v = *rng.pick(&FLOATS);
            if wide {
                put(b, at, &(v as f64).to_le_bytes());
            } else {
                put(b, at, &v.to_le_bytes());
            }
            format!("header {name} = {v}")
        }
        2 => {
            let at = *rng.pick(&[
                offset::FLAGS,
                offset::NAME_LEN,
                offset::LABEL_LEN,
                offset::RESERVED,
            ]);
            let v = rng.below(256) as u8;
            put(b, at, &[v]);
            format!("header byte {at} = {v}")
        }
        3 => {
            let at = offset::HAIRSTYLE_DIGEST + rng.below(64);
            if let Some(x) = b.get_mut(at) {
                *x ^= 1 << rng.below(8);
            }
            format!("digest bit flip at {at}")
        }
        4 | 5 => {
            let k = rng.below(records);
            let Some((at, len)) = record_at(b, k) else {
                return "nothing (no records)".into();
            };
            let coords = (len - TIME_BYTES - CHECKSUM_BYTES) / 4;
            let c = rng.below(coords.max(1));
            let p = at + TIME_BYTES + 4 * c;
            if rng.chance(0.5) {
                let v = *rng.pick(&FLOATS);
                put(b, p, &v.to_le_bytes());
                format!("record {k} coordinate {c} = {v}")
            } else {
                // A nudge of a millimetre: a state the format cannot tell from a real one.
                let old = b
                    .get(p..p + 4)
                    .map_or(0.0, |s| f32::from_le_bytes(s.try_into().unwrap()));
                put(b, p, &(old + 1e-3).to_le_bytes());
                format!("record {k} coordinate {c} nudged by 1 mm")
            }
        }
        6 => {
            let k = rng.below(records);
            let Some((at, _)) = record_at(b, k) else {
                return "nothing (no records)".into();
            };
            let v = *rng.pick(&[f64::NAN, 1e300, -1.0, 0.0, 1.0 / 30.0, 1e-300]);
            put(b, at, &v.to_le_bytes());
            format!("record {k} time = {v}")
        }
        7 => {
            let (from, to) = (rng.below(records), rng.below(records));
            let (Some((a, len)), Some((t, _))) = (record_at(b, from), record_at(b, to)) else {
                return "nothing (no records)".into();
            };
            if a + len <= b.len() && t + len <= b.len() {
                let copy = b[a..a + len].to_vec();
                b[t..t + len].copy_from_slice(&copy);
            }
            format!("record {from} copied onto record {to}")
        }
        _ => {
            let (header, record) = layout(b).unwrap_or((FIXED_HEADER_BYTES, 0));
            if rng.chance(0.5) {
                let keep = header + record * rng.below(records);
                b.truncate(keep.min(b.len()));
                format!("truncated to {keep} bytes (a record boundary)")
            } else {
                let extra = vec![0u8; record.max(1) * (1 + rng.below(2))];
                b.extend_from_slice(&extra);
                format!("{} bytes appended", extra.len())
            }
        }
    };
    reseal(b);
    format!("{what}, checksums resealed")
}

/// The layout's byte sizes, for tests that edit the seed by hand.
pub const POSITION: usize = POSITION_BYTES;
pub const TIME: usize = TIME_BYTES;
pub const CHECKSUM: usize = CHECKSUM_BYTES;
