//! Groom import: the TressFX and cyHair readers on files built here (valid, truncated at every
//! byte, huge counts, NaN, zero-length strands), clustering, the rest pose against the file,
//! the shared ponytail, rendering and thread-count independence.

use glam::{Affine3A, Vec3};
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::process::Command;
use wisp::engine::{Engine, EngineConfig};
use wisp::groom::cluster::{Feature, MIN_WISP_STRANDS, cluster};
use wisp::groom::{Groom, GroomError, GroomOptions, build_groom, load_groom};
use wisp::hairstyle::Hairstyle;
use wisp::input::cyhair::{self, HEADER_BYTES};
use wisp::input::strand_file::parse_strand_file;
use wisp::input::strands::{StrandFile, StrandFileError};
use wisp::input::tfx::{self, encode_tfx3, encode_tfx4};
use wisp::interp::{StrandGeometry, interpolate};
use wisp::motion::Motion;

/// Radius of the test grooms' head sphere and of their strands' arcs, centimetres.
const HEAD_CM: f32 = 9.0;
const ARC_RADIUS_CM: f32 = 10.0;
/// Strand length and vertices of the test grooms.
const STRAND_CM: f32 = 30.0;
const VERTICES: usize = 16;

/// A groom in centimetres: `count` strands rooted on the upper cap of a sphere of radius
/// `HEAD_CM` (Fibonacci lattice), each a circular arc of radius `ARC_RADIUS_CM` and length
/// `STRAND_CM` leaving along the scalp normal and bending down and back. Sampled at `VERTICES`
/// evenly spaced vertices (exactly on the arc).
fn arcs(count: usize) -> Vec<Vec<Vec3>> {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    (0..count)
        .map(|i| {
            let y = 1.0 - 0.9 * (i as f32 + 0.5) / count as f32;
            let r = (1.0 - y * y).sqrt();
            let a = golden * i as f32;
            let n = Vec3::new(r * a.sin(), y, r * a.cos());
            let root = n * HEAD_CM;
            // The arc turns in the plane of the normal and "down and back".
            let down = (Vec3::new(0.0, -1.0, -0.3) - n * n.dot(Vec3::new(0.0, -1.0, -0.3)))
                .normalize_or(Vec3::X);
            let centre = root + down * ARC_RADIUS_CM;
            (0..VERTICES)
                .map(|k| {
                    let phi = STRAND_CM / ARC_RADIUS_CM * k as f32 / (VERTICES - 1) as f32;
                    centre - down * ARC_RADIUS_CM * phi.cos() + n * ARC_RADIUS_CM * phi.sin()
                })
                .collect()
        })
        .collect()
}

/// cyHair bytes with every optional array (segments, points, thickness, transparency, colours).
fn encode_cyhair(strands: &[Vec<Vec3>]) -> Vec<u8> {
    let pts: usize = strands.iter().map(Vec::len).sum();
    let mut b = Vec::new();
    b.extend_from_slice(b"HAIR");
    for v in [strands.len() as u32, pts as u32, 1 | 2 | 4 | 8 | 16, 0] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    for v in [0.01f32, 0.0, 1.0, 1.0, 1.0] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    b.resize(HEADER_BYTES, 0);
    for s in strands {
        b.extend_from_slice(&((s.len() - 1) as u16).to_le_bytes());
    }
    for p in strands.iter().flatten() {
        for v in p.to_array() {
            b.extend_from_slice(&v.to_le_bytes());
        }
    }
    for k in 0..pts {
        b.extend_from_slice(&(0.005 + k as f32 * 1e-6).to_le_bytes());
    }
    for _ in 0..pts {
        b.extend_from_slice(&0.25f32.to_le_bytes());
    }
    for _ in 0..pts {
        for v in [0.3f32, 0.2, 0.1] {
            b.extend_from_slice(&v.to_le_bytes());
        }
    }
    b
}

