//! Simulation caches (issue 10), library level: frames rendered from a cache are the bytes a
//! single run renders (with a warm-up before the first frame, self-collision on, and other
//! thread counts), and a damaged, hostile or foreign cache is refused naming the file and
//! what is wrong, before anything is allocated from its counts. Through the binary, with
//! shards and the local runner: `tests/cli/deploy.rs`; generated hostile caches:
//! `tests/lib/hostile_loaders.rs`.

use crate::bounded::run_bounded;
use crate::support::hostile::cache::{
    CHECKSUM, POSITION, SEED_FRAMES, SEED_MOTION_LABEL, TIME, expected, record_at, reseal, seed,
    seed_config, seed_style, simulate_to,
};
use crate::support::scratch_dir;
use std::path::Path;
use std::time::Duration;
use wisp::cache::format::offset;
use wisp::cache::{CacheError, CacheReader, Expected};
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
}

/// A frame as bits: colour, coverage and depth of every pixel, then the sRGB bytes a PNG gets.
fn frame_bits(engine: &Engine) -> Vec<u32> {
    let fb = engine.framebuffer();
    let mut bits: Vec<u32> = fb
        .color
        .iter()
        .flat_map(|c| c.to_array().map(f32::to_bits))
        .collect();
    bits.extend(fb.coverage.iter().map(|v| v.to_bits()));
    bits.extend(fb.depth.iter().map(|v| v.to_bits()));
    bits.extend(fb.to_srgb8().into_iter().map(u32::from));
    bits
}

fn small_config() -> EngineConfig {
    {
        let mut config = EngineConfig::sized(48, 48);
        config.simulation.settle_s = 0.5;
        config
    }
}

/// The core promise. A single run (2 threads, `render_config`) renders 4 frames from 1.0 s of
/// the dance; a cache of the run is simulated with 1 thread and `simulate_config`, and
/// rendered with 2 threads and `render_config`. Every frame must be the same bits: colour,
/// coverage, depth and the 8-bit sRGB written to PNG.
fn check_cached_frames_match_a_single_run(
    simulate_config: EngineConfig,
    render_config: EngineConfig,
    name: &str,
) {
    let dir = scratch_dir(name);
    let path = dir.join("run.wcache");
    let (frames, start_s, fps) = (4u32, 1.0, 30.0f32);
    let single: Vec<Vec<u32>> = pool(2).install(|| {
        let mut e = Engine::new(
            Hairstyle::default_smooth(),
            Motion::default_dance(),
            render_config.clone(),
        );
        e.run_up_to(start_s);
        (0..frames)
            .map(|i| {
                e.frame(start_s + i as f64 / fps as f64);
                frame_bits(&e)
            })
            .collect()
    });
    pool(1).install(|| {
        simulate_to(
            &path,
            Hairstyle::default_smooth(),
            Motion::default_dance(),
            "the dance",
            simulate_config,
            frames,
            start_s,
        )
    });
    let cached: Vec<Vec<u32>> = pool(2).install(|| {
        let motion = Motion::default_dance();
        let e = Expected::new(&Hairstyle::default_smooth(), &motion, "the dance");
        let mut reader = CacheReader::open(&path, &e).expect("open");
        assert_eq!(reader.header().frames, frames);
        let settled = reader.read_settled(&motion).expect("settled").to_vec();
        let mut engine =
            Engine::from_settled(Hairstyle::default_smooth(), motion, render_config, &settled);
        (0..frames)
            .map(|i| {
                let t = reader.header().frame_time_s(i);
                let p = reader.read_frame(i, engine.motion()).expect("frame");
                engine.set_guide_state(t, p);
                engine.render();
                frame_bits(&engine)
            })
            .collect()
    });
    for (i, (a, b)) in single.iter().zip(&cached).enumerate() {
        let differ = a.iter().zip(b).filter(|(x, y)| x != y).count();
        assert_eq!(differ, 0, "{name}: frame {i}: {differ} values differ");
    }
    // The frames are not all alike (the hair moves), so the comparison means something.
    assert_ne!(single[0], single[3]);
}

#[test]
fn frames_from_a_cache_are_the_bytes_of_a_single_run() {
    check_cached_frames_match_a_single_run(small_config(), small_config(), "cache-identity");
}

