//! The memory budget against the memory really allocated: an engine is built and run for a few
//! frames on its own thread under the counting allocator, and its peak heap is compared with
//! `wisp::engine::estimate`. The estimate must hold the peak (it is what refuses runs before
//! they allocate), and stay within a stated factor of it for the presets (a budget that
//! overstates ten-fold refuses runs that would fit).

use crate::bounded::run_bounded;
use serde_json::{Value, json};
use std::time::Duration;
use wisp::budget::RunPlan;
use wisp::engine::estimate;
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::{Hairstyle, SMOOTH_JSON};
use wisp::motion::Motion;

/// Peak heap of building `style` on the dance and rendering `frames` frames, and the estimate.
/// The dance's mannequin gives a hairstyle its head's size, so a hairstyle whose own head
/// matters is measured on the dance without its meshes (`own_head`).
fn measure(style: Hairstyle, config: EngineConfig, frames: u32, own_head: bool) -> (usize, u64) {
    let motion = if own_head {
        wisp::motion::dance::try_dance(&wisp::motion::MotionOptions {
            meshes: false,
            ..Default::default()
        })
        .expect("the dance")
    } else {
        Motion::default_dance()
    };
    let plan = RunPlan {
        export_png: false,
        ..RunPlan::default()
    };
    let est = estimate(&style, &motion, &config, &plan).memory_bytes();
    let report = run_bounded(
        move || {
            // The engine's threads allocate too; one thread keeps the whole run on this
            // thread's count.
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(1)
                .use_current_thread()
                .build()
                .expect("pool");
            pool.install(|| {
                let mut engine = Engine::new(style, motion, config);
                for i in 0..frames {
                    engine.frame(i as f64 / 30.0);
                }
            })
        },
        Duration::from_secs(600),
    )
    .expect("the engine runs");
    (report.peak_bytes, est)
}

fn smooth_with(edit: impl FnOnce(&mut Value)) -> Hairstyle {
    let mut v: Value = serde_json::from_str(SMOOTH_JSON).unwrap();
    edit(&mut v);
    Hairstyle::from_json(&v.to_string(), "test.json").unwrap()
}

fn small() -> EngineConfig {
    {
        let mut config = EngineConfig::sized(200, 200);
        config.simulation.settle_s = 0.2;
        config
    }
}

/// `config` with the light paths' shader (`--shading volume`) and `paths` paths.
fn volume(mut config: EngineConfig, paths: u32) -> EngineConfig {
    config.shading.mode = wisp::fiber::ShadingMode::Volume;
    config.shading.light_paths.paths = paths;
    config
}

/// `config` with its hair lines at least `px` wide (`--min-line-width-px`): each segment then
/// covers `px` pixels of every row it crosses, so the raster's fragments grow with it.
fn min_line_width(mut config: EngineConfig, px: f32) -> EngineConfig {
    config.raster.line.width = wisp::raster::LineWidth::Projected { min_px: px };
    config
}

#[test]
fn the_estimate_holds_the_peak_heap() {
    let cases: Vec<(&str, Hairstyle, EngineConfig)> = vec![
        ("smooth", Hairstyle::default_smooth(), small()),
        ("curly", Hairstyle::default_curly(), small()),
        ("smooth, map 384", Hairstyle::default_smooth(), {
            let mut config = small();
            config.hair_map.map_res = Some(384);
            config
        }),
        (
            "1 cm head",
            smooth_with(|v| v["head"]["radii_m"] = json!([0.01, 0.01, 0.01])),
            small(),
        ),
        (
            "one long segment per strand",
            smooth_with(|v| v["strands"]["points"] = json!(2)),
            small(),
        ),
        (
            "dense: 40 strands per wisp, 60 links",
            smooth_with(|v| {
                v["wisps"]["strands_per_wisp"] = json!(40);
                v["guides"]["links"] = json!(60);
            }),
            small(),
        ),
        (
            "smooth, --shading volume",
            Hairstyle::default_smooth(),
            volume(small(), 200_000),
        ),
        (
            "smooth, --min-line-width-px 64 (the widest accepted)",
            Hairstyle::default_smooth(),
            min_line_width(small(), 64.0),
        ),
        (
            "dense, --min-line-width-px 64",
            smooth_with(|v| v["wisps"]["strands_per_wisp"] = json!(40)),
            min_line_width(small(), 64.0),
        ),
        (
            "dense, --shading volume",
            smooth_with(|v| v["wisps"]["strands_per_wisp"] = json!(40)),
            volume(small(), 200_000),
        ),
    ];
    for (name, style, config) in cases {
        let own_head = name == "1 cm head";
        let (peak, est) = measure(style, config, 3, own_head);
        println!(
            "{name}: peak heap {:.1} MB, estimate {:.1} MB ({:.2}x)",
            peak as f64 / 1e6,
            est as f64 / 1e6,
            est as f64 / peak as f64
        );
        assert!(
            est as usize >= peak,
            "{name}: estimate {est} B < peak {peak} B"
        );
    }
}
