//! Motion tests: sampler maths through hand-built glTF files (written here with serde_json and
//! a `data:` base64 buffer), the node hierarchy, looping, the embedded dance, RobotExpressive
//! (skipped with a message when `../shared/data` is absent) and loader errors.
//!
//! Reference numbers are derived in the comments next to them (Hermite basis values, rotations
//! composed by hand) or come from `../shared/data/README.md` (RobotExpressive: clip "Dance"
//! 3.33 s, joint "Head").
//!
//! Helpers are in `motion/fixture.rs`, loader-error tests in `motion/errors.rs`.

mod errors;
pub mod fixture;

use crate::common;

use std::f32::consts::{FRAC_PI_2, PI};
use std::path::Path;

use fixture::{Fx, angle_between, assert_rigid, fixed_fit, load, one_channel};
use glam::{Affine3A, Quat, Vec3};
use serde_json::json;
use wisp::motion::fit::FitMethod;
use wisp::motion::{Fit, JointRef, Motion, MotionOptions, Pose, SphereSpec};

// ---------------------------------------------------------------- samplers through glTF

#[test]
fn linear_translation_midpoint() {
    let bytes = one_channel(
        "translation",
        "LINEAR",
        &[0.0, 2.0],
        &[0.0, 0.0, 0.0, 2.0, -4.0, 6.0],
    );
    let m = load(&bytes, &fixed_fit()).expect("loads");
    assert_eq!(m.duration_s(), 2.0);
    let p = m.sample(0.5).head.translation;
    // Quarter of the way: (0.5, −1, 1.5).
    assert!(
        (Vec3::from(p) - Vec3::new(0.5, -1.0, 1.5)).length() < 1e-6,
        "{p:?}"
    );
}

#[test]
fn linear_rotation_is_slerp_on_the_shortest_path() {
    // Keys 0 and 90° about Y; the second stored as −q (the same rotation). Midpoint: 45°.
    let q1 = -Quat::from_rotation_y(FRAC_PI_2);
    let bytes = one_channel(
        "rotation",
        "LINEAR",
        &[0.0, 1.0],
        &[0.0, 0.0, 0.0, 1.0, q1.x, q1.y, q1.z, q1.w],
    );
    let m = load(&bytes, &fixed_fit()).expect("loads");
    let q = Quat::from_mat3a(&m.sample(0.5).head.matrix3);
    let expected = Quat::from_rotation_y(PI / 4.0);
    assert!(q.angle_between(expected) < 1e-4, "{q:?}");
}

#[test]
fn step_holds_the_previous_key() {
    let bytes = one_channel(
        "translation",
        "STEP",
        &[0.0, 1.0, 2.0],
        &[1., 0., 0., 2., 0., 0., 3., 0., 0.],
    );
    let m = load(&bytes, &fixed_fit()).expect("loads");
    assert_eq!(m.sample(0.99).head.translation.x, 1.0);
    assert_eq!(m.sample(1.01).head.translation.x, 2.0);
    assert_eq!(m.sample(1.99).head.translation.x, 2.0);
}

#[test]
fn cubicspline_zero_tangents_match_hermite() {
    // (in, value, out) per key; zero tangents: p(u) = p0 + (p1 − p0)(3u² − 2u³).
    // u = 0.25: 3/16 − 2/64 = 0.15625; u = 0.75: 27/16 − 54/64 = 0.84375.
    let z = [0.0f32; 3];
    let v: Vec<f32> = [z, [0.0, 0.0, 0.0], z, z, [4.0, 0.0, 0.0], z].concat();
    let bytes = one_channel("translation", "CUBICSPLINE", &[0.0, 4.0], &v);
    let m = load(&bytes, &fixed_fit()).expect("loads");
    assert!((m.sample(1.0).head.translation.x - 4.0 * 0.15625).abs() < 1e-5);
    assert!((m.sample(3.0).head.translation.x - 4.0 * 0.84375).abs() < 1e-5);
}

