//! Issue 8, case by case: every hostile input the issue lists (and those found since), each a
//! regression test named after what broke. Library level; the command line's cases are in
//! `tests/cli/hostile.rs`, the generated cases in `hostile_loaders.rs`.

use crate::bounded::run_bounded;
use crate::motion::fixture::{Fx, fixed_fit, load};
use crate::support::hostile::mutate::make_glb;
use crate::support::scratch_dir;
use serde_json::{Value, json};
use std::time::Duration;
use wisp::budget::{Budget, BudgetError, RunPlan};
use wisp::engine::estimate;
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::{Hairstyle, SMOOTH_JSON};
use wisp::input::{ReadError, read_capped};
use wisp::motion::{Motion, MotionOptions};

/// A hang bound for cases that used to loop or take quadratic time (not a speed assertion).
const HANG: Duration = Duration::from_secs(60);

fn smooth_with(edit: impl FnOnce(&mut Value)) -> String {
    let mut v: Value = serde_json::from_str(SMOOTH_JSON).unwrap();
    edit(&mut v);
    v.to_string()
}

fn hairstyle_error(text: &str) -> String {
    match Hairstyle::from_json(text, "hair.json") {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => e.to_string(),
    }
}

fn motion_error(bytes: &[u8], opts: &MotionOptions) -> String {
    match load(bytes, opts) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    }
}

/// One node "Head" whose translation is animated, as a glTF JSON value.
fn head_clip() -> Value {
    let mut fx = Fx::default();
    let h = fx.node(json!({"name": "Head"}));
    fx.channel(h, "translation", "LINEAR", &[0.0, 1.0], &[0.0; 6]);
    fx.json(&["Dance"])
}

// ---------------------------------------------------------------------------------------------
// Panics in glTF loading.

#[test]
fn channel_target_node_out_of_range_is_an_error_not_a_panic() {
    let mut doc = head_clip();
    doc["animations"][0]["channels"][0]["target"]["node"] = json!(7);
    let msg = motion_error(doc.to_string().as_bytes(), &fixed_fit());
    assert!(
        msg.contains("target.node: 7 is out of range (the file has 1 nodes)"),
        "{msg}"
    );
}

#[test]
fn channel_with_an_unknown_target_path_is_an_error_not_a_panic() {
    let mut doc = head_clip();
    doc["animations"][0]["channels"][0]["target"]["path"] = json!("wobble");
    let msg = motion_error(doc.to_string().as_bytes(), &fixed_fit());
    assert!(msg.contains("target.path: not one of"), "{msg}");
}

/// Found by `hostile_loaders`: the gltf crate's own validation indexed `accessors` with a
/// primitive's POSITION attribute before checking it.
#[test]
fn position_accessor_out_of_range_is_an_error_not_a_panic() {
    let mut doc = head_clip();
    doc["meshes"] = json!([{"primitives": [{"attributes": {"POSITION": 99}}]}]);
    let msg = motion_error(doc.to_string().as_bytes(), &fixed_fit());
    assert!(
        msg.contains("POSITION: accessor 99 is out of range"),
        "{msg}"
    );
}

// ---------------------------------------------------------------------------------------------
// Garbage accepted.

#[test]
fn text_after_the_hairstyle_object_is_refused() {
    let msg = hairstyle_error(&format!("{SMOOTH_JSON}\n}} trailing"));
    assert!(msg.contains("after the JSON value"), "{msg}");
}

#[test]
fn an_array_where_an_object_is_expected_is_refused() {
    // Was read as links = 1, length 2 m.
    let msg = hairstyle_error(&smooth_with(|v| v["guides"] = json!([1, 2])));
    assert!(msg.contains("`guides`: must be an object"), "{msg}");
}

#[test]
fn a_head_of_1e_30_metres_is_refused_naming_the_rule() {
    let msg = hairstyle_error(&smooth_with(|v| {
        v["head"]["radii_m"] = json!([1e-30, 1e-30, 1e-30])
    }));
    assert!(msg.contains("`head.radii_m[0]`"), "{msg}");
    assert!(msg.contains("at least 1 cm"), "{msg}");
}