fn malformed(r: Result<StrandFile, StrandFileError>) -> (u64, String) {
    match r {
        Err(StrandFileError::Malformed { file, offset, rule }) => {
            assert!(!file.is_empty());
            (offset, rule)
        }
        other => panic!("expected a malformed-file error, got {other:?}"),
    }
}

fn flat(strands: &[Vec<Vec3>]) -> Vec<Vec3> {
    strands.iter().flatten().copied().collect()
}

#[test]
fn each_reader_reads_what_was_written() {
    let strands = arcs(5);
    for (name, bytes) in [
        ("a.tfx", encode_tfx3(&strands)),
        ("b.tfx", encode_tfx4(&strands)),
        ("c.hair", encode_cyhair(&strands)),
    ] {
        let f = parse_strand_file(&bytes, name).unwrap();
        assert_eq!(f.points, flat(&strands), "{name}");
        assert_eq!(f.strand_points, vec![VERTICES as u32; 5], "{name}");
    }
    let c = parse_strand_file(&encode_cyhair(&strands), "c.hair").unwrap();
    assert_eq!(c.thickness.as_ref().unwrap()[3], 0.005 + 3.0 * 1e-6);
    assert_eq!(c.colors.as_ref().unwrap()[7], Vec3::new(0.3, 0.2, 0.1));
    // Without a segments array every strand has d_segments + 1 points.
    let mut b = encode_cyhair(&strands);
    b[12..16].copy_from_slice(&2u32.to_le_bytes()); // points only
    b[16..20].copy_from_slice(&((VERTICES - 1) as u32).to_le_bytes());
    b.drain(HEADER_BYTES..HEADER_BYTES + 2 * 5);
    let f = parse_strand_file(&b, "d.hair").unwrap();
    assert_eq!(f.points, flat(&strands));
    assert_eq!(f.thickness.unwrap(), vec![0.01; 5 * VERTICES]);
}

#[test]
fn every_truncation_is_a_typed_error_at_or_before_the_cut() {
    let strands = arcs(2);
    for (name, bytes) in [
        ("a.tfx", encode_tfx3(&strands)),
        ("b.tfx", encode_tfx4(&strands)),
        ("c.hair", encode_cyhair(&strands)),
    ] {
        // Every cut inside the header and every cut of the data.
        for cut in 0..bytes.len() {
            let (offset, rule) = malformed(parse_strand_file(&bytes[..cut], name));
            assert!(
                offset <= cut as u64,
                "{name} cut at {cut}: offset {offset} past the end ({rule})"
            );
            assert!(!rule.is_empty());
        }
        assert!(parse_strand_file(&bytes, name).is_ok());
    }
}