#[test]
fn cubicspline_uses_scaled_tangents() {
    // p0 = p1 = 0, out-tangent 1 /s over a 2 s interval: p(u) = 2(u³ − 2u² + u); u = 0.5 -> 0.25.
    let z = [0.0f32; 3];
    let v: Vec<f32> = [z, z, [1.0, 0.0, 0.0], z, z, z].concat();
    let bytes = one_channel("translation", "CUBICSPLINE", &[0.0, 2.0], &v);
    let m = load(&bytes, &fixed_fit()).expect("loads");
    assert!((m.sample(1.0).head.translation.x - 0.25).abs() < 1e-5);
}

#[test]
fn times_outside_the_keys_clamp_and_loop() {
    let bytes = one_channel(
        "translation",
        "LINEAR",
        &[0.0, 2.0],
        &[0.0, 0.0, 0.0, 2.0, 0.0, 0.0],
    );
    let m = load(&bytes, &fixed_fit()).expect("loads");
    for t in [0.3, 1.1, 1.9] {
        let a = m.sample(t).head;
        for k in [-2.0, 1.0, 3.0] {
            let b = m.sample(t + k * m.duration_s()).head;
            assert!(
                (a.translation - b.translation).length() < 1e-5,
                "t {t} k {k}"
            );
        }
    }
    let fast = load(
        &bytes,
        &MotionOptions {
            speed: 2.0,
            ..fixed_fit()
        },
    )
    .expect("loads");
    assert!((fast.sample(0.5).head.translation.x - 1.0).abs() < 1e-6);
    assert!((fast.sample(1.5).head.translation.x - 1.0).abs() < 1e-6);
}

// ---------------------------------------------------------------- hierarchy and fit

/// Root with an animated TRS (incl. scale 2), and a static "Head" child with its own rotation.
fn hierarchy() -> Vec<u8> {
    let mut fx = Fx::default();
    let root = fx.node(json!({"name": "Root", "children": [1], "scale": [2.0, 2.0, 2.0]}));
    let rc = Quat::from_rotation_x(0.3);
    fx.node(json!({"name": "Head", "translation": [0.0, 1.0, 0.5], "rotation": rc.to_array()}));
    let q1 = Quat::from_rotation_y(FRAC_PI_2);
    fx.channel(
        root,
        "translation",
        "LINEAR",
        &[0.0, 1.0],
        &[0., 0., 0., 1., 2., 3.],
    );
    fx.channel(
        root,
        "rotation",
        "LINEAR",
        &[0.0, 1.0],
        &[0., 0., 0., 1., q1.x, q1.y, q1.z, q1.w],
    );
    fx.channel(
        root,
        "scale",
        "LINEAR",
        &[0.0, 1.0],
        &[2., 2., 2., 2., 2., 2.],
    );
    fx.bytes(&["Dance"])
}

#[test]
fn child_world_is_parent_times_local() {
    let m = load(&hierarchy(), &fixed_fit()).expect("loads");
    assert_eq!(m.head_joint(), (1, "Head"));
    let local = Affine3A::from_scale_rotation_translation(
        Vec3::ONE,
        Quat::from_rotation_x(0.3),
        Vec3::new(0.0, 1.0, 0.5),
    );
    let rest_world = Affine3A::from_scale(Vec3::splat(2.0)) * local;
    for t in [0.0f32, 0.25, 0.5, 1.0] {
        let parent = Affine3A::from_scale_rotation_translation(
            Vec3::splat(2.0),
            Quat::from_rotation_y(FRAC_PI_2 * t),
            Vec3::new(1.0, 2.0, 3.0) * t,
        );
        let world = parent * local;
        let h = m.sample(t.min(0.999_9)).head;
        let tol = if t == 1.0 { 1e-3 } else { 1e-5 };
        assert!(
            (h.translation - world.translation).length() < tol,
            "t {t}: {h:?} vs {world:?}"
        );
        // Joint frame = world rotation relative to the rest pose (scale stripped).
        let (_, rw, _) = world.to_scale_rotation_translation();
        let (_, rr, _) = rest_world.to_scale_rotation_translation();
        let expected = rw * rr.inverse();
        assert!(
            Quat::from_mat3a(&h.matrix3).angle_between(expected) < 1e-3,
            "t {t}"
        );
        assert_rigid(&h, "hierarchy head");
    }
}