#[test]
fn keyframe_values_of_1e30_are_refused_naming_the_rule() {
    let mut fx = Fx::default();
    let h = fx.node(json!({"name": "Head"}));
    fx.channel(
        h,
        "translation",
        "LINEAR",
        &[0.0, 1.0],
        &[0.0, 0.0, 0.0, 1e30, 0.0, 0.0],
    );
    let msg = motion_error(&fx.bytes(&["Dance"]), &fixed_fit());
    assert!(msg.contains("within 10000 m of the origin"), "{msg}");
}

#[test]
fn rotation_keys_far_from_unit_length_are_refused() {
    let mut fx = Fx::default();
    let h = fx.node(json!({"name": "Head"}));
    fx.channel(
        h,
        "rotation",
        "LINEAR",
        &[0.0, 1.0],
        &[0.0, 0.0, 0.0, 1.0, 1e30, 0.0, 0.0, 1e30],
    );
    let msg = motion_error(&fx.bytes(&["Dance"]), &fixed_fit());
    assert!(msg.contains("rotation key 1 has length"), "{msg}");
}

#[test]
fn a_node_transform_beyond_f32_is_refused() {
    let mut doc = head_clip();
    doc["nodes"][0]["translation"] = json!([1e39, 0, 0]);
    let msg = motion_error(doc.to_string().as_bytes(), &fixed_fit());
    assert!(msg.contains("rest transform is not finite"), "{msg}");
}

// ---------------------------------------------------------------------------------------------
// Unclear messages.

#[test]
fn a_number_beyond_f32_is_reported_as_written() {
    let msg = hairstyle_error(&smooth_with(|v| v["guides"]["length_m"] = json!(1e308)));
    assert!(msg.contains("`guides.length_m`"), "{msg}");
    assert!(
        msg.contains("1e308 is outside the range of a 32-bit float"),
        "{msg}"
    );
    assert!(!msg.contains("inf"), "{msg}");
}

#[test]
fn a_utf8_byte_order_mark_is_skipped_and_utf16_is_named() {
    let mut bytes = b"\xEF\xBB\xBF".to_vec();
    bytes.extend_from_slice(SMOOTH_JSON.as_bytes());
    assert_eq!(
        Hairstyle::from_bytes(&bytes, "bom.json").unwrap().name,
        "smooth"
    );
    let e = Hairstyle::from_bytes(b"\xFF\xFE{\0}\0", "utf16.json").unwrap_err();
    assert!(e.to_string().contains("UTF-16"), "{e}");
}

#[test]
fn glb_with_a_bom_before_json_is_read() {
    let mut bytes = b"\xEF\xBB\xBF".to_vec();
    bytes.extend_from_slice(head_clip().to_string().as_bytes());
    load(&bytes, &fixed_fit()).expect("a .gltf with a BOM loads");
}

#[test]
fn gltf_validation_messages_are_short_and_say_invalid_gltf_once() {
    // 5,000 accessors pointing at a missing buffer view: 5,000 validation problems.
    let mut doc = head_clip();
    let bad: Vec<Value> = (0..5000)
        .map(|_| json!({"bufferView": 999, "componentType": 5126, "count": 1, "type": "SCALAR"}))
        .collect();
    doc["accessors"].as_array_mut().unwrap().extend(bad);
    let msg = motion_error(doc.to_string().as_bytes(), &fixed_fit());
    assert!(msg.chars().count() < 1500, "{} chars", msg.chars().count());
    assert_eq!(msg.matches("invalid glTF").count(), 1, "{msg}");
    assert!(msg.contains("5000 problems"), "{msg}");
    assert!(msg.contains("(and 4992 more)"), "{msg}");
}