/// The motion does not depend on the light or the map (self-collision reads the simulator's
/// own density grid): a cache simulated in the default light, rendered in another light at
/// another map resolution, is the bytes of a single run in that light.
#[test]
fn a_cache_relit_is_the_bytes_of_a_single_run_in_the_new_light() {
    let mut relit = small_config();
    relit.scene.lights = vec![
        wisp::light::Light::directional(glam::Vec3::new(1.0, -0.5, -0.3), glam::Vec3::splat(6.0))
            .unwrap(),
    ];
    relit.hair_map.map_res = Some(48);
    check_cached_frames_match_a_single_run(small_config(), relit, "cache-relit");
}

/// The cache stores what a frame needs and no more: 8 B of time, 12 B per guide particle and
/// a 4 B checksum per frame (77.2 KB a frame for the smooth preset's 6,432 particles).
#[test]
fn a_record_is_the_time_the_positions_and_a_checksum() {
    let e = Expected::new(
        &Hairstyle::default_smooth(),
        &Motion::default_dance(),
        "dance",
    );
    // 134 wisps × 3 guides × (15 links + 1).
    assert_eq!(e.particles, 6_432);
    assert_eq!(
        wisp::cache::format::record_bytes(e.particles as u64),
        (TIME + CHECKSUM + POSITION * 6_432) as u64
    );
    let bytes = seed();
    let h = wisp::cache::CacheHeader::decode(&bytes, "seed").expect("seed header");
    assert_eq!(h.file_bytes(), bytes.len() as u64);
    assert_eq!(h.particles, 48);
    assert_eq!(h.frames, SEED_FRAMES);
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> std::path::PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).expect("write case");
    p
}

/// Opens `bytes` as a cache and reads every record; the error's message.
fn error_of(bytes: &[u8]) -> String {
    static CASE: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = CASE.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("wisp-cache-case-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = write(&dir, "case.wcache", bytes);
    let msg = read_all(&p, &expected()).expect_err("accepted").to_string();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        msg.contains("case.wcache"),
        "the message names no file: {msg}"
    );
    msg
}

fn read_all(path: &Path, e: &Expected) -> Result<(), CacheError> {
    let motion = Motion::default_dance();
    let mut r = CacheReader::open(path, e)?;
    r.read_settled(&motion)?;
    for i in 0..r.header().frames {
        r.read_frame(i, &motion)?;
    }
    Ok(())
}

fn edited(edit: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
    let mut b = seed();
    edit(&mut b);
    b
}

#[test]
fn the_seed_cache_reads_back() {
    let dir = scratch_dir("cache-seed");
    let p = write(&dir, "seed.wcache", &seed());
    read_all(&p, &expected()).expect("the seed is a valid cache");
}

#[test]
fn a_truncated_cache_is_refused_before_reading_a_record() {
    let b = seed();
    let msg = error_of(&b[..b.len() - 1]);
    assert!(msg.contains("truncated: the file has"), "{msg}");
    let msg = error_of(&b[..100]);
    assert!(msg.contains("shorter than a cache header"), "{msg}");
    let msg = error_of(&[]);
    assert!(msg.contains("not a wisp simulation cache"), "{msg}");
    let mut longer = b.clone();
    longer.push(0);
    assert!(error_of(&longer).contains("too long"));
}

#[test]
fn another_version_is_refused_with_what_to_do() {
    let b = edited(|b| {
        b[offset::VERSION..offset::VERSION + 4].copy_from_slice(&2u32.to_le_bytes());
        reseal(b);
    });
    let msg = error_of(&b);
    assert!(
        msg.contains("version is 2; this wisp reads version 1 (simulate again"),
        "{msg}"
    );
}

#[test]
fn a_flipped_byte_fails_the_header_or_record_checksum() {
    let b = edited(|b| b[offset::START_S] ^= 0x10);
    assert!(error_of(&b).contains("header checksum"));
    let (at, len) = record_at(&seed(), 2).unwrap();
    let b = edited(|b| b[at + len / 2] ^= 0x01);
    let msg = error_of(&b);
    assert!(msg.contains("frame 1: checksum"), "{msg}");
    assert!(msg.contains("the file is damaged"), "{msg}");
}

#[test]
fn records_copied_to_another_place_fail_their_checksum() {
    let (a, len) = record_at(&seed(), 1).unwrap();
    let (b_at, _) = record_at(&seed(), 2).unwrap();
    let b = edited(|b| {
        let copy = b[a..a + len].to_vec();
        b[b_at..b_at + len].copy_from_slice(&copy);
    });
    assert!(error_of(&b).contains("frame 1: checksum"));
}

