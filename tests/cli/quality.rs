//! `--quality` and the scene file's `quality` through the binary: a level is its pass configs,
//! each flag given overrides its level's choice, the flag overrides the file, and a bad level
//! is bad input (exit 2) naming the flag or the field.

use crate::support::scratch_dir;
use crate::{stderr, wisp};
use std::path::Path;

/// The one frame of a still 48 × 48 render with `extra` flags, into `dir/name`.
fn frame(dir: &Path, name: &str, extra: &[&str]) -> Vec<u8> {
    let out = dir.join(name);
    let base = [
        "render", "--still", "--quiet", "--width", "48", "--height", "48",
    ];
    let o = wisp(&[&base[..], extra, &["--out", out.to_str().unwrap()]].concat());
    assert_eq!(o.status.code(), Some(0), "{extra:?}: {}", stderr(&o));
    std::fs::read(out.join("frame_00000.png")).expect("the frame")
}

#[test]
fn flags_given_override_the_level_and_the_level_overrides_the_defaults() {
    let dir = scratch_dir("cli-quality-flags");
    let plain = frame(&dir, "plain", &[]);
    assert!(
        plain == frame(&dir, "final", &["--quality", "final"]),
        "final is the default"
    );
    let preview = frame(&dir, "preview", &["--quality", "preview"]);
    assert!(preview != plain, "preview draws other hair than final");
    // The reference level with each of its choices that has a flag set back to final's: only
    // what has no flag is left (none, for the reference level), so the bytes are final's.
    let undone = frame(
        &dir,
        "undone",
        &[
            "--quality",
            "reference",
            "--shading",
            "dual",
            "--sim-hz",
            "480",
            "--segment-pieces",
            "1",
            "--contact-mm",
            "0",
        ],
    );
    assert!(
        undone == plain,
        "flags given did not override the reference level"
    );
}

#[test]
fn the_scene_file_names_a_level_and_the_flag_overrides_it() {
    let dir = scratch_dir("cli-quality-file");
    let scene = dir.join("s.json");
    std::fs::write(&scene, r#"{"quality": "preview"}"#).unwrap();
    let s = scene.to_str().unwrap();
    let from_file = frame(&dir, "file", &["--scene", s]);
    assert!(from_file == frame(&dir, "flag", &["--quality", "preview"]));
    assert!(
        frame(&dir, "over", &["--scene", s, "--quality", "final"]) == frame(&dir, "plain", &[])
    );
    for (args, needle) in [
        (vec!["render", "--quality", "fast"], "--quality"),
        (
            vec!["render", "--strand-fraction", "0"],
            "--strand-fraction",
        ),
        (vec!["render", "--sim-hz", "5"], "--sim-hz"),
        (
            vec!["bench", "--quality-list", "preview,best"],
            "--quality-list",
        ),
    ] {
        let o = wisp(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
    }
    let bad = dir.join("bad.json");
    std::fs::write(&bad, r#"{"quality": "fast"}"#).unwrap();
    let o = wisp(&["render", "--scene", bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("quality") && stderr(&o).contains("bad.json"),
        "{}",
        stderr(&o)
    );
}