#[test]
fn fit_scales_the_world_and_keeps_the_head_rigid() {
    let fit = Fit {
        scale: 4.0,
        offset_m: Vec3::new(0.0, 0.2, 0.0),
    };
    let opts = MotionOptions {
        fit: Some(fit),
        ..fixed_fit()
    };
    let m = load(&hierarchy(), &opts).expect("loads");
    let plain = load(&hierarchy(), &fixed_fit()).expect("loads");
    for t in [0.0, 0.4, 0.8] {
        let h = m.sample(t).head;
        let p = plain.sample(t).head;
        // Centre = (joint origin + Q·offset) / scale, Q the joint frame rotation.
        let expected = (p.translation + p.matrix3 * glam::Vec3A::new(0.0, 0.2, 0.0)) / 4.0;
        assert!((h.translation - expected).length() < 1e-5);
        assert!(angle_between(&h, &p) < 1e-6);
        assert_rigid(&h, "fitted head");
    }
}

#[test]
fn z_up_centimetre_export_stands_upright_at_human_scale() {
    // A Z-up exporter's root: −90° about X and ×0.01 (centimetres). The head joint sits at
    // z = 157 cm, its HeadTop_End 18 cm above: world head joint at y = 1.57 m, automatic fit
    // radius 0.09 m (scale 1), centre 0.09 m above the joint along world +Y.
    let mut fx = Fx::default();
    let root_q = Quat::from_rotation_x(-FRAC_PI_2);
    fx.node(
        json!({"name": "Armature", "children": [1], "rotation": root_q.to_array(),
                   "scale": [0.01, 0.01, 0.01]}),
    );
    fx.node(json!({"name": "Head", "children": [2], "translation": [0.0, 0.0, 157.0]}));
    let top = fx.node(json!({"name": "HeadTop_End", "translation": [0.0, 0.0, 18.0]}));
    fx.channel(
        top,
        "translation",
        "LINEAR",
        &[0.0, 1.0],
        &[0., 0., 18., 0., 0., 18.],
    );
    let m = load(&fx.bytes(&["Dance"]), &MotionOptions::default()).expect("loads");
    assert_eq!(m.fit_method(), FitMethod::HeadChild);
    assert!((m.fit().scale - 1.0).abs() < 1e-4, "{:?}", m.fit());
    let h = m.sample(0.5).head;
    assert_rigid(&h, "z-up head");
    assert!(
        (Vec3::from(h.translation) - Vec3::new(0.0, 1.66, 0.0)).length() < 1e-4,
        "{h:?}"
    );
    assert!(Quat::from_mat3a(&h.matrix3).angle_between(Quat::IDENTITY) < 1e-4);
}

#[test]
fn body_spheres_follow_their_joints() {
    let spec = SphereSpec {
        joint: JointRef::Name("root".into()),
        offset_m: Vec3::new(0.0, 0.0, 0.1),
        radius_m: 0.05,
    };
    let opts = MotionOptions {
        fit: Some(Fit {
            scale: 2.0,
            offset_m: Vec3::ZERO,
        }),
        body_spheres: Some(vec![spec]),
        ..Default::default()
    };
    let m = load(&hierarchy(), &opts).expect("loads");
    // At t = 1 the root is at (1, 2, 3) turned 90° about Y: the offset +Z maps to +X.
    let p = m.sample(0.999_99);
    assert_eq!(p.spheres.len(), 1);
    let expected = Vec3::new(1.0, 2.0, 3.0) / 2.0 + Vec3::new(0.1, 0.0, 0.0);
    assert!(
        (p.spheres[0].center - expected).length() < 1e-3,
        "{:?}",
        p.spheres[0]
    );
    assert_eq!(p.spheres[0].radius_m, 0.05);
}

