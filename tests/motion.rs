//! Motion tests: sampler maths through hand-built glTF files (written here with serde_json and
//! a `data:` base64 buffer), the node hierarchy, looping, the embedded dance, RobotExpressive
//! (skipped with a message when `../shared/data` is absent) and loader errors.
//!
//! Reference numbers are derived in the comments next to them (Hermite basis values, rotations
//! composed by hand) or come from `../shared/data/README.md` (RobotExpressive: clip "Dance"
//! 3.33 s, joint "Head").

use std::f32::consts::{FRAC_PI_2, PI};
use std::path::{Path, PathBuf};

use glam::{Affine3A, Quat, Vec3};
use serde_json::{Value, json};
use wisp::motion::fit::FitMethod;
use wisp::motion::{Fit, JointRef, Motion, MotionError, MotionOptions, Pose, SphereSpec};

// ---------------------------------------------------------------- fixtures

/// A glTF under construction: nodes, one clip, f32 data in one buffer.
#[derive(Default)]
struct Fx {
    nodes: Vec<Value>,
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
    samplers: Vec<Value>,
    channels: Vec<Value>,
}

fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

impl Fx {
    /// Adds a node; returns its index.
    fn node(&mut self, n: Value) -> usize {
        self.nodes.push(n);
        self.nodes.len() - 1
    }

    fn accessor(&mut self, data: &[f32], kind: &str) -> usize {
        let comps = match kind {
            "SCALAR" => 1,
            "VEC3" => 3,
            _ => 4,
        };
        let offset = self.bin.len();
        for v in data {
            self.bin.extend_from_slice(&v.to_le_bytes());
        }
        self.views
            .push(json!({"buffer": 0, "byteOffset": offset, "byteLength": data.len() * 4}));
        self.accessors.push(json!({
            "bufferView": self.views.len() - 1, "componentType": 5126,
            "count": data.len() / comps, "type": kind,
        }));
        self.accessors.len() - 1
    }

    fn channel(&mut self, node: usize, path: &str, interp: &str, times: &[f32], values: &[f32]) {
        let kind = if path == "rotation" { "VEC4" } else { "VEC3" };
        let input = self.accessor(times, "SCALAR");
        let output = self.accessor(values, kind);
        self.samplers
            .push(json!({"input": input, "output": output, "interpolation": interp}));
        self.channels.push(
            json!({"sampler": self.samplers.len() - 1, "target": {"node": node, "path": path}}),
        );
    }

    /// The glTF JSON; `clips` names the copies of the clip (none = no animations).
    fn json(&self, clips: &[&str]) -> Value {
        let anims: Vec<Value> = clips
            .iter()
            .map(|n| json!({"name": n, "samplers": self.samplers, "channels": self.channels}))
            .collect();
        let mut doc = json!({
            "asset": {"version": "2.0"},
            "scenes": [{"nodes": [0]}],
            "nodes": self.nodes,
            "accessors": self.accessors,
            "bufferViews": self.views,
            "buffers": [{
                "byteLength": self.bin.len(),
                "uri": format!("data:application/octet-stream;base64,{}", base64(&self.bin)),
            }],
        });
        if !anims.is_empty() {
            doc["animations"] = json!(anims);
        }
        doc
    }

    fn bytes(&self, clips: &[&str]) -> Vec<u8> {
        self.json(clips).to_string().into_bytes()
    }
}

fn load(bytes: &[u8], opts: &MotionOptions) -> Result<Motion, MotionError> {
    Motion::from_glb_bytes(bytes, "fixture.gltf", opts)
}

fn fixed_fit() -> MotionOptions {
    MotionOptions {
        fit: Some(Fit::IDENTITY),
        body_spheres: Some(vec![]),
        ..Default::default()
    }
}

/// A single "Head" node with one animated property.
fn one_channel(path: &str, interp: &str, times: &[f32], values: &[f32]) -> Vec<u8> {
    let mut fx = Fx::default();
    let head = fx.node(json!({"name": "Head"}));
    fx.channel(head, path, interp, times, values);
    fx.bytes(&["Dance"])
}

fn angle_between(a: &Affine3A, b: &Affine3A) -> f32 {
    let qa = Quat::from_mat3a(&a.matrix3);
    let qb = Quat::from_mat3a(&b.matrix3);
    qa.angle_between(qb)
}

fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("wisp-motion-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn assert_rigid(h: &Affine3A, what: &str) {
    let m = h.matrix3;
    let mtm = m.transpose() * m;
    let err = (mtm - glam::Mat3A::IDENTITY)
        .to_cols_array()
        .iter()
        .map(|v| v.abs())
        .fold(0.0, f32::max);
    assert!(err < 1e-4, "{what}: MᵀM differs from I by {err}");
    assert!(
        (m.determinant() - 1.0).abs() < 1e-4,
        "{what}: det {}",
        m.determinant()
    );
}

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
            spheres: vec![]
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
    // HeadTop_End is 0.18 m above Head (examples/make_dance.rs): radius 0.09 m, scale 1.
    assert_eq!(m.fit_method(), FitMethod::HeadChild);
    assert!((m.fit().scale - 1.0).abs() < 1e-4, "{:?}", m.fit());
    assert_eq!(m.sample(0.0).spheres.len(), 4, "neck, chest, two shoulders");

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
    for (a, b) in end.spheres.iter().zip(&m.sample(0.0).spheres) {
        assert!((a.center - b.center).length() < 1e-4);
    }
}

#[test]
fn embedded_dance_loads_from_a_file_too() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("animations/dance.glb");
    let m = Motion::load(&path, &MotionOptions::default()).expect("animations/dance.glb loads");
    assert_eq!(m.sample(2.7), Motion::default_dance().sample(2.7));
}

// ---------------------------------------------------------------- RobotExpressive

fn robot() -> Option<PathBuf> {
    let p =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/animations/RobotExpressive.glb");
    if p.exists() {
        Some(p)
    } else {
        println!(
            "skipped: {} is absent (see ../shared/data/README.md)",
            p.display()
        );
        None
    }
}

#[test]
fn robot_expressive_dance() {
    let Some(path) = robot() else { return };
    let m = Motion::load(&path, &MotionOptions::default()).expect("RobotExpressive loads");
    assert_eq!(m.clip_name(), "Dance");
    assert_eq!(m.head_joint().1, "Head");
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

#[test]
fn robot_expressive_every_clip_loads() {
    let Some(path) = robot() else { return };
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
    let Some(path) = robot() else { return };
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

// ---------------------------------------------------------------- loader errors

#[test]
fn missing_file_is_an_io_error() {
    let p = Path::new("/nonexistent/wisp/dance.glb");
    let e = Motion::load(p, &MotionOptions::default()).expect_err("missing");
    assert!(matches!(e, MotionError::Io { .. }));
    assert!(e.to_string().contains("/nonexistent/wisp/dance.glb"), "{e}");
}

#[test]
fn random_bytes_are_not_gltf() {
    // A fixed xorshift stream (deterministic "random" bytes).
    let mut x = 0x9E37_79B9u32;
    let bytes: Vec<u8> = (0..4096)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x as u8
        })
        .collect();
    let e = load(&bytes, &MotionOptions::default()).expect_err("random");
    assert!(matches!(e, MotionError::NotGltf { .. }), "{e}");
    assert!(e.to_string().contains("fixture.gltf"));
    assert!(matches!(
        load(b"", &MotionOptions::default()),
        Err(MotionError::NotGltf { .. })
    ));
    let e = load(b"{ not json", &MotionOptions::default()).expect_err("bad json");
    assert!(matches!(e, MotionError::Invalid { .. }), "{e}");
}

#[test]
fn gltf_without_animations() {
    let mut fx = Fx::default();
    fx.node(json!({"name": "Head"}));
    let e = load(&fx.bytes(&[]), &MotionOptions::default()).expect_err("no clip");
    assert!(matches!(e, MotionError::NoAnimations { .. }), "{e}");
    assert!(e.to_string().contains("no animations"));
}

#[test]
fn unknown_clip_lists_the_clips() {
    let mut fx = Fx::default();
    let h = fx.node(json!({"name": "Head"}));
    fx.channel(h, "translation", "LINEAR", &[0.0, 1.0], &[0.0; 6]);
    let bytes = fx.bytes(&["Idle", "Salsa"]);
    let opts = MotionOptions {
        clip: Some("Tango".into()),
        ..Default::default()
    };
    let e = load(&bytes, &opts).expect_err("unknown clip");
    let msg = e.to_string();
    assert!(
        msg.contains("Tango") && msg.contains("Idle") && msg.contains("Salsa"),
        "{msg}"
    );
    // No "Dance": the first clip is the default; names also match case-insensitively.
    assert_eq!(
        load(&bytes, &MotionOptions::default())
            .expect("ok")
            .clip_name(),
        "Idle"
    );
    let opts = MotionOptions {
        clip: Some("salsa".into()),
        ..Default::default()
    };
    assert_eq!(load(&bytes, &opts).expect("ok").clip_name(), "Salsa");
}