#[test]
fn huge_declared_counts_are_refused_before_allocating() {
    let strands = arcs(2);
    // TressFX: 4 billion strands of 4096 vertices would be 200 TB of positions.
    for (name, mut bytes) in [
        ("a.tfx", encode_tfx3(&strands)),
        ("b.tfx", encode_tfx4(&strands)),
    ] {
        bytes[4..8].copy_from_slice(&u32::MAX.to_le_bytes());
        let (offset, rule) = malformed(parse_strand_file(&bytes, name));
        assert_eq!(offset, 4, "{rule}");
        assert!(rule.contains("over the limit of 2000000 strands"), "{rule}");
        // At the strand cap (2,000,000) of 4,096 vertices: 98 GB of positions.
        bytes[4..8].copy_from_slice(&2_000_000u32.to_le_bytes());
        bytes[8..12].copy_from_slice(&tfx::MAX_VERTICES_PER_STRAND.to_le_bytes());
        let (offset, rule) = malformed(parse_strand_file(&bytes, name));
        assert!(rule.contains("vertex positions"), "{rule}");
        assert!(offset > 0, "{rule}");
        bytes[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
        let (offset, rule) = malformed(parse_strand_file(&bytes, name));
        assert_eq!(offset, 8, "{rule}");
    }
    // cyHair: the most points allowed, and more.
    let mut bytes = encode_cyhair(&strands);
    bytes[4..8].copy_from_slice(&u32::MAX.to_le_bytes());
    let (offset, rule) = malformed(parse_strand_file(&bytes, "c.hair"));
    assert_eq!(offset, 4, "{rule}");
    assert!(rule.contains("over the limit of 2000000 strands"), "{rule}");
    bytes[4..8].copy_from_slice(&2_000_000u32.to_le_bytes());
    bytes[8..12].copy_from_slice(&cyhair::MAX_POINTS.to_le_bytes());
    let (_, rule) = malformed(parse_strand_file(&bytes, "c.hair"));
    assert!(rule.contains("header announces"), "{rule}");
    bytes[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
    let (offset, rule) = malformed(parse_strand_file(&bytes, "c.hair"));
    assert_eq!(offset, 8, "{rule}");
    // Segments that do not add up to the point count.
    let mut bytes = encode_cyhair(&strands);
    bytes[HEADER_BYTES..HEADER_BYTES + 2].copy_from_slice(&40u16.to_le_bytes());
    let (offset, rule) = malformed(parse_strand_file(&bytes, "c.hair"));
    assert_eq!(offset, HEADER_BYTES as u64);
    assert!(rule.contains("add up to"), "{rule}");
    // A vertex offset far past the end.
    let mut bytes = encode_tfx3(&strands);
    bytes[144..148].copy_from_slice(&u32::MAX.to_le_bytes());
    let (_, rule) = malformed(parse_strand_file(&bytes, "a.tfx"));
    assert!(rule.contains("need more than"), "{rule}");
}

#[test]
fn a_nan_position_is_named_by_its_byte_offset() {
    let mut strands = arcs(3);
    strands[1][2].y = f32::NAN;
    let at = |header: usize, stride: usize| (header + (VERTICES + 2) * stride) as u64;
    for (name, bytes, expect) in [
        ("a.tfx", encode_tfx3(&strands), at(tfx::HEADER_3_BYTES, 12)),
        ("b.tfx", encode_tfx4(&strands), at(tfx::HEADER_4_BYTES, 16)),
        (
            "c.hair",
            encode_cyhair(&strands),
            at(HEADER_BYTES + 2 * 3, 12),
        ),
    ] {
        let (offset, rule) = malformed(parse_strand_file(&bytes, name));
        assert_eq!(offset, expect, "{name}: {rule}");
        assert!(rule.contains("not finite"), "{rule}");
    }
}

#[test]
fn zero_length_strands_are_read_then_dropped_and_counted() {
    let mut strands = arcs(40);
    strands[3] = vec![strands[3][0]; VERTICES];
    let tfx = parse_strand_file(&encode_tfx3(&strands), "a.tfx").unwrap();
    assert_eq!(tfx.strand_count(), 40);
    // cyHair also allows a strand of 0 segments (a single point).
    let mut short = arcs(40);
    short[7] = vec![short[7][0]];
    let hair = parse_strand_file(&encode_cyhair(&short), "b.hair").unwrap();
    assert_eq!(hair.strand_points[7], 1);
    let base = Hairstyle::default_smooth();
    for f in [tfx, hair] {
        let g = build_groom(&[("x".into(), f)], &base, &GroomOptions::default()).unwrap();
        assert_eq!(g.report.strands_dropped, 1);
        // 39 file strands; a sparse groom's interpolated strands follow them (densify.rs).
        assert_eq!(g.layout.count() - g.report.strands_added, 39);
    }
    // Nothing but zero-length strands: a clear error, not an empty groom.
    let dead = vec![vec![Vec3::ONE; 4]; 5];
    let f = parse_strand_file(&encode_tfx3(&dead), "dead.tfx").unwrap();
    let e = build_groom(&[("dead.tfx".into(), f)], &base, &GroomOptions::default()).unwrap_err();
    assert!(
        e.to_string().contains("dead.tfx") && e.to_string().contains("0 strands"),
        "{e}"
    );
}

#[test]
fn roots_far_from_any_head_surface_are_refused_with_the_worst_strand() {
    // Roots spread through a cube (a cloud, not a scalp): no scale and offset lays them on
    // the head.
    let mut s = 1u64;
    let mut rnd = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 40) as f32 / (1u64 << 24) as f32 - 0.5
    };
    let strands: Vec<Vec<Vec3>> = (0..200)
        .map(|_| {
            let root = Vec3::new(rnd(), rnd(), rnd()) * 40.0;
            (0..4).map(|k| root - Vec3::Y * k as f32).collect()
        })
        .collect();
    let f = parse_strand_file(&encode_tfx3(&strands), "cloud.tfx").unwrap();
    let e = build_groom(
        &[("cloud.tfx".into(), f)],
        &Hairstyle::default_smooth(),
        &GroomOptions::default(),
    )
    .unwrap_err();
    assert!(matches!(e, GroomError::RootsOffHead { .. }), "{e}");
    let m = e.to_string();
    assert!(m.contains("cloud.tfx") && m.contains("strand "), "{m}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn clustering_keeps_every_strand_in_a_wisp_of_at_least_three(
        seeds in proptest::collection::vec((-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0), 3..300),
        k in 1usize..120,
    ) {
        let features: Vec<Feature> = seeds
            .iter()
            .map(|&(a, b, c, d)| [a, b * 0.1, c, d, d * a, 0.0, b, c, a * 0.5])
            .collect();
        let wisp = cluster(&features, k);
        prop_assert_eq!(wisp.len(), features.len());
        let wisps = *wisp.iter().max().unwrap() as usize + 1;
        prop_assert!(wisps <= k.max(1));
        let mut size = vec![0usize; wisps];
        for w in &wisp {
            size[*w as usize] += 1;
        }
        // Numbered without gaps, every wisp big enough for its 3 guides.
        prop_assert!(size.iter().all(|s| *s >= MIN_WISP_STRANDS), "{:?}", size);
    }
}