#[test]
fn sample_into_reuses_the_sphere_buffer() {
    let m = Motion::default_dance();
    let mut pose = m.sample(0.0);
    let ptr = pose.spheres.as_ptr();
    for i in 0..50 {
        m.sample_into(i as f32 * 0.17, &mut pose);
    }
    assert_eq!(pose.spheres.as_ptr(), ptr, "sample_into reallocated");
    assert_eq!(pose, m.sample(49.0 * 0.17));
}

#[test]
fn still_is_still() {
    let head =
        Affine3A::from_rotation_translation(Quat::from_rotation_y(0.4), Vec3::new(0.0, 1.6, 0.0));
    let m = Motion::still(head);
    assert_eq!(
        m.sample(0.0),
        Pose {
            head,
            spheres: vec![],
            capsules: vec![],
            carriers: vec![]
        }
    );
    assert_eq!(m.sample(12.3).head, head);
}

// ---------------------------------------------------------------- the embedded dance

#[test]
fn embedded_dance_plays_and_loops_seamlessly() {
    let m = Motion::default_dance();
    assert_eq!(m.clip_name(), "Dance");
    assert!((m.duration_s() - 8.0).abs() < 1e-4);
    assert_eq!(m.head_joint().1, "Head");
    // The mannequin's head (examples/make_dance/mannequin.rs) is an ellipsoid of geometric
    // mean radius 0.09 m centred 0.09 m above Head: scale 1, as HeadTop_End gave before.
    assert!(
        matches!(m.fit_method(), FitMethod::MeshBounds { .. }),
        "{:?}",
        m.fit_method()
    );
    assert!((m.fit().scale - 1.0).abs() < 1e-4, "{:?}", m.fit());
    assert!((m.fit().offset_m - Vec3::new(0.0, 0.09, 0.0)).length() < 1e-4);
    // The mesh's capsules replace the default body spheres.
    assert!(m.sample(0.0).spheres.is_empty());
    assert!(m.sample(0.0).capsules.len() >= 10);

    let p0 = m.sample(0.0).head;
    let (mut max_move_m, mut max_turn_rad) = (0.0f32, 0.0f32);
    for i in 0..=800 {
        let h = m.sample(i as f32 * 0.01).head;
        assert_rigid(&h, "dance head");
        max_move_m = max_move_m.max((h.translation - p0.translation).length());
        max_turn_rad = max_turn_rad.max(angle_between(&h, &p0));
    }
    assert!(max_move_m > 0.05, "head moved only {max_move_m} m");
    assert!(max_turn_rad > 0.6, "head turned only {max_turn_rad} rad");
    // Seamless: the pose just before the end equals the start (zero velocity at both ends).
    let end = m.sample(m.duration_s() - 1e-3);
    assert!((end.head.translation - p0.translation).length() < 1e-4);
    assert!(angle_between(&end.head, &p0) < 1e-3);
    for (a, b) in end.capsules.iter().zip(&m.sample(0.0).capsules) {
        assert!((a.a - b.a).length() < 1e-4 && (a.b - b.b).length() < 1e-4);
    }
}

#[test]
fn embedded_dance_loads_from_a_file_too() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("animations/dance.glb");
    let m = Motion::load(&path, &MotionOptions::default()).expect("animations/dance.glb loads");
    assert_eq!(m.sample(2.7), Motion::default_dance().sample(2.7));
}

// ---------------------------------------------------------------- RobotExpressive