#[test]
fn joint_lists_in_messages_are_short() {
    let mut fx = Fx::default();
    let root = fx.node(json!({"name": "Root"}));
    for i in 0..3000 {
        fx.node(json!({"name": format!("Bone{i}")}));
    }
    fx.channel(root, "translation", "LINEAR", &[0.0, 1.0], &[0.0; 6]);
    let msg = motion_error(&fx.bytes(&["Dance"]), &MotionOptions::default());
    assert!(msg.chars().count() < 1500, "{} chars", msg.chars().count());
    assert!(msg.contains("more)"), "{msg}");
    // The library does not name its own option types in user-facing messages.
    assert!(!msg.contains("MotionOptions"), "{msg}");
}

#[test]
fn io_errors_state_their_cause_once() {
    let e = Hairstyle::load(std::path::Path::new("/no/such/hair.json")).unwrap_err();
    let chain = format!("{:#}", anyhow::Error::new(e));
    assert_eq!(chain.matches("No such file").count(), 1, "{chain}");
    let e = Motion::load(
        std::path::Path::new("/no/such/dance.glb"),
        &MotionOptions::default(),
    )
    .unwrap_err();
    let chain = format!("{:#}", anyhow::Error::new(e));
    assert_eq!(chain.matches("No such file").count(), 1, "{chain}");
}

// ---------------------------------------------------------------------------------------------
// Size caps on every file read.

#[test]
fn devices_fifos_and_directories_are_refused_before_reading() {
    let dir = scratch_dir("hostile-cases-files");
    let fifo = dir.join("pipe.json");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    for (path, kind) in [
        (std::path::PathBuf::from("/dev/zero"), "character device"),
        (dir.clone(), "directory"),
        (fifo.clone(), "named pipe"),
    ] {
        if path == fifo && !made.as_ref().is_ok_and(|s| s.success()) {
            println!("skipped: mkfifo is not available");
            continue;
        }
        // Opening a FIFO would block and reading /dev/zero would never end: a hang bound.
        let p = path.clone();
        let report = run_bounded(move || Hairstyle::load(&p).map(|_| ()), HANG).unwrap();
        let msg = report.value.unwrap_err().to_string();
        assert!(msg.contains(kind), "{}: {msg}", path.display());
        let p = path.clone();
        let report = run_bounded(
            move || Motion::load(&p, &MotionOptions::default()).map(|_| ()),
            HANG,
        )
        .unwrap();
        let msg = report.value.unwrap_err().to_string();
        assert!(msg.contains(kind), "{}: {msg}", path.display());
    }
}

#[test]
fn a_file_over_the_cap_is_refused_from_its_size_alone() {
    let dir = scratch_dir("hostile-cases-sparse");
    let big = dir.join("big.glb");
    // A sparse 300 MB file: nothing is written, and nothing may be read.
    std::fs::File::create(&big)
        .unwrap()
        .set_len(300 << 20)
        .unwrap();
    let report = run_bounded(
        move || Motion::load(&big, &MotionOptions::default()).map(|_| ()),
        HANG,
    )
    .unwrap();
    let msg = report.value.unwrap_err().to_string();
    assert!(
        msg.contains("over the 268.4 MB limit for a glTF file"),
        "{msg}"
    );
    assert!(
        report.peak_bytes < 1 << 20,
        "read {} bytes",
        report.peak_bytes
    );
    match read_capped(&dir.join("missing"), 10, "x") {
        Err(ReadError::Io(_)) => {}
        other => panic!("{other:?}"),
    }
}

#[test]
fn an_external_buffer_that_is_a_device_is_refused() {
    let dir = scratch_dir("hostile-cases-bin");
    let mut doc = head_clip();
    doc["buffers"][0]["uri"] = json!("zero.bin");
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.bin")).unwrap();
    let gltf = dir.join("clip.gltf");
    std::fs::write(&gltf, doc.to_string()).unwrap();
    let report = run_bounded(move || Motion::load(&gltf, &fixed_fit()).map(|_| ()), HANG).unwrap();
    let msg = report.value.unwrap_err().to_string();
    assert!(msg.contains("character device"), "{msg}");
}

// ---------------------------------------------------------------------------------------------
// Hangs and unbounded work found beyond the list.

