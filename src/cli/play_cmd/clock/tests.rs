use super::{MAX_FRAME_INTERVAL_S, MotionClock};

const FRAME_S: f64 = 1.0 / 60.0;
const STEP_S: f64 = 1.0 / 240.0;

/// At a steady 60 frames a second and 240 steps a second, every frame is 4 steps: real time.
#[test]
fn a_steady_window_keeps_real_time_in_whole_steps() {
    let mut clock = MotionClock::new(FRAME_S, STEP_S);
    let moved: f64 = (0..600).map(|_| clock.tick(FRAME_S)).sum();
    assert_eq!(clock.steps_per_frame(), 4);
    assert!((moved - 10.0).abs() < 1e-9, "600 frames moved {moved} s");
}

/// One frame 20 times as slow as the rest does not change the next frame's steps: the
/// spike the wall clock would have handed on as 80 steps.
#[test]
fn one_slow_frame_does_not_slow_the_next() {
    let mut clock = MotionClock::new(FRAME_S, STEP_S);
    for _ in 0..100 {
        clock.tick(FRAME_S);
    }
    let after_spike = clock.tick(20.0 * FRAME_S);
    assert!(
        after_spike <= 5.0 * STEP_S,
        "moved {after_spike} s after the spike"
    );
    let next = clock.tick(FRAME_S);
    assert!(next <= 5.0 * STEP_S);
}

/// A window that sustains 20 frames a second moves 12 steps a frame (real time again), and
/// one slower than the longest interval plays in slow motion rather than in jumps.
#[test]
fn a_slow_window_follows_up_to_the_longest_interval() {
    let mut clock = MotionClock::new(FRAME_S, STEP_S);
    for _ in 0..400 {
        clock.tick(0.05);
    }
    assert_eq!(clock.steps_per_frame(), 12);
    for _ in 0..400 {
        clock.tick(1.0);
    }
    let most = (MAX_FRAME_INTERVAL_S / STEP_S).round() as u32;
    assert_eq!(clock.steps_per_frame(), most);
}

/// Non-finite or zero inputs give a working clock that moves at least one step a frame.
#[test]
fn bad_inputs_give_at_least_one_step() {
    let mut clock = MotionClock::new(f64::NAN, 0.0);
    assert!(clock.tick(f64::NAN) > 0.0);
    assert!(clock.tick(f64::INFINITY).is_finite());
    let mut fine = MotionClock::new(FRAME_S, 1.0);
    assert_eq!(
        fine.tick(FRAME_S),
        1.0,
        "a step longer than a frame: one a frame"
    );
}
