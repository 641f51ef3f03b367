//! `wisp::accuracy::LevelTfReference`: a quality level's key-light map against the exact
//! reference of the full hair, as `wisp bench --quality-list` reports it ("Tf MAE"), on a
//! small groom (40 wisps of 8 strands of 10 fibres) a second into the dance.

use crate::common;
use wisp::accuracy::LevelTfReference;
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;
use wisp::quality::Quality;

fn small_style() -> Hairstyle {
    let mut style = Hairstyle::default_smooth();
    style.wisps.count = 40;
    style.wisps.strands_per_wisp = 8;
    style.strands.fibers_per_strand = 10.0;
    style
}

/// The engine at `quality`, 96 × 96, briefly settled.
fn engine_at(quality: Quality) -> Engine {
    let mut config = EngineConfig::at_quality(quality);
    config.scene.width = 96;
    config.scene.height = 96;
    config.simulation.settle_s = 0.3;
    Engine::new(small_style(), Motion::default_dance(), config)
}

/// `engine` drawing the guide particles `guides` at `t_s` (its map built for them).
fn drawn(mut engine: Engine, t_s: f64, guides: &[glam::Vec3]) -> Engine {
    engine.set_guide_state(t_s, guides);
    engine.render();
    engine
}

#[test]
fn a_map_read_at_its_own_hair_is_near_the_reference_and_the_figure_is_deterministic() {
    let mut full = engine_at(Quality::Final);
    full.run_up_to(1.0);
    let guides = full.state().positions.clone();
    let full = drawn(full, 1.0, &guides);
    let reference = LevelTfReference::new(&full, 400, 8);
    assert_eq!((reference.vertices(), reference.placements()), (400, 8));
    // Measured: MAE 0.038, the reference's own noise (8 placements of 32 rays) included.
    let own = reference.compare(&full);
    assert!(own.vertices == 400 && own.mae < 0.05, "{own:?}");
    // The same reference and reading again, on one thread: the same figures, bit for bit.
    let again = common::on_threads(1, || LevelTfReference::new(&full, 400, 8).compare(&full));
    assert_eq!(again, own);
    // The preview level from the same guides draws half the strands, read where the full
    // hair is: a figure of the same kind (measured: 0.042).
    let preview = drawn(engine_at(Quality::Preview), 1.0, &guides);
    let thinned = reference.compare(&preview);
    assert!(thinned.mae.is_finite() && thinned.mae < 0.1, "{thinned:?}");
    // A map of the hair at 4.5 s, in the dance's fastest head motions, does not describe this
    // hair: the figure says so (measured: 0.164).
    let mut later = engine_at(Quality::Final);
    later.run_up_to(4.5);
    later.render();
    let moved = reference.compare(&later);
    assert!(moved.mae > 2.0 * own.mae, "{moved:?} against {own:?}");
}
