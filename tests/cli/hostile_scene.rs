//! Issue 60's scene and message cases through the binary, each as the issue gave it: colours
//! that overflow once exposed, a far point light, an unknown field in a tagged enum, and three
//! messages that blamed the wrong thing (a camera at 1e30 m, `--fps 1e-45`, a groom kept as
//! authored at a unit that collapses it). Plus a sample of the generated scene classes
//! (`support::hostile::scene`).

use crate::support::hostile::Rng;
use crate::support::hostile::scene::{overflowing_after_exposure, slots, unknown_field};
use crate::support::scratch_dir;
use crate::support::strand_files::hairsalon_bytes;
use crate::{stderr, wisp};
use glam::Vec3;
use std::path::Path;

/// A one-frame 32 × 32 render of the still head alone, with `extra` flags, into `dir/out`.
fn render(dir: &Path, extra: &[&str]) -> (Option<i32>, String) {
    let out = dir.join("out");
    let out = out.to_str().unwrap();
    let mut args = vec![
        "render",
        "--still",
        "--no-solids",
        "--frames",
        "1",
        "--width",
        "32",
        "--height",
        "32",
        "--quiet",
        "--out",
        out,
    ];
    args.extend_from_slice(extra);
    let o = wisp(&args);
    (o.status.code(), stderr(&o))
}

fn scene_file(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

#[test]
fn colours_that_overflow_once_exposed_exit_2_naming_the_field() {
    let dir = scratch_dir("hostile-scene-cli-exposure");
    // Before: exit 0, the hair black (NaN), no word.
    let (code, err) = render(&dir, &["--ambient", "3e38", "--exposure-stops", "20"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("ambient (set by --ambient and --exposure-stops): [3e38, 3e38, 3e38] × 2^20")
            && err.contains("must be finite"),
        "{err}"
    );
    let bg = scene_file(
        &dir,
        "bg.json",
        r#"{"background": [3e38, 3e38, 3e38], "exposure_stops": 20}"#,
    );
    let (code, err) = render(&dir, &["--scene", &bg]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("bg.json: background: "), "{err}");
    // Generated: a colour field overflowing at 2 to 20 stops.
    for i in 0..4 {
        let (scene, field) = overflowing_after_exposure(&mut Rng::new(0x5CE0_0C00 + i));
        let f = scene_file(&dir, "gen.json", &scene.to_string());
        let (code, err) = render(&dir, &["--scene", &f]);
        assert_eq!(code, Some(2), "{err}");
        assert!(err.contains(&format!("gen.json: {field}: ")), "{err}");
    }
}

#[test]
fn a_point_light_at_1e18_m_is_drawn_as_a_directional_light_said_once() {
    let dir = scratch_dir("hostile-scene-cli-far");
    let far = scene_file(
        &dir,
        "far.json",
        r#"{"lights": [{"type": "point", "position_m": [1e18, 1e18, 1e18], "intensity": [6e36, 6e36, 6e36]}]}"#,
    );
    let (code, err) = render(&dir, &["--scene", &far]);
    assert_eq!(code, Some(0), "{err}");
    // Before: "103850 of 103850 render points are not finite numbers and are not drawn", and
    // the hair unshadowed.
    assert_eq!(
        err.matches("drawn as a directional light").count(),
        1,
        "{err}"
    );
    assert!(
        err.contains("far.json: lights[0] is a point light"),
        "{err}"
    );
    assert!(!err.contains("left out of the map"), "{err}");
    assert!(!err.contains("not drawn"), "{err}");
}

#[test]
fn an_unknown_field_in_the_camera_exits_2_naming_the_allowed_fields() {
    let dir = scratch_dir("hostile-scene-cli-unknown");
    let cam = scene_file(
        &dir,
        "cam.json",
        r#"{"camera": {"type": "follow_head", "position_m": "garbage", "zzz": [1, 2]}}"#,
    );
    let (code, err) = render(&dir, &["--scene", &cam]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("cam.json: camera: unknown field `position_m`, expected `framing`"),
        "{err}"
    );
    // Generated: every struct and tagged variant of the scene file.
    for (k, slot) in slots().iter().enumerate() {
        let (scene, name) = unknown_field(&mut Rng::new(0x5CE0_0D00 + k as u64), slot);
        let f = scene_file(&dir, "gen.json", &scene.to_string());
        let (code, err) = render(&dir, &["--scene", &f]);
        assert_eq!(code, Some(2), "{}: {err}", slot.what);
        assert!(
            err.contains("gen.json: ") && err.contains(&format!("unknown field `{name}`")),
            "{}: {err}",
            slot.what
        );
    }
}

#[test]
fn messages_blame_what_is_wrong() {
    let dir = scratch_dir("hostile-scene-cli-blame");
    // Before: "camera.up: camera up [0, 1, 0] must be non-zero and not parallel to the view
    // direction [-0, 0, -0]".
    let (code, err) = render(
        &dir,
        &["--camera-eye", "1e30,1.6,1", "--camera-target", "0,1.6,0"],
    );
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("camera.position_m (set by --camera-eye): camera eye [1e30, 1.6, 1]")
            && err.contains("within 10000 m")
            && !err.contains("camera.up"),
        "{err}"
    );
    // Before: "(set by wisps.count × guides.links, dynamics.step_s, --start-s)".
    let (code, err) = render(&dir, &["--fps", "1e-45"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("--fps: the first frame alone lasts 1/fps") && !err.contains("--start-s"),
        "{err}"
    );
    // Before: "the longest strand is 0.000 m once fitted to the head: it must be more than 0".
    let strands: Vec<Vec<Vec3>> = (0..12)
        .map(|i| {
            let x = 0.01 * i as f32;
            (0..6)
                .map(|k| Vec3::new(x, 0.1 - 0.03 * k as f32, 0.0))
                .collect()
        })
        .collect();
    let groom = dir.join("fur.data");
    std::fs::write(&groom, hairsalon_bytes(&strands)).unwrap();
    let groom = groom.display().to_string();
    let (code, err) = render(
        &dir,
        &[
            "--hairstyle",
            &groom,
            "--groom-as-authored",
            "--groom-unit-m",
            "1e-40",
        ],
    );
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("kept as authored at 1.000e-40 m per file unit (--groom-unit-m)")
            && !err.contains("once fitted to the head"),
        "{err}"
    );
}