#[test]
fn a_scalp_of_1e_30_degrees_is_refused_instead_of_growing_the_root_lattice_for_ever() {
    let msg = hairstyle_error(&smooth_with(|v| {
        v["scalp"] = json!({"max_polar_deg": 1e-30, "front_polar_deg": 1e-30})
    }));
    assert!(msg.contains("`scalp.max_polar_deg`"), "{msg}");
}

#[test]
fn a_denormal_curl_period_is_refused_instead_of_making_nan_strands() {
    let msg = hairstyle_error(&smooth_with(|v| {
        v["curl"] = json!({"radius_m": 0.01, "period_m": 1e-45})
    }));
    assert!(msg.contains("`curl.period_m`"), "{msg}");
}

#[test]
fn a_chain_of_100000_nodes_loads_in_linear_time() {
    // Each node's chain was walked to check for cycles: 10^10 steps.
    let mut fx = Fx::default();
    let n = 100_000;
    for i in 0..n {
        let children = if i + 1 < n { json!([i + 1]) } else { json!([]) };
        let name = if i + 1 == n {
            "Head".to_string()
        } else {
            format!("n{i}")
        };
        fx.node(json!({"name": name, "children": children}));
    }
    fx.channel(n - 1, "translation", "LINEAR", &[0.0, 1.0], &[0.0; 6]);
    let bytes = fx.bytes(&["Dance"]);
    let report = run_bounded(move || load(&bytes, &fixed_fit()).map(|_| ()), HANG).unwrap();
    report.value.expect("a long chain is a valid hierarchy");
}

#[test]
fn a_cycle_in_the_hierarchy_is_named() {
    let mut doc = head_clip();
    doc["nodes"] = json!([{"name": "Head", "children": [1]}, {"name": "B", "children": [0]}]);
    let msg = motion_error(doc.to_string().as_bytes(), &fixed_fit());
    assert!(
        msg.contains("has two parents") || msg.contains("cycle"),
        "{msg}"
    );
}

#[test]
fn one_accessor_read_by_many_channels_is_charged_each_time() {
    // 2,000 channels sharing one 40,000-key accessor: 2000 × 40000 × 4 values = 320 M values,
    // over the 64 M decoded-value budget, from a file of a few hundred KB.
    let keys = 40_000;
    let mut fx = Fx::default();
    let h = fx.node(json!({"name": "Head"}));
    let times: Vec<f32> = (0..keys).map(|i| i as f32).collect();
    let mut rot = Vec::with_capacity(keys * 4);
    for _ in 0..keys {
        rot.extend_from_slice(&[0.0, 0.0, 0.0, 1.0]);
    }
    fx.channel(h, "rotation", "LINEAR", &times, &rot);
    let mut doc = fx.json(&["Dance"]);
    let channel = doc["animations"][0]["channels"][0].clone();
    let many: Vec<Value> = (0..2000).map(|_| channel.clone()).collect();
    doc["animations"][0]["channels"] = json!(many);
    let bytes = doc.to_string().into_bytes();
    let report = run_bounded(move || load(&bytes, &fixed_fit()).map(|_| ()), HANG).unwrap();
    let msg = report.value.unwrap_err().to_string();
    assert!(msg.contains("over 67108864 values"), "{msg}");
    assert!(
        report.peak_bytes < 1 << 30,
        "peak {} bytes",
        report.peak_bytes
    );
}

#[test]
fn glb_buffers_other_than_the_first_may_not_share_the_binary_chunk() {
    let mut doc = head_clip();
    doc["buffers"] = json!([{"byteLength": 4}, {"byteLength": 4}]);
    let glb = make_glb(&doc.to_string(), &[0u8; 4]);
    let msg = motion_error(&glb, &fixed_fit());
    assert!(msg.contains("buffer 1: has no uri"), "{msg}");
}

// ---------------------------------------------------------------------------------------------
// Memory: the budget.

fn hairstyle(edit: impl FnOnce(&mut Value)) -> Hairstyle {
    Hairstyle::from_json(&smooth_with(edit), "big.json").expect("within the field limits")
}

