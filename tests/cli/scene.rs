//! Scene files on the command line (issue 9): `--print-scene` and `--scene` give the default
//! render's bytes back, flags override a file's fields, and bad scene files exit 2 naming the
//! file, the field and the rule, never panicking.

use crate::support::scratch_dir;
use crate::wisp;

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

#[test]
fn printed_scene_renders_the_same_bytes_as_the_default() {
    let dir = scratch_dir("scene-cli-roundtrip");
    let size = ["--width", "64", "--height", "48"];
    let printed = wisp(&[&["render", "--print-scene"][..], &size].concat());
    assert_eq!(printed.status.code(), Some(0), "{}", text(&printed.stderr));
    let scene = dir.join("s.json");
    std::fs::write(&scene, &printed.stdout).unwrap();
    let (a, b) = (dir.join("a"), dir.join("b"));
    let plain = wisp(
        &[
            &["render", "--still", "--quiet", "--out", a.to_str().unwrap()][..],
            &size,
        ]
        .concat(),
    );
    assert_eq!(plain.status.code(), Some(0), "{}", text(&plain.stderr));
    let via = wisp(&[
        "render",
        "--still",
        "--quiet",
        "--scene",
        scene.to_str().unwrap(),
        "--out",
        b.to_str().unwrap(),
    ]);
    assert_eq!(via.status.code(), Some(0), "{}", text(&via.stderr));
    let frame = "frame_00000.png";
    assert!(
        std::fs::read(a.join(frame)).unwrap() == std::fs::read(b.join(frame)).unwrap(),
        "the scene file's frame differs from the default render"
    );
    // Printing the file's scene gives the file back.
    let again = wisp(&[
        "render",
        "--print-scene",
        "--scene",
        scene.to_str().unwrap(),
    ]);
    assert_eq!(text(&again.stdout), text(&printed.stdout));
}

