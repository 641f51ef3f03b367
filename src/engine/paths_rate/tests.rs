use super::{PathsKey, PathsSchedule, slot_of};
use crate::fiber::FiberParams;
use crate::light::Light;
use crate::light_paths::LightPathParams;
use glam::{Affine3A, Vec3};

/// What a build is made with, owned, for [`PathsKey`]s borrowing it.
struct Made {
    lights: Vec<Light>,
    params: LightPathParams,
    fiber: FiberParams,
}

impl Made {
    fn new() -> Self {
        Self {
            lights: vec![Light::Point {
                position_m: Vec3::new(0.0, 2.0, 0.0),
                intensity: Vec3::ONE,
            }],
            params: LightPathParams::default(),
            fiber: FiberParams::default(),
        }
    }

    fn key(&self) -> PathsKey<'_> {
        PathsKey {
            lights: &self.lights,
            params: &self.params,
            fiber: &self.fiber,
        }
    }
}

/// Builds over `frames` frames at `fps` with slots of `interval_s`: which frames built.
fn builds(first: u32, frames: u32, fps: f64, interval_s: f64) -> Vec<u32> {
    let made = Made::new();
    let key = made.key();
    let mut s = PathsSchedule::default();
    let mut built = Vec::new();
    for i in first..first + frames {
        let t = i as f64 / fps;
        if s.due(t, interval_s, &key) {
            s.built(t, &key, Affine3A::IDENTITY);
            built.push(i);
        }
    }
    built
}

/// At 30 frames a second and slots of 1/10 s, every third frame builds, whatever the rounding
/// of i/30; a run that starts inside a slot builds there and then on the same frames as a run
/// from the start.
#[test]
fn slots_are_aligned_to_the_clock() {
    assert_eq!(builds(0, 12, 30.0, 0.1), vec![0, 3, 6, 9]);
    assert_eq!(builds(4, 8, 30.0, 0.1), vec![4, 6, 9]);
    for i in 0..3000 {
        let t = i as f64 / 30.0;
        assert_eq!(slot_of(t, 0.1), i / 3, "frame {i}");
    }
}

/// Interval 0: every frame builds, and a build for the frame itself needs no transform.
#[test]
fn a_zero_interval_builds_every_frame() {
    assert_eq!(builds(0, 5, 30.0, 0.0), vec![0, 1, 2, 3, 4]);
    let made = Made::new();
    let key = made.key();
    let mut s = PathsSchedule::default();
    s.built(0.5, &key, Affine3A::from_translation(Vec3::X));
    assert!(s.head_back(0.5, Affine3A::IDENTITY).is_none());
}

/// Other lights, other parameters, another fibre, no build yet or a NaN time build at once; within a slot, the same key does not.
#[test]
fn a_changed_key_builds_at_once() {
    let made = Made::new();
    let key = made.key();
    let mut s = PathsSchedule::default();
    s.built(0.0, &key, Affine3A::IDENTITY);
    assert!(!s.due(0.05, 0.1, &key));
    let turned = vec![Light::Point {
        position_m: Vec3::new(0.0, 2.0, 1.0),
        intensity: Vec3::ONE,
    }];
    assert!(s.due(
        0.05,
        0.1,
        &PathsKey {
            lights: &turned,
            ..key
        }
    ));
    let fewer = LightPathParams {
        paths: 1000,
        ..made.params
    };
    assert!(s.due(
        0.05,
        0.1,
        &PathsKey {
            params: &fewer,
            ..key
        }
    ));
    let other = FiberParams {
        radius_m: made.fiber.radius_m * 2.0,
        ..made.fiber.clone()
    };
    assert!(s.due(
        0.05,
        0.1,
        &PathsKey {
            fiber: &other,
            ..key
        }
    ));
    assert!(s.due(f64::NAN, 0.1, &key));
    assert!(PathsSchedule::default().due(0.05, 0.1, &key));
}

/// A frame lit by an earlier build reads it where the head was: the transform takes a point
/// carried by the head back to where it was at the build.
#[test]
fn head_back_undoes_the_heads_motion() {
    let made = Made::new();
    let key = made.key();
    let then = Affine3A::from_rotation_translation(
        glam::Quat::from_rotation_y(0.3),
        Vec3::new(0.1, 1.6, 0.0),
    );
    let now = Affine3A::from_rotation_translation(
        glam::Quat::from_rotation_y(0.5),
        Vec3::new(0.12, 1.58, 0.01),
    );
    let mut s = PathsSchedule::default();
    s.built(0.0, &key, then);
    let back = s.head_back(1.0 / 30.0, now).expect("an earlier build");
    let local = Vec3::new(0.02, 0.08, -0.05);
    let p = back.transform_point3(now.transform_point3(local));
    assert!((p - then.transform_point3(local)).length() < 1e-6, "{p}");
}
