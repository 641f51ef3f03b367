//! Times one stage (`shade`, `map`, `raster` or `solids`: the character and head alone, lit
//! through the maps as in a frame) alone on a fixed hair state of smooth at
//! 1280×720, for A/B runs of two builds (alternated whole-process timings, or callgrind with
//! `--toggle-collect`): `cargo run --release --example stage_loop -- [REPS] [STAGE] [STYLE]
//! [CONTACT_MM]`. STYLE: `smooth` (default), `curly`, `dense`, or `smoothxK` (smooth with K
//! times the strands, one fibre each, as `wisp accuracy --single-fibre-strands K`);
//! CONTACT_MM: the contact window (0 = off; default: the engine's). The environment variable
//! `WISP_AT_S` sets the time in the dance of the timed frame (default 2 s).
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;
fn main() {
    let reps: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(20);
    let stage = std::env::args().nth(2).unwrap_or_else(|| "shade".into());
    let style_name = std::env::args().nth(3).unwrap_or_else(|| "smooth".into());
    let style = match style_name.as_str() {
        "curly" => Hairstyle::default_curly(),
        "dense" => Hairstyle::dense(),
        s => match s.strip_prefix("smoothx").and_then(|k| k.parse().ok()) {
            Some(k) => wisp::accuracy::single_fiber_variant(&Hairstyle::default_smooth(), k),
            None => Hairstyle::default_smooth(),
        },
    };
    let mut config = EngineConfig::sized(1280, 720);
    if let Some(mm) = std::env::args().nth(4).and_then(|a| a.parse::<f32>().ok()) {
        config.hair_map.contact = wisp::engine::ContactShadowing::from_mm(mm);
    }
    let mut e = Engine::new(style, Motion::default_dance(), config);
    let at_s: f64 = std::env::var("WISP_AT_S")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(2.0);
    e.run_up_to(at_s);
    e.frame(at_s);
    // The shadows copied: the solids are drawn into the engine while they are read.
    let shadows = e.shadows();
    let (maps, solids, skin) = (
        shadows.maps.to_vec(),
        shadows.solids.to_vec(),
        shadows.skin.to_vec(),
    );
    let shadows = wisp::map::Shadows {
        maps: &maps,
        solids: &solids,
        skin: &skin,
        earlier: None,
    };
    let scene = e.scene.clone();
    let lighting = e.shading.lighting(&scene);
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
            "solids" => {
                e.solids_image(|p, n, albedo| {
                    wisp::shade::shade_skin(shadows, &lighting, albedo, p, n)
                });
            }
            _ => e.shade(),
        }
    }
    eprintln!(
        "{stage}: {:.2} ms per call",
        t.elapsed().as_secs_f64() * 1e3 / reps as f64
    );
}