/// The rest pose of `g` (interpolated from its rest guides with the offsets), per strand.
fn rest_pose(g: &Groom) -> StrandGeometry {
    let mut geo = StrandGeometry::default();
    interpolate(
        &g.guides,
        &g.layout,
        &g.style.curl,
        &g.guides.rest,
        &mut geo,
    );
    geo
}

fn point_to_polyline(p: Vec3, line: &[Vec3]) -> f32 {
    line.windows(2)
        .map(|w| {
            let e = w[1] - w[0];
            let t = ((p - w[0]).dot(e) / e.length_squared()).clamp(0.0, 1.0);
            (p - w[0] - t * e).length()
        })
        .fold(f32::INFINITY, f32::min)
}

#[test]
fn the_rest_pose_reproduces_the_file_within_the_resampling_bound() {
    let strands = arcs(600);
    let f = parse_strand_file(&encode_tfx3(&strands), "arcs.tfx").unwrap();
    let g = build_groom(
        &[("arcs.tfx".into(), f)],
        &Hairstyle::default_smooth(),
        &GroomOptions::default(),
    )
    .unwrap();
    // 600 strands are sparse (smooth renders 3,350): every file strand is a render strand,
    // the first 600, and strands interpolated among them follow, in wisps of about 3.
    let added = g.report.strands_added;
    assert_eq!(
        g.layout.count() - added,
        600,
        "every strand is a render strand"
    );
    assert!(added > 0 && g.report.wisps <= 600 / 3, "{:?}", g.report);
    let place = g.report.placement.unwrap();
    // Bound: the rest points lie on the file's polyline (offsets restore the arc-length
    // resampling to rounding), so what remains is how far a file vertex is from the chords
    // between rest points. Both are inscribed in the same arc, so that is at most the sagitta
    // of the rest chords, h²/(8R) with h the rest spacing along the arc and R its radius
    // (metres after the fit's scale), plus float rounding at head scale (1 µm).
    let scale_m = place.scale;
    let n = g.layout.points_per_strand;
    let h = STRAND_CM / (n - 1) as f32 * scale_m;
    let bound_m = h * h / (8.0 * ARC_RADIUS_CM * scale_m) + 1e-6;
    let geo = rest_pose(&g);
    let mut worst = 0.0f32;
    for (s, file) in strands.iter().enumerate() {
        let file: Vec<Vec3> = file.iter().map(|p| place.apply(*p)).collect();
        let rest = &geo.positions[s * n..(s + 1) * n];
        for p in rest {
            worst = worst.max(point_to_polyline(*p, &file));
        }
        for p in &file {
            worst = worst.max(point_to_polyline(*p, rest));
        }
    }
    assert!(worst <= bound_m, "worst {worst} m, bound {bound_m} m");
    // The report measures the same thing.
    assert!((g.report.rest_distance_max_m - worst).abs() < 1e-6);
    assert!(g.report.rest_distance_mean_m <= g.report.rest_distance_max_m);
    // The fit lays the roots on the head: they were on a sphere, the head is an ellipsoid
    // (semi-axes 76-98 mm), so within the difference of the shapes.
    assert!(g.report.root_distance_max_m < 0.02, "{:?}", g.report);
}

