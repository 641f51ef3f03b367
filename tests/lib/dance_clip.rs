//! Issue #4 on the real clips: the project's dance (embedded) and, when present, the CC0
//! RobotExpressive "Dance" from ../shared/data. The whole engine runs (motion, simulation with
//! density-based self-collision from the map of the previous frame, interpolation, map), frame
//! by frame at 30 fps; `tests/lib/sim_*.rs` cover the same invariants on an analytic motion.

use crate::common;
use crate::support::full_size;

use glam::{Affine3A, Vec3};
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::{Motion, MotionOptions};
use wisp::sim::Colliders;

/// Penetration allowed into the head: the collision margin is 1 mm outside each collider, so
/// anything inside the collider itself is a failure; allow 0.1 mm for f32 rounding at
/// head-frame coordinates.
const PENETRATION_TOLERANCE_M: f32 = 1e-4;

/// Penetration allowed into the body's capsules, which overlap where limbs meet the trunk: a
/// particle pinched in the crease between two of them (an arm against the chest) may have no
/// position at one link from its predecessor outside both, and the collision rounds leave it
/// inside one. Measured (every 1/240 s step, the full-size runs): the dance's mannequin 0.75 mm
/// for smooth at 0.3 s of each loop, none for curly (0.13 mm at 3× speed, once a loop),
/// RobotExpressive 4.4 mm at 0.73 s of each loop (47 capsules, boxy parts pressed together).
const DANCE_BODY_TOLERANCE_M: f32 = 5e-3;
const ROBOT_BODY_TOLERANCE_M: f32 = 1e-2;

struct Run {
    max_length_error: f32,
    /// Into any collider, at every simulation step.
    max_penetration_m: f32,
    /// Into the head ellipsoid, at every frame.
    max_head_penetration_m: f32,
    finite: bool,
    frames: u32,
}

fn dance(style: Hairstyle, motion: Motion, seconds: f64, fps: f64) -> Run {
    let config = EngineConfig::sized(64, 64);
    let mut engine = Engine::new(style, motion, config);
    let mut run = Run {
        max_length_error: 0.0,
        max_penetration_m: 0.0,
        max_head_penetration_m: 0.0,
        finite: true,
        frames: 0,
    };
    let ppg = engine.guides.points_per_guide;
    let frames = (seconds * fps).round() as u32;
    for f in 1..=frames {
        engine.advance(f as f64 / fps);
        engine.build_map(); // the next advance's self-collision reads this map
        run.max_penetration_m = run
            .max_penetration_m
            .max(engine.simulation.stats.max_penetration_m);
        let pos = &engine.simulation.state.positions;
        run.finite &= pos.iter().all(|p| p.is_finite());
        let head = Colliders::head_only(engine.pose().head, Vec3::from(engine.style.head.radii_m));
        for (i, p) in pos.iter().enumerate() {
            if i % ppg >= 2 {
                run.max_head_penetration_m = run.max_head_penetration_m.max(head.penetration_m(*p));
            }
        }
        for g in 0..engine.guides.count() {
            let l = engine.guides.link_length_m[g];
            for i in 0..ppg - 1 {
                let d = (pos[g * ppg + i + 1] - pos[g * ppg + i]).length();
                run.max_length_error = run.max_length_error.max((d / l - 1.0).abs());
            }
        }
        run.frames += 1;
    }
    run
}

/// Seconds of the dance at 1× speed: 10 at full size (`WISP_FULL_TESTS=1`: the 8 s loop and
/// its seam), 5.2 by default: through the clip's fastest head motions (the whips' 10.3 rad/s at
/// 4.21 s, the head-bang's 0.56 m/s at 4.86 s; `animations/README.md`) and the deepest
/// penetration of the full run (smooth, 0.3 s).
fn dance_seconds() -> f64 {
    if full_size() { 10.0 } else { 5.2 }
}

