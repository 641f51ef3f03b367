//! Scratch measurement: the map against the exact reference (issue 7).
use glam::Vec3;
use std::time::Instant;
use wisp::fiber::LightAtPoint;
use wisp::frame::{Engine, EngineConfig};
use wisp::hairstyle::{Hairstyle, SplitMix64};
use wisp::map::exact::{ExactInput, ExactReference, Footprint};
use wisp::map::{CountModel, LightMap, MapBuildInput, MapGeometry};
use wisp::motion::{MotionOptions, dance::try_dance};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let preset = args.get(1).map(|s| s.as_str()).unwrap_or("smooth");
    let f_override: Option<u32> = args.get(2).and_then(|s| s.parse().ok());
    let fp_scale: f32 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1.0);
    let mut style = match preset {
        "curly" => Hairstyle::default_curly(),
        _ => Hairstyle::default_smooth(),
    };
    if let Some(k) = f_override {
        // one-fibre-per-strand variant: k x strands, 1 fibre each
        style.wisps.strands_per_wisp *= k;
        style.strands.fibers_per_strand = 1.0;
    }
    let motion = try_dance(&MotionOptions::default()).unwrap();
    let config = EngineConfig {
        width: 200,
        height: 200,
        ..Default::default()
    };
    let mut engine = Engine::new(style.clone(), motion, config.clone());
    engine.run_up_to(4.0);
    engine.frame(4.0);
    let s = style.strand_spacing_m();
    let ppl = engine.strands.points_per_strand;
    let fibers = style.strands.fibers_per_strand;
    let t0 = Instant::now();
    let exact = ExactReference::build(
        &ExactInput {
            positions: &engine.strands.positions,
            fibre_share: &engine.strands.fibre_share,
            points_per_strand: ppl,
            fibers_per_strand: fibers.round() as u32,
            bundle_radius_m: 0.5 * s,
            light_dir: config.lighting.light_dir,
            fiber: &engine.fiber,
        },
        0.5 * s,
    );
    let build_ms = t0.elapsed().as_secs_f64() * 1e3;
    let nv = engine.strands.positions.len();
    let mut rng = SplitMix64::new(7);
    let verts: Vec<usize> = (0..3000)
        .map(|_| (rng.next_u64() % nv as u64) as usize)
        .collect();
    let geom_default = engine.map_geometry();
    let fp = if let Some(r) = std::env::var("BALL")
        .ok()
        .and_then(|v| v.parse::<f32>().ok())
    {
        Footprint::Ball {
            radius_m: r * s,
            rays: 128,
        }
    } else if std::env::var("FIBRES").is_ok() {
        Footprint::Fibres { rays: 128 }
    } else {
        Footprint::Disc {
            radius_m: fp_scale * s,
            rays: 128,
            exclude_segments: std::env::var("EXCL")
                .ok()
                .and_then(|v| v.parse().ok())
                .unwrap_or(1),
        }
    };
    let t0 = Instant::now();
    let truth = exact.light_at_vertices(&verts, &fp);
    let q_ms = t0.elapsed().as_secs_f64() * 1e3;
    println!(
        "{preset}: s = {:.2} mm, segments {}, build {build_ms:.0} ms, 3000 queries {q_ms:.0} ms, default N {}",
        s * 1e3,
        exact.segment_count(),
        geom_default.n
    );
    let span = MapGeometry::span_m(style.max_length_m(), style.head_size_m());
    let input = MapBuildInput {
        positions: &engine.strands.positions,
        tangents: &engine.strands.tangents,
        lengths_m: &engine.strands.lengths_m,
        fibers_per_strand: fibers,
        light_dir: config.lighting.light_dir,
        fiber: &engine.fiber,
    };
    let warp_m: Option<f32> = std::env::var("WARP").ok().and_then(|v| v.parse().ok());
    for n in std::env::var("NS")
        .map(|v| {
            v.split(",")
                .map(|x| x.parse::<u32>().unwrap())
                .collect::<Vec<_>>()
        })
        .unwrap_or(vec![32u32, 64, 96, 129, 192, 256])
    {
        let mut map = LightMap::new(MapGeometry::with_resolution(span, n), CountModel::Poisson);
        let warped;
        let (pos, input) = if let Some(mfine) = warp_m {
            warped = warp(
                &engine.strands.positions,
                config.lighting.light_dir,
                span / n as f32 / mfine,
            );
            (
                &warped,
                MapBuildInput {
                    positions: &warped,
                    ..input
                },
            )
        } else {
            (&engine.strands.positions, MapBuildInput { ..input })
        };
        map.build(&input);
        let t0 = Instant::now();
        for _ in 0..5 {
            map.build(&input);
        }
        let b_ms = t0.elapsed().as_secs_f64() * 1e3 / 5.0;
        let t0 = Instant::now();
        let mut acc = 0.0f32;
        for p in pos.iter() {
            acc += map.light_at(*p).direct_fraction;
        }
        let l_ms = t0.elapsed().as_secs_f64() * 1e3;
        println!(
            "N={n}: build {b_ms:.1} ms, {} lookups {l_ms:.1} ms ({acc:.0}), cells {}",
            pos.len(),
            map.stats().filled_cells
        );
        let est: Vec<LightAtPoint> = verts.iter().map(|&v| map.light_at(pos[v])).collect();
        report(n, &truth, &est);
    }
}