#[test]
fn robot_expressive_dance() {
    let Some(path) = common::robot_expressive_glb() else {
        return;
    };
    let m = Motion::load(&path, &MotionOptions::default()).expect("RobotExpressive loads");
    assert_eq!(m.clip_name(), "Dance");
    // Node 12 is the "Head" joint; node 13, also named "Head", is the (non-joint) head mesh.
    assert_eq!(m.head_joint(), (12, "Head"));
    // ../shared/data/README.md: Dance lasts 3.33 s.
    assert!((m.duration_s() - 3.33).abs() < 0.01, "{}", m.duration_s());
    assert!(
        matches!(m.fit_method(), FitMethod::MeshBounds { .. }),
        "{:?}",
        m.fit_method()
    );
    let p0 = m.sample(0.0).head;
    let mut max_turn = 0.0f32;
    for i in 0..=100 {
        let h = m.sample(i as f32 * 0.0333).head;
        assert_rigid(&h, "robot head");
        max_turn = max_turn.max(angle_between(&h, &p0));
    }
    assert!(max_turn > 0.2, "robot head turned only {max_turn} rad");

    // Independent size check: the Head -> Head_end bone (top of the skull, 1.1 model m in this
    // cartoon robot) seen in the pose world must be head-sized (a human skull is ~0.2 m tall).
    let unit = MotionOptions {
        fit: Some(Fit::IDENTITY),
        body_spheres: Some(vec![]),
        ..Default::default()
    };
    let head = Motion::load(&path, &unit)
        .expect("loads")
        .sample(0.0)
        .head
        .translation;
    let end_opts = MotionOptions {
        head_joint: Some(JointRef::Name("Head_end".into())),
        ..unit
    };
    let end = Motion::load(&path, &end_opts)
        .expect("loads")
        .sample(0.0)
        .head
        .translation;
    let bone_pose_m = (end - head).length() / m.fit().scale;
    assert!(
        (0.05..0.15).contains(&bone_pose_m),
        "head bone {bone_pose_m} m after the fit"
    );
}

/// Without --clip: "Dance", else a clip named like dance, else like idle, else the longest
/// (a rig's alphabetically first clip, "agree", is rarely the one to watch hair on).
#[test]
fn the_default_clip_is_a_dance_an_idle_or_the_longest() {
    let mut fx = Fx::default();
    let head = fx.node(json!({"name": "Head"}));
    let q = [0.0, 0.0, 0.0, 1.0];
    let turn = [0.0, 0.38268343, 0.0, 0.9238795];
    fx.channel(head, "rotation", "LINEAR", &[0.0, 1.0], &[q, turn].concat());
    fx.channel(head, "rotation", "LINEAR", &[0.0, 3.0], &[q, turn].concat());
    let chosen = |clips: &[(&str, usize)]| {
        load(&fx.bytes_one_channel_each(clips), &fixed_fit())
            .unwrap()
            .clip_name()
            .to_string()
    };
    assert_eq!(chosen(&[("agree", 0), ("idle", 0), ("walk", 0)]), "idle");
    assert_eq!(
        chosen(&[("Agree", 0), ("Idle", 0), ("Salsa_Dance", 0)]),
        "Salsa_Dance"
    );
    assert_eq!(chosen(&[("agree", 0), ("dance", 1), ("Dance", 0)]), "Dance");
    assert_eq!(chosen(&[("agree", 0), ("walk", 1), ("wave", 0)]), "walk");
    assert_eq!(
        chosen(&[("agree", 0), ("wave", 0)]),
        "agree",
        "the first of equals"
    );
}

#[test]
fn robot_expressive_every_clip_loads() {
    let Some(path) = common::robot_expressive_glb() else {
        return;
    };
    for clip in [
        "Idle", "Walking", "Running", "Wave", "Jump", "Yes", "No", "Death",
    ] {
        let opts = MotionOptions {
            clip: Some(clip.into()),
            ..Default::default()
        };
        let m = Motion::load(&path, &opts).unwrap_or_else(|e| panic!("{clip}: {e}"));
        assert_eq!(m.clip_name(), clip);
        assert!(m.duration_s() > 0.0);
        assert_rigid(&m.sample(0.37).head, clip);
    }
}

#[test]
fn robot_expressive_truncated_is_an_error() {
    let Some(path) = common::robot_expressive_glb() else {
        return;
    };
    let bytes = std::fs::read(&path).expect("readable");
    for len in [
        0,
        3,
        11,
        12,
        19,
        20,
        100,
        1000,
        82_723,
        82_724,
        82_730,
        200_000,
        bytes.len() - 1,
    ] {
        let r = Motion::from_glb_bytes(&bytes[..len], "cut.glb", &MotionOptions::default());
        assert!(r.is_err(), "{len} bytes loaded");
    }
}