#[test]
fn a_4x_tfx_and_a_cyhair_file_give_the_same_groom_as_3x() {
    let strands = arcs(90);
    let base = Hairstyle::default_smooth();
    let build = |name: &str, bytes: Vec<u8>| {
        let f = parse_strand_file(&bytes, name).unwrap();
        build_groom(&[(name.into(), f)], &base, &GroomOptions::default()).unwrap()
    };
    let a = build("a.tfx", encode_tfx3(&strands));
    let b = build("a.tfx", encode_tfx4(&strands));
    let c = build("a.hair", encode_cyhair(&strands));
    for other in [&b, &c] {
        assert_eq!(a.guides.rest, other.guides.rest);
        assert_eq!(a.layout.rest_offset, other.layout.rest_offset);
    }
}

fn ponytail_dir() -> Option<PathBuf> {
    let d = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/hair/tressfx-ponytail");
    d.join("tail.tfx").exists().then_some(d)
}

fn ponytail_paths(d: &Path) -> Vec<PathBuf> {
    ["front_top", "side", "back", "tail"]
        .iter()
        .map(|p| d.join(format!("{p}.tfx")))
        .collect()
}

#[test]
fn the_shared_ponytail_loads_as_one_groom_on_the_head() {
    let Some(dir) = ponytail_dir() else {
        println!("skipped: ../shared/data/hair/tressfx-ponytail is missing");
        return;
    };
    let paths = ponytail_paths(&dir);
    let refs: Vec<&Path> = paths.iter().map(|p| p.as_path()).collect();
    let g = load_groom(
        &refs,
        &Hairstyle::default_smooth(),
        &GroomOptions::default(),
    )
    .unwrap();
    let r = &g.report;
    // ../shared/data/README.md: 4,933 strands of 16 vertices.
    assert_eq!(r.strands_read, 4933);
    assert_eq!(r.strands_dropped, 0);
    assert_eq!(g.layout.count(), 4933);
    assert_eq!(r.wisps, g.layout.wisp_guides.len());
    assert!((150..=4933 / 3).contains(&r.wisps), "{}", r.wisps);
    // Its ponytail hangs toward +Z in the file: turned to wisp's back (−Z).
    let p = r.placement.unwrap();
    assert!((p.yaw_rad - std::f32::consts::PI).abs() < 1e-6);
    // Roots on the scalp (a real head is not an ellipsoid, the ponytail's tie is off it).
    assert!(r.root_distance_mean_m < 0.01, "{r:?}");
    // The rest pose is the file's, to a fraction of a millimetre (16 vertices resampled to
    // 31 points: only corner cutting at the file's vertices remains).
    assert!(r.rest_distance_mean_m < 1e-5, "{r:?}");
    assert!(r.rest_distance_max_m < 1e-3, "{r:?}");
    assert!(g.guides.rest.iter().all(|p| p.is_finite()));
}

