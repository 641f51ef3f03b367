//! The light paths at a lower rate than the frames (`ShadingConfig::paths_interval_s`): built
//! from the first frame of each slot of motion and read by the slot's later frames where the
//! hair was then. The slot's first frame is the bytes of a build for every frame, the frames
//! after it are about as far from converged light as a build for every frame, the frames are
//! the same on one and two threads, and a still head's frames do not change.

use glam::Affine3A;
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;
use wisp::quality::Quality;

use crate::common;

/// `final` at `size`² with few paths (the test's time), built every `interval_s` (0: every
/// frame).
fn config(size: u32, interval_s: f64) -> EngineConfig {
    let mut config = EngineConfig::sized(size, size);
    config.apply_quality(Quality::Final);
    config.shading.light_paths.paths = 20_000;
    config.shading.paths_interval_s = interval_s;
    config
}

/// Linear RGB of frames at 30 a second from 0.5 s of the dance.
fn dance(config: EngineConfig, frames: u32) -> Vec<Vec<f32>> {
    let mut engine = Engine::new(Hairstyle::default_smooth(), Motion::default_dance(), config);
    (0..frames)
        .map(|i| {
            let fb = engine.frame(0.5 + f64::from(i) / 30.0);
            fb.color.iter().flat_map(|p| p.to_array()).collect()
        })
        .collect()
}

/// Mean |a − b| over the frame's values (the same pixels for every pair compared).
fn mean_difference(a: &[f32], b: &[f32]) -> f64 {
    let sum: f64 = a.iter().zip(b).map(|(x, y)| f64::from((x - y).abs())).sum();
    sum / a.len().max(1) as f64
}

/// At 10 builds a second and 30 frames, frames 0 and 3 start their slots (0.5 s and 0.6 s)
/// and are a build of their own; frames 1, 2, 4 and 5 read a build one or two frames old. Paths
/// built for every frame are noisy themselves, so both are measured against converged light
/// (10 times the paths, every frame): over the frames between builds, the late light is
/// within a quarter of a build for every frame's own error (the bench measures the dance's
/// fastest stretch the same way, BENCHMARKS.md). On one and two threads the frames are the same.
#[test]
fn a_slots_later_frames_read_its_first_frames_paths() {
    let size = 96;
    let at_rate = common::on_threads(2, || dance(config(size, 0.1), 6));
    let one_thread = common::on_threads(1, || dance(config(size, 0.1), 6));
    assert!(
        at_rate == one_thread,
        "frames differ between 1 and 2 threads"
    );
    let every = common::on_threads(2, || dance(config(size, 0.0), 6));
    let mut converged = config(size, 0.0);
    converged.shading.light_paths.paths *= 10;
    let converged = common::on_threads(2, || dance(converged, 6));
    let (mut late, mut own) = (0.0, 0.0);
    for i in 0..6 {
        if i % 3 == 0 {
            assert!(at_rate[i] == every[i], "frame {i} starts a slot");
            continue;
        }
        assert!(
            at_rate[i] != every[i],
            "frame {i}: the late paths change nothing"
        );
        late += mean_difference(&at_rate[i], &converged[i]);
        own += mean_difference(&every[i], &converged[i]);
    }
    eprintln!("late light {late:.3e}, every frame's own {own:.3e}");
    assert!(own > 0.0, "10 times the paths change nothing");
    assert!(
        late < 1.25 * own,
        "late light {late} against every frame's {own}"
    );
}

/// A still head at rest renders the same frames with paths built every few frames: each
/// slot's build traces the same hair, and the frames between read it unmoved. Frames from
/// the settle at 30 a second, as `sim_still_frames` (the hair is at rest by 1 s); frames 30 to
/// 38 span three slots.
#[test]
fn a_still_head_does_not_flicker_between_builds() {
    let mut engine = Engine::new(
        Hairstyle::default_smooth(),
        Motion::still(Affine3A::IDENTITY),
        config(96, 0.1),
    );
    for i in 0..30 {
        engine.frame(f64::from(i) / 30.0);
    }
    let first = engine.frame(1.0).to_srgb8();
    for i in 31..39 {
        let frame = engine.frame(f64::from(i) / 30.0).to_srgb8();
        assert!(frame == first, "frame {i} differs from frame 30");
    }
}
