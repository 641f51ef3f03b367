//! Times one stage (`shade`, `map` or `raster`) alone on a fixed hair state of smooth at
//! 1280×720, for A/B runs of two builds (`farm-bench --vs`, or callgrind with
//! `--toggle-collect`): `cargo run --release --example stage_loop -- [REPS] [STAGE]`.
use wisp::frame::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;
fn main() {
    let reps: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(20);
    let stage = std::env::args().nth(2).unwrap_or_else(|| "shade".into());
    let config = EngineConfig {
        width: 1280,
        height: 720,
        ..EngineConfig::default()
    };
    let mut e = Engine::new(Hairstyle::default_smooth(), Motion::default_dance(), config);
    e.run_up_to(2.0);
    e.frame(2.0);
    let t = std::time::Instant::now();
    for _ in 0..reps {
        match stage.as_str() {
            "map" => {
                e.invalidate_maps();
                e.build_map();
            }
            "raster" => {
                e.draw();
            }
            _ => e.shade(),
        }
    }
    eprintln!(
        "{stage}: {:.2} ms per call",
        t.elapsed().as_secs_f64() * 1e3 / reps as f64
    );
}
