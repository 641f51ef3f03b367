//! Segments cut into pieces (`EngineConfig::segment_pieces`, `--segment-pieces`): the same
//! drawn hair with its light read more often along it. The polyline invariants are proptests
//! in `interp::subdivide`; here, whole frames.

use glam::Affine3A;
use wisp::engine::{ContactShadowing, DEFAULT_CONTACT_WINDOW_M, Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

const SIDE: u32 = 96;

/// Smooth at one fibre per strand (so contact shadows apply), few strands.
fn one_fiber_style() -> Hairstyle {
    let mut style = Hairstyle::default_smooth();
    style.wisps.strands_per_wisp = 40;
    style.strands.fibers_per_strand = 1.0;
    style
}

fn frame(pieces: u32) -> wisp::raster::Framebuffer {
    let config = {
        let mut config = EngineConfig::sized(SIDE, SIDE);
        config.hair_map.contact = ContactShadowing::WindowM(DEFAULT_CONTACT_WINDOW_M);
        config.interpolation.segment_pieces = pieces;
        config
    };
    let mut e = Engine::new(one_fiber_style(), Motion::still(Affine3A::IDENTITY), config);
    e.frame(0.0).clone()
}

#[test]
fn cut_segments_give_the_same_bytes_with_one_and_two_threads() {
    let render = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| frame(2).to_srgb8())
    };
    assert!(
        render(1) == render(2),
        "frames differ between 1 and 2 threads"
    );
}

/// Cutting segments moves no hair: the coverage the raster draws is the same up to the
/// joints the pieces add (measured: 0.035% of the mean coverage moves, the bound is 0.2%),
/// while the colours change (the light is read at the midpoints), and nothing invalid
/// reaches a pixel.
#[test]
fn cut_segments_draw_the_same_hair_with_other_light() {
    let (one, two) = (frame(1), frame(2));
    let n = one.coverage.len() as f64;
    let mean = |c: &[f32]| c.iter().map(|&a| a as f64).sum::<f64>() / n;
    let (c1, c2) = (mean(&one.coverage), mean(&two.coverage));
    assert!(c1 > 0.05, "the hair covers {c1} of the image");
    let moved = one
        .coverage
        .iter()
        .zip(&two.coverage)
        .map(|(a, b)| (a - b).abs() as f64)
        .sum::<f64>()
        / n;
    assert!(
        moved < 0.002 * c1,
        "coverage moved by {moved} (mean {c1} → {c2})"
    );
    assert!(two.color.iter().all(|c| c.is_finite()));
    let changed = one
        .color
        .iter()
        .zip(&two.color)
        .filter(|(a, b)| (**a - **b).abs().max_element() > 1e-4)
        .count();
    assert!(
        changed > 0,
        "the light read at the midpoints changed no pixel"
    );
}
