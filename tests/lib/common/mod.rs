//! Helpers shared by the library tests.

pub mod golden;

use glam::Vec3;
use wisp::fiber::{Fiber, FiberParams};
use wisp::hairstyle::{Hairstyle, generate};
use wisp::interp::{StrandGeometry, interpolate};
use wisp::map::{CountModel, LightFrame, LightMap, MapBuildInput, MapGeometry};

/// Runs `f` on a pool of exactly `threads` worker threads (the determinism tests compare 1
/// and 2).
pub fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
        .install(f)
}

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

/// A slab of hair filling slices `slices` (cells of `ds` metres along the light) and lateral
/// columns −8..8, fibres along map Y, `len_m` of hair per sample on a 2 × 2 × 2 lattice per
/// cell (`map_slab.rs`, `map_surface.rs`).
pub fn slab(
    frame: &LightFrame,
    slices: std::ops::Range<i32>,
    ds: f32,
    len_m: f32,
) -> StrandGeometry {
    let mut geo = StrandGeometry {
        points_per_strand: 1,
        ..Default::default()
    };
    for i in slices {
        for j in -8..8 {
            for k in -8..8 {
                for s in 0..8 {
                    let sub =
                        Vec3::new((s & 1) as f32, ((s >> 1) & 1) as f32, ((s >> 2) & 1) as f32);
                    let m = (Vec3::new(i as f32, j as f32, k as f32) + 0.25 + 0.5 * sub) * ds;
                    geo.positions.push(frame.to_world(m));
                    geo.tangents.push(frame.y);
                    geo.lengths_m.push(len_m);
                    geo.fiber_share.push(1.0);
                }
            }
        }
    }
    geo
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
        fiber_share: &geo.fiber_share,
        fibers_per_strand: fibers,
        light: light.into(),
        fiber,
    });
    map
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

/// The point of triangle `abc` nearest `p` and its barycentric weights (Ericson, Real-Time
/// Collision Detection §5.1.5: by Voronoi region).
pub fn closest_on_triangle(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> (Vec3, [f32; 3]) {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, [1.0, 0.0, 0.0]);
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return (b, [0.0, 1.0, 0.0]);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (a + ab * v, [1.0 - v, v, 0.0]);
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return (c, [0.0, 0.0, 1.0]);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (a + ac * w, [1.0 - w, 0.0, w]);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, [0.0, 1.0 - w, w]);
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    (a + ab * v + ac * w, [1.0 - v - w, v, w])
}

/// Penetration (metres) of each of `points` under a mesh's surface, looked for within
/// `SEARCH_M` of it: a point is under the surface when it lies behind the nearest triangle,
/// judged by the vertex normals interpolated at the nearest point (right for smooth closed
/// surfaces; where parts of a mesh interpenetrate, a point inside one part near another's
/// surface counts by that surface). Triangles are binned in a uniform grid of `SEARCH_M`
/// cells, so the cost is linear in points and triangles.
pub fn mesh_penetrations_m(
    positions: &[Vec3],
    normals: &[Vec3],
    triangles: &[[u32; 3]],
    points: &[Vec3],
) -> Vec<f32> {
    const SEARCH_M: f32 = 0.03;
    use std::collections::HashMap;
    let cell = |p: Vec3| (p / SEARCH_M).floor().as_ivec3();
    let mut grid: HashMap<glam::IVec3, Vec<u32>> = HashMap::new();
    for (t, tri) in triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|i| positions[i as usize]);
        let (lo, hi) = (
            cell(a.min(b).min(c) - SEARCH_M),
            cell(a.max(b).max(c) + SEARCH_M),
        );
        for x in lo.x..=hi.x {
            for y in lo.y..=hi.y {
                for z in lo.z..=hi.z {
                    grid.entry(glam::IVec3::new(x, y, z))
                        .or_default()
                        .push(t as u32);
                }
            }
        }
    }
    let mut out = vec![0.0f32; points.len()];
    for (p, o) in points.iter().zip(&mut out) {
        let Some(list) = grid.get(&cell(*p)) else {
            continue;
        };
        let mut best = (SEARCH_M, 0.0f32);
        for &t in list {
            let tri = triangles[t as usize];
            let [a, b, c] = tri.map(|i| positions[i as usize]);
            let (q, w) = closest_on_triangle(*p, a, b, c);
            let d = (*p - q).length();
            if d < best.0 {
                let n = tri
                    .iter()
                    .zip(w)
                    .map(|(&i, wi)| normals[i as usize] * wi)
                    .sum::<Vec3>();
                let behind = (*p - q).dot(n) < 0.0;
                best = (d, if behind { d } else { 0.0 });
            }
        }
        *o = best.1;
    }
    out
}

/// Camera at the origin looking down −Z, 90° vertical fov: focal length = height / 2, so a
/// point (x, y, −1) lands on pixel (w/2 + f·x, h/2 − f·y).
pub fn axis_camera(w: u32, h: u32) -> wisp::raster::Camera {
    wisp::raster::Camera::look_at(
        Vec3::ZERO,
        Vec3::NEG_Z,
        Vec3::Y,
        std::f32::consts::FRAC_PI_2,
        w,
        h,
    )
}

/// World point at depth `z` that projects to pixel position (px, py) for [`axis_camera`].
pub fn unproject(cam: &wisp::raster::Camera, px: f32, py: f32, z: f32) -> Vec3 {
    let f = cam.focal_px();
    let (cx, cy) = (0.5 * cam.width as f32, 0.5 * cam.height as f32);
    Vec3::new((px - cx) / f * z, -(py - cy) / f * z, -z)
}