/// Counts far beyond the file are refused from the file's size, before the reader allocates
/// a record: the whole open stays under 1 MB of heap (the claimed record is 925 MB).
#[test]
fn huge_counts_are_refused_against_the_file_size_before_allocating() {
    let b = edited(|b| {
        let big = 3 * 100_000 * 257u32; // the most particles any hairstyle can have
        b[offset::PARTICLES..offset::PARTICLES + 4].copy_from_slice(&big.to_le_bytes());
        b[offset::POINTS_PER_GUIDE..offset::POINTS_PER_GUIDE + 4]
            .copy_from_slice(&257u32.to_le_bytes());
        b[offset::FRAMES..offset::FRAMES + 4].copy_from_slice(&100_000u32.to_le_bytes());
        reseal(b);
    });
    let report = run_bounded(move || error_of(&b), Duration::from_secs(30)).expect("no panic");
    assert!(
        report.value.contains("truncated: the file has"),
        "{}",
        report.value
    );
    assert!(report.value.contains("100000 frames of 77100000 particles"));
    assert!(report.peak_bytes < 1 << 20, "peak {} B", report.peak_bytes);
    // Counts beyond any hairstyle are refused by rule.
    let b = edited(|b| {
        b[offset::FRAMES..offset::FRAMES + 4].copy_from_slice(&u32::MAX.to_le_bytes());
        reseal(b);
    });
    assert!(error_of(&b).contains("frames is 4294967295, outside 1..=100000"));
}

#[test]
fn nan_and_far_away_states_are_refused_naming_frame_and_particle() {
    let (at, _) = record_at(&seed(), 3).unwrap();
    let coord = at + TIME + POSITION * 17 + 4;
    let b = edited(|b| {
        b[coord..coord + 4].copy_from_slice(&f32::NAN.to_le_bytes());
        reseal(b);
    });
    let msg = error_of(&b);
    assert!(
        msg.contains("frame 2: particle 17 is at [") && msg.contains("NaN"),
        "{msg}"
    );
    assert!(msg.contains("not a finite position"), "{msg}");
    let b = edited(|b| {
        b[coord..coord + 4].copy_from_slice(&1e30f32.to_le_bytes());
        reseal(b);
    });
    let msg = error_of(&b);
    assert!(msg.contains("frame 2: particle 17 is"), "{msg}");
    assert!(msg.contains("farther than hair can reach"), "{msg}");
    // The settled state is checked as the frames are.
    let (at0, _) = record_at(&seed(), 0).unwrap();
    let b = edited(|b| {
        b[at0 + TIME..at0 + TIME + 4].copy_from_slice(&f32::INFINITY.to_le_bytes());
        reseal(b);
    });
    assert!(error_of(&b).contains("the settled state: particle 0"));
}

#[test]
fn a_record_with_another_time_is_refused() {
    let (at, _) = record_at(&seed(), 2).unwrap();
    let b = edited(|b| {
        b[at..at + 8].copy_from_slice(&5.0f64.to_le_bytes());
        reseal(b);
    });
    let msg = error_of(&b);
    assert!(msg.contains("frame 1: its time is 5 s"), "{msg}");
}

#[test]
fn header_fields_out_of_range_are_refused_naming_the_field() {
    let cases: [(usize, Vec<u8>, &str); 6] = [
        (offset::FPS, f32::NAN.to_le_bytes().to_vec(), "fps is NaN"),
        (
            offset::START_S,
            (-1.0f64).to_le_bytes().to_vec(),
            "start time is -1 s",
        ),
        (
            offset::LIGHT_DIR,
            2.0f32.to_le_bytes().to_vec(),
            "not a unit vector",
        ),
        (
            offset::MAP_RES,
            2u32.to_le_bytes().to_vec(),
            "map resolution is 2",
        ),
        (
            offset::POINTS_PER_GUIDE,
            5u32.to_le_bytes().to_vec(),
            "whole number of guides",
        ),
        (offset::FLAGS, vec![0x80], "unknown bits"),
    ];
    for (at, value, needle) in cases {
        let b = edited(|b| {
            b[at..at + value.len()].copy_from_slice(&value);
            reseal(b);
        });
        let msg = error_of(&b);
        assert!(msg.contains(needle), "{needle}: {msg}");
    }
}

