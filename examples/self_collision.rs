//! What self-collision does to the hair, measured on the light map as `wisp bench` does
//! (section 2), without shading or drawing: peak cell volume fraction and hair volume (filled
//! cells) averaged over frames of the dance, with self-collision off and on, and the
//! simulation time per frame.
//!
//! ```text
//! cargo run --release --example self_collision -- [--hairstyle smooth|curly|FILE] [--frames 90]
//!     [--still] [--threshold X] [--repulsion K] [--friction C] [--density-scale S]
//! ```
//!
//! `--threshold`, `--repulsion` and `--friction` override `dynamics.density_threshold`,
//! `repulsion_m2_s2` and `hair_friction_per_s` (to calibrate them); `--density-scale S`
//! multiplies `wisps.count` by S (a denser hairstyle). Frames are 1/30 s apart from t = 0,
//! after the engine's 2 s settle.

use std::time::Instant;
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

fn main() {
    if let Err(e) = run() {
        eprintln!("self_collision: {e}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut style = Hairstyle::default_smooth();
    let mut frames = 90u32;
    let mut still = false;
    let mut i = 0;
    let num = |i: usize| -> Result<f32, String> {
        args.get(i + 1)
            .and_then(|s| s.parse().ok())
            .ok_or(format!("{} needs a number", args[i]))
    };
    let mut overrides: Vec<(usize, f32)> = Vec::new();
    while i < args.len() {
        match args[i].as_str() {
            "--hairstyle" => {
                let v = args.get(i + 1).ok_or("--hairstyle needs a value")?;
                style = match v.as_str() {
                    "smooth" => Hairstyle::default_smooth(),
                    "curly" => Hairstyle::default_curly(),
                    f => Hairstyle::load(std::path::Path::new(f)).map_err(|e| e.to_string())?,
                };
                i += 2;
            }
            "--frames" => {
                frames = num(i)? as u32;
                i += 2;
            }
            "--still" => {
                still = true;
                i += 1;
            }
            "--threshold" => {
                overrides.push((0, num(i)?));
                i += 2;
            }
            "--repulsion" => {
                overrides.push((1, num(i)?));
                i += 2;
            }
            "--friction" => {
                overrides.push((2, num(i)?));
                i += 2;
            }
            "--density-scale" => {
                overrides.push((3, num(i)?));
                i += 2;
            }
            other => return Err(format!("unknown argument {other}")),
        }
    }
    for (k, v) in overrides {
        match k {
            0 => style.dynamics.density_threshold = v,
            1 => style.dynamics.repulsion_m2_s2 = v,
            2 => style.dynamics.hair_friction_per_s = v,
            _ => style.wisps.count = (style.wisps.count as f32 * v).round() as u32,
        }
    }
    style
        .validate()
        .map_err(|(field, rule)| format!("{field}: {rule}"))?;
    let motion = if still {
        Motion::still(glam::Affine3A::IDENTITY)
    } else {
        Motion::default_dance()
    };
    println!(
        "{} ({} wisps), {frames} frames of {}; threshold {}, repulsion {} m²/s², friction {} /s",
        style.name,
        style.wisps.count,
        if still { "a still head" } else { "the dance" },
        style.dynamics.density_threshold,
        style.dynamics.repulsion_m2_s2,
        style.dynamics.hair_friction_per_s
    );
    println!("| self-collision | peak cell volume fraction | hair volume (L) | sim ms / frame |");
    println!("|---|---|---|---|");
    let mut volumes = [0.0f64; 2];
    for (k, on) in [false, true].into_iter().enumerate() {
        let config = {
            let mut config = EngineConfig::sized(16, 16);
            config.simulation.self_collision = on;
            config
        };
        let mut engine = Engine::new(style.clone(), motion.clone(), config);
        let (mut peak, mut volume, mut sim_s) = (0.0f64, 0.0f64, Vec::new());
        for f in 0..frames {
            let t0 = Instant::now();
            engine.advance(f64::from(f) / 30.0);
            sim_s.push(t0.elapsed().as_secs_f64() - engine.timings.interpolation_s);
            engine.build_map();
            peak += f64::from(engine.map_stats().peak_volume_fraction);
            volume += f64::from(engine.map_stats().hair_volume_m3);
        }
        sim_s.sort_by(f64::total_cmp);
        let n = f64::from(frames.max(1));
        volumes[k] = volume / n;
        println!(
            "| {} | {:.3} | {:.2} | {:.2} |",
            if on { "on" } else { "off" },
            peak / n,
            volume / n * 1e3,
            sim_s[sim_s.len() / 2] * 1e3
        );
    }
    println!(
        "hair volume change: {:+.1}%",
        (volumes[1] / volumes[0].max(1e-12) - 1.0) * 100.0
    );
    Ok(())
}