#[test]
fn unknown_head_joint_lists_the_joints() {
    let mut fx = Fx::default();
    let root = fx.node(json!({"name": "Pelvis", "children": [1]}));
    fx.node(json!({"name": "Skull"}));
    fx.channel(root, "translation", "LINEAR", &[0.0, 1.0], &[0.0; 6]);
    let bytes = fx.bytes(&["Dance"]);
    // No joint named like "head" and none requested.
    let e = load(&bytes, &MotionOptions::default()).expect_err("no head");
    let msg = e.to_string();
    assert!(msg.contains("0 Pelvis") && msg.contains("1 Skull"), "{msg}");
    let opts = MotionOptions {
        head_joint: Some(JointRef::Name("Kopf".into())),
        ..Default::default()
    };
    let msg = load(&bytes, &opts).expect_err("unknown").to_string();
    assert!(msg.contains("Kopf") && msg.contains("1 Skull"), "{msg}");
    let opts = MotionOptions {
        head_joint: Some(JointRef::Index(7)),
        ..Default::default()
    };
    assert!(matches!(
        load(&bytes, &opts),
        Err(MotionError::UnknownJoint { .. })
    ));
    let opts = MotionOptions {
        head_joint: Some(JointRef::Index(1)),
        ..Default::default()
    };
    assert_eq!(
        load(&bytes, &opts).expect("by index").head_joint(),
        (1, "Skull")
    );
}

#[test]
fn truncated_glb_never_panics() {
    let bytes = wisp::motion::dance::DANCE_GLB;
    let mut lens: Vec<usize> = (0..bytes.len()).step_by(53).collect();
    lens.extend([
        1,
        4,
        8,
        11,
        12,
        16,
        19,
        20,
        21,
        bytes.len() - 4,
        bytes.len() - 1,
    ]);
    for len in lens {
        let r = Motion::from_glb_bytes(&bytes[..len], "cut.glb", &MotionOptions::default());
        let e = r.err().unwrap_or_else(|| panic!("{len} bytes loaded"));
        assert!(e.to_string().contains("cut.glb"), "{e}");
    }
    // A header that claims fewer bytes than its own header (would underflow a naive reader).
    let mut bad = bytes.to_vec();
    bad[8..12].copy_from_slice(&4u32.to_le_bytes());
    assert!(Motion::from_glb_bytes(&bad, "bad.glb", &MotionOptions::default()).is_err());
}

#[test]
fn gltf_with_a_relative_bin_file() {
    let mut fx = Fx::default();
    let h = fx.node(json!({"name": "Head"}));
    fx.channel(
        h,
        "translation",
        "LINEAR",
        &[0.0, 1.0],
        &[0., 0., 0., 0., 1., 0.],
    );
    let mut doc = fx.json(&["Dance"]);
    doc["buffers"][0]["uri"] = json!("dance%20data.bin");
    let dir = temp_dir("relative");
    std::fs::write(dir.join("dance data.bin"), &fx.bin).expect("write bin");
    let path = dir.join("motion.gltf");
    std::fs::write(&path, doc.to_string()).expect("write gltf");
    let m = Motion::load(&path, &fixed_fit()).expect("relative buffer loads");
    assert!((m.sample(0.5).head.translation.y - 0.5).abs() < 1e-6);

    // Without a folder (bytes only) a relative URI is a clear error; other schemes are refused.
    let e = load(doc.to_string().as_bytes(), &fixed_fit()).expect_err("no folder");
    assert!(matches!(e, MotionError::Buffer { index: 0, .. }), "{e}");
    doc["buffers"][0]["uri"] = json!("https://example.com/x.bin");
    let e = load(doc.to_string().as_bytes(), &fixed_fit()).expect_err("https");
    assert!(e.to_string().contains("not supported"), "{e}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn malformed_clip_data_is_an_error() {
    // Decreasing key times.
    let bytes = one_channel("translation", "LINEAR", &[1.0, 0.0], &[0.0; 6]);
    assert!(matches!(
        load(&bytes, &fixed_fit()),
        Err(MotionError::BadClip { .. })
    ));
    // An accessor that runs past its buffer.
    let mut doc: Value = serde_json::from_slice(&one_channel(
        "translation",
        "LINEAR",
        &[0.0, 1.0],
        &[0.0; 6],
    ))
    .expect("json");
    doc["accessors"][1]["count"] = json!(1000);
    let e = load(doc.to_string().as_bytes(), &fixed_fit()).expect_err("overrun");
    assert!(e.to_string().contains("fixture.gltf"), "{e}");
    // Bad options.
    let opts = MotionOptions {
        speed: f32::NAN,
        ..fixed_fit()
    };
    assert!(matches!(
        load(&bytes, &opts),
        Err(MotionError::BadOption { .. })
    ));
}
