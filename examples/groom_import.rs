//! Import figures for BENCHMARKS.md ("Captured grooms"): import and clustering time of the TressFX
//! ponytail and of a generated 50,000-strand groom, the rest-pose distance to the file, and how
//! far the settled hair (2 s under gravity, head still) moves from the file's pose.
//!
//! `cargo run --release --example groom_import [-- PONYTAIL_DIR]`

use glam::{Affine3A, Vec3};
use std::path::{Path, PathBuf};
use std::time::Instant;
use wisp::engine::{Engine, EngineConfig};
use wisp::groom::{GroomOptions, build_groom, load_groom, synthetic_strands};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

fn settled_distance_mm(groom: &wisp::groom::Groom) -> (f32, f32) {
    let config = EngineConfig::sized(64, 64);
    let engine = Engine::with_hair(
        groom.style.clone(),
        groom.guides.clone(),
        groom.layout.clone(),
        Motion::still(Affine3A::IDENTITY),
        config,
    );
    let mut rest = wisp::interp::StrandGeometry::default();
    wisp::interp::interpolate(
        &groom.guides,
        &groom.layout,
        &groom.style.curl,
        &groom.guides.rest,
        &mut rest,
    );
    // The same without the offsets: how far the wisps' blended centre lines moved.
    let mut bare = groom.layout.clone();
    bare.rest_offset.clear();
    let (mut c_rest, mut c_now) = (
        wisp::interp::StrandGeometry::default(),
        wisp::interp::StrandGeometry::default(),
    );
    wisp::interp::interpolate(
        &groom.guides,
        &bare,
        &groom.style.curl,
        &groom.guides.rest,
        &mut c_rest,
    );
    wisp::interp::interpolate(
        &groom.guides,
        &bare,
        &groom.style.curl,
        &engine.simulation.state.positions,
        &mut c_now,
    );
    let dc: Vec<f32> = c_rest
        .positions
        .iter()
        .zip(&c_now.positions)
        .map(|(a, b)| (*a - *b).length() * 1e3)
        .collect();
    println!(
        "  centre lines (no offsets) moved: mean {:.1} mm, max {:.1} mm",
        dc.iter().sum::<f32>() / dc.len() as f32,
        dc.iter().copied().fold(0.0, f32::max)
    );
    let d: Vec<f32> = rest
        .positions
        .iter()
        .zip(&engine.strands().positions)
        .map(|(a, b)| (*a - *b).length() * 1e3)
        .collect();
    (
        d.iter().sum::<f32>() / d.len() as f32,
        d.iter().copied().fold(0.0, f32::max),
    )
}

fn main() {
    let dir = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("../shared/data/hair/tressfx-ponytail"));
    let base = Hairstyle::default_smooth();
    let parts = ["front_top", "side", "back", "tail"].map(|p| dir.join(format!("{p}.tfx")));
    if parts.iter().all(|p| p.exists()) {
        let paths: Vec<&Path> = parts.iter().map(|p| p.as_path()).collect();
        for wisps in [None, Some(1600)] {
            let t = Instant::now();
            let groom = load_groom(
                &paths,
                &base,
                &GroomOptions {
                    wisps,
                    ..Default::default()
                },
            )
            .expect("ponytail loads");
            let total = t.elapsed().as_secs_f64();
            let r = &groom.report;
            println!(
                "ponytail: {} strands, {} wisps: import {:.1} ms (clustering {:.1} ms); rest vs file mean {:.4} mm max {:.3} mm",
                r.strands_read,
                r.wisps,
                total * 1e3,
                r.cluster_s * 1e3,
                r.rest_distance_mean_m * 1e3,
                r.rest_distance_max_m * 1e3
            );
            let (share, deepest) = inside_head(&groom);
            println!(
                "  guide particles inside the head at rest: {:.1}%, deepest {deepest:.1} mm",
                share * 100.0
            );
            // The settle runs before any map exists, so self-collision plays no part in it.
            let (mean, max) = settled_distance_mm(&groom);
            println!(
                "  settled 2 s: render points from the file's pose mean {mean:.1} mm, max {max:.1} mm"
            );
        }
    } else {
        println!("skipped: ponytail not found in {}", dir.display());
    }
    for count in [5_000, 50_000] {
        let file = synthetic_strands(count, 24);
        let t = Instant::now();
        let groom = build_groom(
            &[("synthetic".into(), file)],
            &base,
            &GroomOptions::default(),
        )
        .expect("synthetic groom builds");
        let total = t.elapsed().as_secs_f64();
        let r = &groom.report;
        println!(
            "synthetic: {count} strands x 24 points, {} wisps: build {:.1} ms (clustering {:.1} ms); rest vs file mean {:.4} mm max {:.3} mm",
            r.wisps,
            total * 1e3,
            r.cluster_s * 1e3,
            r.rest_distance_mean_m * 1e3,
            r.rest_distance_max_m * 1e3
        );
    }
}

/// Share of guide particles (past the pinned root link) inside the head ellipsoid, and the
/// deepest, millimetres: the collision pushes them out as the hair settles.
pub fn inside_head(groom: &wisp::groom::Groom) -> (f32, f32) {
    let r = Vec3::from(groom.style.head.radii_m);
    let ppg = groom.guides.points_per_guide;
    let (mut inside, mut total, mut deepest) = (0usize, 0usize, 0.0f32);
    for (i, p) in groom.guides.rest.iter().enumerate() {
        if i % ppg < 2 {
            continue;
        }
        total += 1;
        if (*p / r).length() < 1.0 {
            inside += 1;
            deepest = deepest.max(wisp::groom::fit::surface_distance_m(*p, r) * 1e3);
        }
    }
    (inside as f32 / total as f32, deepest)
}