#[test]
fn the_dance_keeps_links_and_stays_outside_head_and_body() {
    for style in [Hairstyle::default_smooth(), Hairstyle::default_curly()] {
        let name = style.name.clone();
        let motion = Motion::default_dance();
        assert!(
            motion.sample(1.0).capsules.len() >= 10,
            "the dance's mannequin carries body capsules"
        );
        let run = dance(style, motion, dance_seconds(), 30.0);
        println!(
            "{name}: {} frames, max link error {:.2e}, max penetration {:.2e} m (head {:.2e} m)",
            run.frames, run.max_length_error, run.max_penetration_m, run.max_head_penetration_m
        );
        assert!(run.finite, "{name}: non-finite particle");
        assert!(
            run.max_length_error < 1e-4,
            "{name}: link error {}",
            run.max_length_error
        );
        assert!(
            run.max_head_penetration_m <= PENETRATION_TOLERANCE_M,
            "{name}: head penetration {}",
            run.max_head_penetration_m
        );
        assert!(
            run.max_penetration_m <= DANCE_BODY_TOLERANCE_M,
            "{name}: penetration {}",
            run.max_penetration_m
        );
    }
}

/// 10 s of frames at full size (`WISP_FULL_TESTS=1`: 3.75 loops), one loop (8/3 s) by default:
/// every move at three times its speed, and the deepest penetration, which recurs each loop.
#[test]
fn dance_at_three_times_speed_with_30_fps_frames_stays_finite_and_rigid() {
    let opts = MotionOptions {
        speed: 3.0,
        ..MotionOptions::default()
    };
    let motion = wisp::motion::dance::try_dance(&opts).expect("embedded dance");
    let seconds = if full_size() { 10.0 } else { 8.0 / 3.0 };
    let run = dance(Hairstyle::default_smooth(), motion, seconds, 30.0);
    println!(
        "3x: max link error {:.2e}, max penetration {:.2e} m (head {:.2e} m)",
        run.max_length_error, run.max_penetration_m, run.max_head_penetration_m
    );
    assert!(run.finite);
    assert!(
        run.max_length_error < 1e-4,
        "link error {}",
        run.max_length_error
    );
    assert!(run.max_head_penetration_m <= PENETRATION_TOLERANCE_M);
    assert!(
        run.max_penetration_m <= DANCE_BODY_TOLERANCE_M,
        "penetration {}",
        run.max_penetration_m
    );
}

/// Two loops of the clip at full size (`WISP_FULL_TESTS=1`), one by default: its deepest
/// penetration recurs each loop.
#[test]
fn robot_expressive_dances_with_hair_on_its_head() {
    let Some(path) = common::robot_expressive_glb() else {
        return;
    };
    let motion = Motion::load(&path, &MotionOptions::default()).expect("RobotExpressive loads");
    assert_eq!(motion.clip_name(), "Dance");
    let loops = if full_size() { 2.0 } else { 1.0 };
    let duration = motion.duration_s() as f64;
    let run = dance(
        Hairstyle::default_smooth(),
        motion.clone(),
        loops * duration,
        30.0,
    );
    println!(
        "robot: max link error {:.2e}, max penetration {:.2e} m (head {:.2e} m)",
        run.max_length_error, run.max_penetration_m, run.max_head_penetration_m
    );
    assert!(run.finite);
    assert!(run.max_length_error < 1e-4);
    assert!(run.max_head_penetration_m <= PENETRATION_TOLERANCE_M);
    assert!(run.max_penetration_m <= ROBOT_BODY_TOLERANCE_M);

    // Rendered: the hair's roots sit on the robot's head and hair covers part of the image.
    let config = EngineConfig::sized(160, 160);
    let mut engine = Engine::new(Hairstyle::default_smooth(), motion, config);
    let fb = engine.frame(1.0).clone();
    let head: Affine3A = engine.pose().head;
    let radii = Vec3::from(engine.style.head.radii_m);
    let ppg = engine.guides.points_per_guide;
    for g in 0..engine.guides.count() {
        let root_local = head
            .inverse()
            .transform_point3(engine.simulation.state.positions[g * ppg]);
        assert!(
            ((root_local / radii).length() - 1.0).abs() < 1e-3,
            "root {g} is off the head"
        );
    }
    let background = engine.scene.background;
    let drawn = fb
        .color
        .iter()
        .filter(|c| (**c - background).abs().max_element() > 1e-3)
        .count();
    assert!(drawn > fb.color.len() / 20, "only {drawn} pixels drawn");
}