/// An engine for a groom, head at the identity, no solids so only hair is drawn.
fn groom_engine(g: &Groom, motion: Motion, size: u32, simulate: bool) -> Engine {
    let config = {
        let mut config = EngineConfig::sized(size, size);
        config.scene.draw_solids = false;
        config.simulation.simulate = simulate;
        config.simulation.settle_s = 0.5;
        config
    };
    Engine::with_hair(
        g.style.clone(),
        g.guides.clone(),
        g.layout.clone(),
        motion,
        config,
    )
}

#[test]
fn a_generated_cyhair_file_renders() {
    let dir = std::env::temp_dir().join(format!("wisp-groom-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("arcs.hair");
    std::fs::write(&path, encode_cyhair(&arcs(300))).unwrap();
    let g = load_groom(
        &[path.as_path()],
        &Hairstyle::default_smooth(),
        &GroomOptions::default(),
    )
    .unwrap();
    let mut e = groom_engine(&g, Motion::still(Affine3A::IDENTITY), 96, true);
    let bg = e.scene.background;
    let fb = e.frame(0.0);
    let mut hair = 0;
    for y in 0..96 {
        for x in 0..96 {
            let c = fb.pixel(x, y).unwrap();
            assert!(c.is_finite(), "non-finite pixel at {x},{y}");
            if (c - bg).abs().max_element() > 1e-3 {
                hair += 1;
            }
        }
    }
    // The camera frames the hair: it covers a good part of the image.
    assert!(hair > 96 * 96 / 20, "{hair} hair pixels");
    // And through the command line, with the figures printed.
    let out = Command::new(env!("CARGO_BIN_EXE_wisp"))
        .args(["render", "--still", "--width", "48", "--height", "48"])
        .arg("--hairstyle")
        .arg(&path)
        .arg("--out")
        .arg(dir.join("frames"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("rest pose vs file"), "{err}");
    assert!(dir.join("frames/frame_00000.png").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_malformed_groom_exits_with_code_2_naming_file_offset_and_rule() {
    let dir = std::env::temp_dir().join(format!("wisp-groom-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.tfx");
    let mut bytes = encode_tfx3(&arcs(4));
    bytes.truncate(400);
    std::fs::write(&path, &bytes).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_wisp"))
        .args(["render", "--still", "--hairstyle"])
        .arg(&path)
        .arg("--out")
        .arg(dir.join("frames"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("bad.tfx") && err.contains("byte 296") && err.contains("vertex positions"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn imported_groom_frames_are_byte_identical_with_one_and_two_threads() {
    let strands = arcs(400);
    let render = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            // The import (clustering, offsets) runs in the pool too.
            let f = parse_strand_file(&encode_tfx3(&strands), "a.tfx").unwrap();
            let g = build_groom(
                &[("a.tfx".into(), f)],
                &Hairstyle::default_smooth(),
                &GroomOptions::default(),
            )
            .unwrap();
            let mut e = groom_engine(&g, Motion::default_dance(), 120, true);
            let frames: Vec<Vec<u8>> = (0..3)
                .map(|i| e.frame(1.0 + i as f64 / 30.0).to_srgb8())
                .collect();
            (g.layout.strand_wisp.clone(), frames)
        })
    };
    let (wa, a) = render(1);
    let (wb, b) = render(2);
    assert_eq!(wa, wb, "clustering differs between 1 and 2 threads");
    for (i, (fa, fb)) in a.iter().zip(&b).enumerate() {
        assert!(fa == fb, "frame {i} differs between 1 and 2 threads");
    }
}

#[test]
fn an_imported_groom_moves_with_the_head() {
    // Without simulation the hair rides on the head: a turned head turns the groom rigidly,
    // offsets included (they live in the guides' frame).
    let strands = arcs(120);
    let f = parse_strand_file(&encode_tfx3(&strands), "a.tfx").unwrap();
    let g = build_groom(
        &[("a.tfx".into(), f)],
        &Hairstyle::default_smooth(),
        &GroomOptions::default(),
    )
    .unwrap();
    let head = Affine3A::from_rotation_translation(
        glam::Quat::from_rotation_y(1.1) * glam::Quat::from_rotation_x(0.4),
        Vec3::new(0.1, 1.5, -0.2),
    );
    let mut e = groom_engine(&g, Motion::still(head), 32, false);
    e.advance(0.0);
    // The same groom on an unturned head: the engine keeps render points out of the head
    // ellipsoid (`interp::solids`), which moves with the head, so compare engine with engine.
    let mut still = groom_engine(&g, Motion::still(Affine3A::IDENTITY), 32, false);
    still.advance(0.0);
    let worst = e
        .strands()
        .positions
        .iter()
        .zip(&still.strands().positions)
        .map(|(moved, r)| (*moved - head.transform_point3(*r)).length())
        .fold(0.0f32, f32::max);
    // f32 rounding at 1.5 m from the origin (an ulp is 0.12 µm) over the ~30 operations of the
    // blend, spline and frame transport along a strand: 10 µm.
    assert!(worst < 1e-5, "{worst} m");
}

/// Regression (found by the hostile-loaders suite): a strand whose coordinates are finite but
/// near f32::MAX made every feature distance infinite, the grid search found no centroid and
/// the clustering indexed wisp u32::MAX (a panic). Now every strand gets a wisp, and a groom
/// whose coordinates overflow once placed is refused with the strand.
#[test]
fn infinite_feature_distances_still_give_every_strand_a_wisp() {
    let mut features: Vec<Feature> = (0..30)
        .map(|i| [i as f32 * 0.01, 0.0, 0.0, 0.0, -0.1, 0.0, 0.0, -0.2, 0.0])
        .collect();
    features[7] = [3e38, -3e38, 3e38, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    features[9][4] = f32::INFINITY;
    let wisp = cluster(&features, 5);
    assert_eq!(wisp.len(), 30);
    let wisps = *wisp.iter().max().unwrap() as usize + 1;
    assert!(wisps <= 5);

    let mut strands = arcs(60);
    strands[5] = (0..VERTICES)
        .map(|k| Vec3::new(3e38, -3e38 + k as f32 * 1e32, 0.0))
        .collect();
    let f = parse_strand_file(&encode_tfx3(&strands), "huge.tfx").unwrap();
    match build_groom(
        &[("huge.tfx".into(), f)],
        &Hairstyle::default_smooth(),
        &GroomOptions::default(),
    ) {
        Ok(g) => assert!(g.guides.rest.iter().all(|p| p.is_finite())),
        Err(e) => assert!(e.to_string().contains("huge.tfx"), "{e}"),
    }
}

#[test]
fn an_imported_groom_drops_the_hairstyle_s_curls_and_so_their_advice() {
    // The CLI warns about what will be drawn: a coarse-curled hairstyle warns on its own, but a
    // groom keeps its own shape (no curls), so the same hairstyle under a groom does not.
    let mut base = Hairstyle::default_curly();
    base.strands.points = 61;
    assert_eq!(base.advisories().len(), 1);
    let f = parse_strand_file(&encode_cyhair(&arcs(60)), "g.hair").unwrap();
    let g = build_groom(&[("g.hair".into(), f)], &base, &GroomOptions::default()).unwrap();
    assert_eq!(g.style.curl_turn_per_segment_deg(), None);
    assert!(g.style.advisories().is_empty());
}
