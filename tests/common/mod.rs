//! Helpers shared by integration tests.
#![allow(dead_code)]

use glam::Vec3;
use wisp::fiber::{Fiber, FiberParams};
use wisp::hairstyle::{Hairstyle, generate};
use wisp::interp::{StrandGeometry, interpolate};
use wisp::map::{CountModel, LightMap, MapBuildInput, MapGeometry};

/// Rest-pose render strands of a preset.
pub fn rest_strands(style: &Hairstyle) -> StrandGeometry {
    let (g, layout) = generate(style);
    let mut geo = StrandGeometry::default();
    interpolate(&g, &layout, &style.curl, &g.rest, &mut geo);
    geo
}

pub fn default_fiber() -> Fiber {
    Fiber::new(&FiberParams::default())
}

/// Builds a map of `geo` lit along `light`.
pub fn build_map(
    geo: &StrandGeometry,
    fiber: &Fiber,
    geom: MapGeometry,
    light: Vec3,
    fibers: f32,
) -> LightMap {
    let mut map = LightMap::new(geom, CountModel::Poisson);
    map.build(&MapBuildInput {
        positions: &geo.positions,
        tangents: &geo.tangents,
        lengths_m: &geo.lengths_m,
        fibers_per_strand: fibers,
        light_dir: light,
        fiber,
    });
    map
}

/// Directory for test outputs under target/.
pub fn out_dir(name: &str) -> std::path::PathBuf {
    let d = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&d).expect("create test output dir");
    d
}

/// `../shared/data/animations/RobotExpressive.glb` (CC0), or `None` with a printed skip
/// message when the shared data is not beside the checkout.
pub fn robot_expressive_glb() -> Option<std::path::PathBuf> {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/data/animations/RobotExpressive.glb");
    if p.exists() {
        Some(p)
    } else {
        println!(
            "skipped: {} is absent (see ../shared/data/README.md)",
            p.display()
        );
        None
    }
}
