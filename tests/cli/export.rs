//! `wisp export` through the binary: the scene it writes carries the camera and light flags
//! (or a scene file's one point light),
//! the EXR its size and coverage, and bad camera flags are bad input (exit 2).

use crate::support::scratch_dir;
use crate::wisp;
use glam::Vec3;
use wisp::export::{LightJson, ReferenceScene};
use wisp::output::read_exr_rgba_f32;

/// A scene file's one point light is exported with the numbers it was given: its position in
/// metres and its intensity (tools/reference/render.py's `point` emitter).
#[test]
fn export_writes_a_point_light() {
    let dir = scratch_dir("export-cli-point");
    let scene_file = dir.join("p.json");
    std::fs::write(
        &scene_file,
        r#"{"lights": [{"type": "point", "position_m": [0.3, 0.2, 0.4], "intensity": [0.2, 0.1, 0.05]}]}"#,
    )
    .unwrap();
    let out = dir.join("scene");
    let o = wisp(&[
        "export",
        "--still",
        "--no-solids",
        "--ambient",
        "0",
        "--width",
        "32",
        "--height",
        "32",
        "--scene",
        scene_file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let scene: ReferenceScene =
        serde_json::from_str(&std::fs::read_to_string(out.join("scene.json")).unwrap()).unwrap();
    assert_eq!(
        scene.light,
        LightJson::Point {
            position_m: [0.3, 0.2, 0.4],
            intensity: [0.2, 0.1, 0.05],
        }
    );
}

#[test]
fn export_command_writes_the_scene_and_refuses_bad_cameras() {
    let dir = scratch_dir("export-cli");
    let out = dir.join("scene");
    let out_s = out.to_str().unwrap();
    let o = wisp(&[
        "export",
        "--still",
        "--no-solids",
        "--ambient",
        "0",
        "--irradiance",
        "1",
        "--width",
        "48",
        "--height",
        "40",
        "--camera-eye",
        "0.6,0,1",
        "--camera-target",
        "0,-0.1,0",
        "--fov-deg",
        "35",
        "--light-dir",
        "-1,0,-1",
        "--out",
        out_s,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let scene: ReferenceScene =
        serde_json::from_str(&std::fs::read_to_string(out.join("scene.json")).unwrap()).unwrap();
    assert_eq!(scene.camera.eye, [0.6, 0.0, 1.0]);
    assert!((scene.camera.fov_y_deg - 35.0).abs() < 1e-4);
    let LightJson::Directional {
        direction,
        irradiance,
    } = scene.light
    else {
        panic!("a directional light was exported as {:?}", scene.light);
    };
    assert_eq!(irradiance, [1.0; 3]);
    assert_eq!(scene.ambient, [0.0; 3]);
    let s = std::f32::consts::FRAC_1_SQRT_2;
    assert!((Vec3::from(direction) - Vec3::new(-s, 0.0, -s)).length() < 1e-6);
    let (w, h, _, alpha) = read_exr_rgba_f32(&out.join("wisp.exr")).unwrap();
    assert_eq!((w, h), (48, 40));
    assert!(alpha.iter().any(|a| *a > 0.0));

    for (args, needle) in [
        (
            vec!["--camera-eye", "0,0,1", "--camera-target", "0,0,1"],
            "must differ",
        ),
        (
            vec![
                "--camera-eye",
                "0,0,1",
                "--camera-target",
                "0,0,0",
                "--camera-up",
                "0,0,1",
            ],
            "parallel",
        ),
        (
            vec![
                "--camera-eye",
                "0,0,1",
                "--camera-target",
                "0,0,0",
                "--fov-deg",
                "180",
            ],
            "field of view",
        ),
        (vec!["--camera-eye", "0,0,1"], "--camera-target"),
        (vec!["--fov-deg", "30"], "--camera-eye"),
        (
            vec!["--camera-eye", "0,nan,1", "--camera-target", "0,0,0"],
            "finite",
        ),
        (vec!["--ambient", "-1"], ">= 0"),
        (vec!["--irradiance", "1,2"], "three"),
        (vec!["--min-line-width-px", "0"], "--min-line-width-px"),
    ] {
        let mut a = vec!["export", "--still", "--out", out_s];
        a.extend(args.iter().copied());
        let o = wisp(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"));
    }
    // Missing --out is a usage error too.
    assert_eq!(wisp(&["export", "--still"]).status.code(), Some(2));
}
