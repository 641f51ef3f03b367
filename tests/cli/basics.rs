//! The `wisp` binary as a user meets it: exit codes and messages for bad input, and a small
//! export whose frames are complete PNGs, byte-identical for 1 and 2 threads.

use crate::support::scratch_dir;
use crate::{stderr, wisp};
use std::path::Path;
use std::process::Command;

#[test]
fn bad_flags_exit_2_with_a_message_naming_the_flag() {
    for (args, needle) in [
        (vec!["render", "--light-dir", "1,2"], "--light-dir"),
        (vec!["render", "--light-dir", "0,0,0"], "must not be zero"),
        (vec!["render", "--light-dir", "1,nan,0"], "finite"),
        (vec!["render", "--width", "0"], "--width"),
        (vec!["render", "--frames", "-3"], "--frames"),
        (vec!["render", "--fps", "0"], "--fps"),
        (vec!["render", "--map-res", "100000"], "--map-res"),
        (vec!["render", "--shading", "phong"], "--shading"),
        (vec!["render", "--speed", "inf"], "--speed"),
        (vec!["render", "--no-such-flag"], "--no-such-flag"),
        (vec!["render", "--clip", "Walk"], "--animation"),
    ] {
        let o = wisp(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains(needle),
            "{args:?}: message does not mention {needle}: {}",
            stderr(&o)
        );
        assert!(!stderr(&o).contains("panicked"), "{args:?} panicked");
    }
}