#[test]
fn a_cache_for_another_hairstyle_or_motion_is_refused_saying_which() {
    let dir = scratch_dir("cache-mismatch");
    let p = write(&dir, "run.wcache", &seed());
    let curly = Expected::new(
        &Hairstyle::default_curly(),
        &Motion::default_dance(),
        "dance",
    );
    let msg = read_all(&p, &curly).unwrap_err().to_string();
    assert!(
        msg.contains("was simulated for hairstyle \"min\"")
            && msg.contains("not for this hairstyle \"curly\""),
        "{msg}"
    );
    let still = Expected::new(
        &seed_style(),
        &Motion::still(glam::Affine3A::IDENTITY),
        "--still",
    );
    let msg = read_all(&p, &still).unwrap_err().to_string();
    assert!(
        msg.contains(&format!("was simulated with motion {SEED_MOTION_LABEL}"))
            && msg.contains("--still"),
        "{msg}"
    );
    // The same hairstyle with one dynamics value changed is another hairstyle.
    let mut stiffer = seed_style();
    stiffer.dynamics.bending_stiffness += 0.1;
    let e = Expected::new(&stiffer, &Motion::default_dance(), SEED_MOTION_LABEL);
    assert!(matches!(read_all(&p, &e), Err(CacheError::Mismatch { .. })));
}

#[test]
fn directories_devices_and_missing_files_are_refused_without_reading() {
    let dir = scratch_dir("cache-special");
    let msg = read_all(&dir, &expected()).unwrap_err().to_string();
    assert!(msg.contains("a directory"), "{msg}");
    let msg = read_all(Path::new("/dev/zero"), &expected())
        .unwrap_err()
        .to_string();
    assert!(msg.contains("character device"), "{msg}");
    let msg = read_all(&dir.join("missing.wcache"), &expected())
        .unwrap_err()
        .to_string();
    assert!(msg.contains("missing.wcache: cannot read"), "{msg}");
}

#[test]
fn writing_refuses_a_directory_or_a_device_and_leaves_no_cache_when_incomplete() {
    let dir = scratch_dir("cache-write");
    let h = wisp::cache::CacheHeader::decode(&seed(), "seed").unwrap();
    let e = wisp::cache::CacheWriter::create(&dir, h.clone())
        .err()
        .unwrap();
    assert!(e.to_string().contains("is a directory"), "{e}");
    let e = wisp::cache::CacheWriter::create(Path::new("/dev/null"), h.clone())
        .err()
        .unwrap();
    assert!(e.to_string().contains("not a regular file"), "{e}");
    let e = wisp::cache::CacheWriter::create(&dir.join("no/such/dir.wcache"), h.clone())
        .err()
        .unwrap();
    assert!(e.to_string().contains("folder does not exist"), "{e}");
    // Two of the four records, then finish: refused, and only the temporary file exists.
    let p = dir.join("part.wcache");
    let mut w = wisp::cache::CacheWriter::create(&p, h).unwrap();
    let pts = vec![glam::Vec3::ZERO; 48];
    w.write_positions(0.0, &pts).unwrap();
    w.write_positions(0.0, &pts).unwrap();
    let e = w.finish().unwrap_err();
    assert!(e.to_string().contains("2 of 4 records written"), "{e}");
    assert!(!p.exists());
    assert!(dir.join("part.wcache.tmp").exists());
}

/// An accepted cache with a hand-made but plausible state still renders finite pixels (the
/// reader cannot tell a nudged position from a simulated one; the renderer must cope).
#[test]
fn a_nudged_state_renders_finite_pixels() {
    let (at, _) = record_at(&seed(), 1).unwrap();
    let b = edited(|b| {
        for k in 0..48 {
            let c = at + TIME + POSITION * k;
            let v = f32::from_le_bytes(b[c..c + 4].try_into().unwrap()) + 0.01;
            b[c..c + 4].copy_from_slice(&v.to_le_bytes());
        }
        reseal(b);
    });
    let dir = scratch_dir("cache-nudged");
    let p = write(&dir, "n.wcache", &b);
    let motion = Motion::default_dance();
    let mut r = CacheReader::open(&p, &expected()).expect("accepted");
    let settled = r.read_settled(&motion).unwrap().to_vec();
    let mut engine = Engine::from_settled(seed_style(), motion, seed_config(), &settled);
    let t = r.header().frame_time_s(0);
    let pts = r.read_frame(0, engine.motion()).unwrap().to_vec();
    engine.set_guide_state(t, &pts);
    let fb = engine.render();
    assert!(fb.color.iter().all(|c| c.is_finite()));
}