fn check(style: &Hairstyle) -> Result<(), BudgetError> {
    estimate(
        style,
        &Motion::still(glam::Affine3A::IDENTITY),
        &EngineConfig::default(),
        &RunPlan::default(),
    )
    .check(&Budget::default())
}

#[test]
fn the_documented_maxima_are_refused_by_the_budget_naming_the_map() {
    // 100,000 wisps × 20 strands × 20 points: 2 M strands, 40 M points (the field limits).
    let style = hairstyle(|v| {
        v["wisps"] = json!({"count": 100000, "radius_m": 0.013, "strands_per_wisp": 20});
        v["strands"] = json!({"points": 20, "fibers_per_strand": 30});
    });
    match check(&style) {
        Err(BudgetError::Memory { what, .. }) => assert_eq!(what, "light map"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_hundred_thousand_wisps_of_256_links_are_refused_naming_the_simulation() {
    let style = hairstyle(|v| {
        v["wisps"] = json!({"count": 100000, "radius_m": 0.013, "strands_per_wisp": 1});
        v["guides"]["links"] = json!(256);
        v["strands"] = json!({"points": 2, "fibers_per_strand": 30});
    });
    match check(&style) {
        Err(BudgetError::Memory { what, .. }) => assert_eq!(what, "simulation"),
        other => panic!("{other:?}"),
    }
    // With the memory allowed, the work before the first frame is refused.
    let est = estimate(
        &style,
        &Motion::still(glam::Affine3A::IDENTITY),
        &EngineConfig::default(),
        &RunPlan::default(),
    );
    let roomy = Budget {
        memory_bytes: 100_000_000_000,
        ..Budget::default()
    };
    match est.check(&roomy) {
        Err(BudgetError::Work { what, .. }) => {
            assert_eq!(what, "settle and warm-up simulation")
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_step_of_2e_5_seconds_is_charged_as_work() {
    // 50,000 steps per simulated second: the 2 s settle alone is 100,000 steps of 96,000
    // particles (one render strand per wisp, so the memory stays small and the work is what
    // is over).
    let style = hairstyle(|v| {
        v["wisps"]["count"] = json!(2000);
        v["wisps"]["strands_per_wisp"] = json!(1);
        v["dynamics"]["step_s"] = json!(2e-5);
    });
    assert!(matches!(check(&style), Err(BudgetError::Work { .. })));
}

// ---------------------------------------------------------------------------------------------
// Degenerate but legal: a sensible picture.

/// Hair pixels (neither background nor the head's skin tone would be guessed reliably, so count
/// pixels that differ from the background) and whether all are finite.
fn render_one(style: Hairstyle, motion: Motion) -> (usize, bool, wisp::map::MapStats) {
    let config = {
        let mut config = EngineConfig::sized(96, 96);
        config.simulation.settle_s = 0.5;
        config
    };
    let background = config.scene.background;
    let mut engine = Engine::new(style, motion, config);
    engine.frame(0.0);
    let fb = engine.framebuffer();
    let drawn = fb.color.iter().filter(|c| **c != background).count();
    let finite = fb.color.iter().all(|c| c.is_finite());
    (drawn, finite, engine.map_stats().clone())
}

#[test]
fn the_smallest_legal_head_gives_a_picture_with_hair() {
    let style = hairstyle(|v| v["head"]["radii_m"] = json!([0.01, 0.01, 0.01]));
    let (drawn, finite, stats) = render_one(style, Motion::still(glam::Affine3A::IDENTITY));
    assert!(finite);
    assert_eq!(stats.skipped, 0, "{stats:?}");
    assert!(drawn > 200, "only {drawn} of 9216 pixels drawn");
}

#[test]
fn a_head_far_away_but_within_the_limit_still_renders() {
    let far = glam::Affine3A::from_translation(glam::Vec3::new(9_000.0, 0.0, 0.0));
    let (drawn, finite, stats) = render_one(Hairstyle::default_smooth(), Motion::still(far));
    assert!(finite);
    assert_eq!(stats.skipped, 0, "{stats:?}");
    assert!(drawn > 200, "only {drawn} of 9216 pixels drawn");
}