fn report(n: u32, truth: &[LightAtPoint], est: &[LightAtPoint]) {
    let edges = [0.0f32, 0.2, 0.5, 0.8, 1.01];
    let mean = |v: Vec3| (v.x + v.y + v.z) / 3.0;
    let mut line = format!("N={n:4}");
    let (mut mae, mut cnt) = (0.0f64, 0usize);
    let mut bins = String::new();
    for b in 0..4 {
        let (mut e, mut bias, mut c, mut dbias) = (0.0f64, 0.0f64, 0usize, 0.0f64);
        for (t, m) in truth.iter().zip(est) {
            let tv = mean(t.tf);
            if tv >= edges[b] && tv < edges[b + 1] {
                let d = (m.tf - t.tf).abs();
                e += mean(d) as f64;
                bias += mean(m.tf - t.tf) as f64;
                dbias += (m.direct_fraction - t.direct_fraction) as f64;
                c += 1;
            }
        }
        mae += e;
        cnt += c;
        let c1 = c.max(1) as f64;
        bins += &format!(
            " | [{:.1},{:.1}) n={c:4} mae {:.3} bias {:+.3} dbias {:+.3}",
            edges[b],
            edges[b + 1].min(1.0),
            e / c1,
            bias / c1,
            dbias / c1
        );
    }
    line += &format!(" MAE {:.4}", mae / cnt as f64);
    println!("{line}{bins}");
    // Calibration: binned by the estimate.
    let mut cal = String::from("        by estimate:");
    let mut all_bias = 0.0f64;
    for b in 0..4 {
        let (mut bias, mut c) = (0.0f64, 0usize);
        for (t, m) in truth.iter().zip(est) {
            let mv = mean(m.tf);
            if mv >= edges[b] && mv < edges[b + 1] {
                bias += mean(m.tf - t.tf) as f64;
                c += 1;
            }
        }
        all_bias += bias;
        cal += &format!(
            " | [{:.1},{:.1}) n={c:4} bias {:+.3}",
            edges[b],
            edges[b + 1].min(1.0),
            bias / c.max(1) as f64
        );
    }
    println!("{cal} | overall bias {:+.4}", all_bias / truth.len() as f64);
}

/// Surface-relative warp (deep-opacity-map prototype): x -> x - z0(y, z), z0 = min x over a
/// 3x3 neighbourhood of fine lateral cells of size `fine`.
fn warp(pos: &[Vec3], light: Vec3, fine: f32) -> Vec<Vec3> {
    use std::collections::HashMap;
    let frame = wisp::map::LightFrame::new(light);
    let key = |m: Vec3| ((m.y / fine).floor() as i64, (m.z / fine).floor() as i64);
    let mut z0: HashMap<(i64, i64), f32> = HashMap::new();
    for p in pos {
        let m = frame.to_map(*p);
        let e = z0.entry(key(m)).or_insert(f32::MAX);
        *e = e.min(m.x);
    }
    pos.iter()
        .map(|p| {
            let m = frame.to_map(*p);
            let (a, b) = key(m);
            let mut s = f32::MAX;
            for da in -1..=1 {
                for db in -1..=1 {
                    if let Some(v) = z0.get(&(a + da, b + db)) {
                        s = s.min(*v);
                    }
                }
            }
            let x = m.x - s + 0.5; // offset keeps it positive
            frame.to_world(Vec3::new(x, m.y, m.z))
        })
        .collect()
}
