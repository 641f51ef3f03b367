//! Loader errors: each is a typed error naming the file, never a panic.

use std::path::Path;

use serde_json::{Value, json};
use wisp::motion::{JointRef, Motion, MotionError, MotionOptions};

use super::fixture::{Fx, fixed_fit, load, one_channel, temp_dir};
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
    // No joint named like "head", none requested, and no joint above another to take as the
    // topmost.
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