#[test]
fn bad_files_exit_2_naming_the_file() {
    let dir = scratch_dir("cli-bad-files");
    let bad_json = dir.join("bad.json");
    std::fs::write(&bad_json, "{ \"name\": 3 }").unwrap();
    let not_gltf = dir.join("dance.glb");
    std::fs::write(&not_gltf, b"certainly not a glTF file").unwrap();
    let out = dir.join("out");
    let out = out.to_str().unwrap();
    for (args, needle) in [
        (
            vec!["render", "--hairstyle", "/no/such/hair.json", "--out", out],
            "/no/such/hair.json",
        ),
        (
            vec![
                "render",
                "--hairstyle",
                bad_json.to_str().unwrap(),
                "--out",
                out,
            ],
            "bad.json",
        ),
        (
            vec!["render", "--animation", "/no/such/dance.glb", "--out", out],
            "/no/such/dance.glb",
        ),
        (
            vec![
                "render",
                "--animation",
                not_gltf.to_str().unwrap(),
                "--out",
                out,
            ],
            "dance.glb",
        ),
    ] {
        let o = wisp(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"));
    }
    // No frames were written for failed runs.
    assert!(!Path::new(out).join("frame_00000.png").exists());
}

#[test]
fn export_writes_complete_frames_identical_for_one_and_two_threads() {
    let a = scratch_dir("cli-export-1");
    let b = scratch_dir("cli-export-2");
    let common = [
        "render",
        "--frames",
        "2",
        "--width",
        "96",
        "--height",
        "96",
        "--start-s",
        "4.0",
        "--quiet",
    ];
    for (threads, dir) in [("1", &a), ("2", &b)] {
        let mut args = vec!["--threads", threads];
        args.extend(common);
        args.extend(["--out", dir.to_str().unwrap()]);
        let o = wisp(&args);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    for i in 0..2 {
        let name = format!("frame_{i:05}.png");
        let fa = std::fs::read(a.join(&name)).unwrap();
        let fb = std::fs::read(b.join(&name)).unwrap();
        assert_eq!(&fa[1..4], b"PNG");
        assert!(fa == fb, "{name} differs between 1 and 2 threads");
    }
    // Only complete frames: no temporary files left behind.
    let leftovers: Vec<_> = std::fs::read_dir(&a)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty());
}

#[test]
fn play_without_a_display_fails_cleanly() {
    let o = Command::new(env!("CARGO_BIN_EXE_wisp"))
        .args(["play", "--frames", "1"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("wisp render"), "{}", stderr(&o));
    assert!(!stderr(&o).contains("panicked"));
}

#[test]
fn bench_runs_and_writes_json() {
    let dir = scratch_dir("cli-bench");
    let json = dir.join("bench.json");
    let style = crate::support::small_hairstyle(&dir);
    let o = wisp(&[
        "bench",
        "--hairstyle",
        style.to_str().unwrap(),
        "--frames",
        "2",
        "--width",
        "64",
        "--height",
        "64",
        "--threads-list",
        "1,2",
        "--map-res-list",
        "16,32",
        "--repeats",
        "1",
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert_eq!(v["scaling"].as_array().unwrap().len(), 2);
    // The map stage by part: the dance moves the hair, so every frame builds the hair map.
    for row in v["scaling"].as_array().unwrap() {
        for key in ["map_hair_ms", "map_occluders_ms", "map_skin_texture_ms"] {
            let ms = row[key].as_f64().unwrap();
            assert!(ms.is_finite() && ms >= 0.0, "{key}: {row}");
        }
        assert!(row["map_hair_ms"].as_f64().unwrap() > 0.0, "{row}");
    }
    let rows = v["speed_vs_error"].as_array().unwrap();
    // The two resolutions asked for, plus the scene's own choice.
    assert_eq!(rows.len(), 3);
    for r in rows {
        let e = r["luminance_rel_rms"].as_f64().unwrap();
        assert!(e.is_finite() && e >= 0.0, "{r}");
    }
    let o = wisp(&["bench", "--threads-list", "0"]);
    assert_eq!(o.status.code(), Some(2));
    // `--parts scaling`: the timings only.
    let o = wisp(&[
        "bench",
        "--frames",
        "1",
        "--width",
        "64",
        "--height",
        "64",
        "--threads-list",
        "1",
        "--parts",
        "scaling",
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert_eq!(v["scaling"].as_array().unwrap().len(), 1);
    assert!(v.get("speed_vs_error").is_none() && v.get("self_collision").is_none());
    let o = wisp(&["bench", "--parts", "everything"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--parts"), "{}", stderr(&o));
}

#[test]
fn a_reader_that_closes_the_pipe_early_stops_wisp_quietly() {
    // `wisp fiber tables | head -c 10`: the reader is gone before wisp writes its tables. The
    // standard print macros would panic with a backtrace; wisp stops with 141 (as a program
    // killed by SIGPIPE) and says nothing.
    let mut child = Command::new(env!("CARGO_BIN_EXE_wisp"))
        .args(["fiber", "tables"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run wisp");
    drop(child.stdout.take());
    let o = child.wait_with_output().expect("wait for wisp");
    assert_eq!(o.status.code(), Some(141), "stderr: {}", stderr(&o));
    assert!(stderr(&o).is_empty(), "stderr: {}", stderr(&o));
}

#[test]
fn a_hairstyle_with_coarse_curls_loads_with_a_warning_naming_the_field() {
    // The curly preset at its old 61 points: legal, but measured to light curls wrongly
    // (`Hairstyle::advisories`). It renders (exit 0) and says so; at 121 points it is silent.
    let dir = scratch_dir("cli-coarse-curls");
    for (points, warned) in [(61u32, true), (121, false)] {
        let mut style = wisp::hairstyle::Hairstyle::default_curly();
        style.strands.points = points;
        let file = dir.join(format!("curly{points}.json"));
        std::fs::write(&file, serde_json::to_string(&style).unwrap()).unwrap();
        let out = dir.join(format!("out{points}"));
        let o = wisp(&[
            "render",
            "--frames",
            "1",
            "--width",
            "32",
            "--height",
            "32",
            "--quiet",
            "--hairstyle",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let err = stderr(&o);
        let named = err.contains("warning")
            && err.contains(&format!("curly{points}.json"))
            && err.contains("strands.points");
        assert_eq!(named, warned, "{points} points: {err}");
        assert!(out.join("frame_00000.png").exists());
    }
}