#[test]
fn flags_override_the_scene_file() {
    let dir = scratch_dir("scene-cli-override");
    let scene = dir.join("s.json");
    std::fs::write(
        &scene,
        r#"{"image": {"width": 100, "height": 80}, "ambient": [0.1, 0.1, 0.1]}"#,
    )
    .unwrap();
    let o = wisp(&[
        "render",
        "--print-scene",
        "--scene",
        scene.to_str().unwrap(),
        "--width",
        "48",
        "--ambient",
        "0",
        "--no-solids",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["image"]["width"], 48);
    assert_eq!(v["image"]["height"], 80);
    assert_eq!(v["ambient"][0], 0.0);
    assert_eq!(v["draw_solids"], false);
}

#[test]
fn bad_scene_files_exit_2_naming_file_field_and_rule() {
    let dir = scratch_dir("scene-cli-bad");
    let point_first =
        r#"{"lights": [{"type": "point", "position_m": [2, 0, 0], "intensity": [1, 1, 1]}]}"#;
    let cases: Vec<(&str, &str, Vec<&str>)> = vec![
        ("{", "EOF while parsing", vec![]),
        (
            r#"{"lights": []}"#,
            "lights: needs at least one light",
            vec![],
        ),
        (r#"{"lights": 3}"#, "lights", vec![]),
        (
            r#"{"image": {"width": "wide", "height": 80}}"#,
            "image.width",
            vec![],
        ),
        (r#"{"image": {"width": 80}}"#, "image", vec![]),
        (r#"{"ambient": [NaN, 0, 0]}"#, "ambient[0]", vec![]),
        (r#"{"ambient": [1e39, 0, 0]}"#, "ambient", vec![]),
        (r#"{"exposure_stops": -40}"#, "exposure_stops", vec![]),
        (r#"{"camera": {"type": "orbit"}}"#, "camera", vec![]),
        (
            r#"{"camera": {"type": "fixed", "position_m": [0, 0, 1], "target_m": [0, 0, 1]}}"#,
            "camera.position_m",
            vec![],
        ),
        (
            r#"{"camera": {"type": "fixed", "position_m": [0, 0, 1], "target_m": [0, 0, 0], "up": [0, 0, 1]}}"#,
            "camera.up",
            vec![],
        ),
        (
            r#"{"lights": [{"type": "directional", "direction": [0, 0, 0], "irradiance": [1, 1, 1]}]}"#,
            "lights[0].direction",
            vec![],
        ),
        (
            r#"{"lights": [{"type": "directional", "direction": [0, -1, 0]}]}"#,
            "lights[0]",
            vec![],
        ),
        (
            r#"{"lights": [{"type": "point", "position_m": [0.05, 0.0, 0.0], "intensity": [1, 1, 1]}]}"#,
            "lights[0].position_m: the point light",
            vec![],
        ),
        (r#"{"lighting": {}}"#, "lighting", vec![]),
        (point_first, "--irradiance", vec!["--irradiance", "2"]),
        (point_first, "--light-dir", vec!["--light-dir", "0,-1,0"]),
    ];
    for (i, (content, needle, extra)) in cases.iter().enumerate() {
        let path = dir.join(format!("bad{i}.json"));
        std::fs::write(&path, content).unwrap();
        let out = dir.join(format!("out{i}"));
        let args = [
            &[
                "render",
                "--still",
                "--quiet",
                "--width",
                "32",
                "--height",
                "32",
                "--scene",
                path.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ][..],
            &extra[..],
        ]
        .concat();
        let o = wisp(&args);
        let err = text(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{content}: {err}");
        assert!(!err.contains("panicked"), "{content} panicked: {err}");
        assert!(err.contains(needle), "{content}: no `{needle}` in: {err}");
        if extra.is_empty() {
            assert!(
                err.contains(&format!("bad{i}.json")),
                "{content}: the file is not named: {err}"
            );
        }
        assert!(!out.join("frame_00000.png").exists());
    }
    // Not a file at all.
    for path in [dir.clone(), dir.join("missing.json")] {
        let o = wisp(&["render", "--scene", path.to_str().unwrap(), "--print-scene"]);
        assert_eq!(o.status.code(), Some(2), "{}", text(&o.stderr));
        assert!(text(&o.stderr).contains(path.to_str().unwrap()));
    }
}

/// `export` writes a path tracer's scene, which has one light (directional or point): a
/// scene with two is refused up front (exit 2), before any frame is rendered.
#[test]
fn export_refuses_scenes_it_cannot_describe() {
    let dir = scratch_dir("scene-cli-export");
    let scene = dir.join("s.json");
    std::fs::write(
        &scene,
        r#"{"lights": [{"type": "point", "position_m": [2, 0, 0], "intensity": [1, 1, 1]},
                      {"type": "directional", "direction": [0, -1, 0], "irradiance": [1, 1, 1]}]}"#,
    )
    .unwrap();
    let out = dir.join("out");
    let o = wisp(&[
        "export",
        "--still",
        "--scene",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o.stderr));
    assert!(text(&o.stderr).contains("exactly one light"));
    assert!(text(&o.stderr).contains("this scene has 2"));
    assert!(!out.join("scene.json").exists());
}

/// `--framing` writes the engine camera's framing into the scene (`--print-scene` shows it),
/// and is refused (exit 2, naming the flag) for an unknown name, beside `--camera-eye`, and
/// over a scene file whose camera is fixed.
#[test]
fn framing_flag_is_written_into_the_scene_and_refused_where_it_cannot_apply() {
    let printed = wisp(&["render", "--print-scene", "--framing", "full"]);
    assert_eq!(printed.status.code(), Some(0), "{}", text(&printed.stderr));
    let out = text(&printed.stdout);
    assert!(out.contains("\"framing\": \"full\""), "{out}");
    let bad = wisp(&["render", "--print-scene", "--framing", "legs"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(text(&bad.stderr).contains("head, upper or full"));
    let eye = [
        "render",
        "--print-scene",
        "--framing",
        "upper",
        "--camera-eye",
        "0,0,1",
        "--camera-target",
        "0,0,0",
    ];
    assert_eq!(wisp(&eye).status.code(), Some(2));
    let dir = scratch_dir("scene-cli-framing");
    let fixed = dir.join("fixed.json");
    let camera = r#"{"camera": {"type": "fixed", "position_m": [0, 0, 1], "target_m": [0, 0, 0]}}"#;
    std::fs::write(&fixed, camera).unwrap();
    let o = wisp(&[
        "render",
        "--print-scene",
        "--scene",
        fixed.to_str().unwrap(),
        "--framing",
        "upper",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o.stderr).contains("--framing"), "{}", text(&o.stderr));
}
