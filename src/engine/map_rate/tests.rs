use super::MapSchedule;
use crate::light::Light;
use glam::Vec3;

fn key() -> Vec<Light> {
    vec![Light::Point {
        position_m: Vec3::new(0.0, 2.0, 0.0),
        intensity: Vec3::ONE,
    }]
}

/// At 60 frames a second and a 1/30 s interval, every other frame builds, whatever the
/// rounding of i/60.
#[test]
fn builds_every_other_frame_at_half_the_frame_rate() {
    let (mut s, lights) = (MapSchedule::default(), key());
    let mut built = Vec::new();
    for i in 0..12 {
        let t = i as f64 / 60.0;
        let due = s.due(t, &lights, 1.0 / 30.0);
        if due {
            s.built(t, &lights);
        }
        built.push(due);
    }
    let expected: Vec<bool> = (0..12).map(|i| i % 2 == 0).collect();
    assert_eq!(built, expected);
}

/// Interval 0 (final, reference): every frame builds.
#[test]
fn a_zero_interval_builds_every_frame() {
    let (mut s, lights) = (MapSchedule::default(), key());
    s.built(0.0, &lights);
    assert!(s.due(0.0, &lights, 0.0));
    assert!(s.due(1e-9, &lights, 0.0));
}

/// Going back in time, turned lights, a forgotten build or a NaN time build at once.
#[test]
fn jumps_and_changed_lights_build_at_once() {
    let (mut s, lights) = (MapSchedule::default(), key());
    assert!(s.due(0.5, &lights, 1.0), "the first frame builds");
    s.built(0.5, &lights);
    assert!(!s.due(0.6, &lights, 1.0));
    assert!(s.due(0.4, &lights, 1.0), "back in time");
    assert!(s.due(f64::NAN, &lights, 1.0), "NaN time");
    let mut turned = lights.clone();
    if let Light::Point { position_m, .. } = &mut turned[0] {
        position_m.x += 0.1;
    }
    assert!(s.due(0.6, &turned, 1.0), "turned light");
    assert!(s.due(0.6, &[], 1.0), "light removed");
    s.forget();
    assert!(s.due(0.6, &lights, 1.0), "forgotten");
}
