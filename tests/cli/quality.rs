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
            "--volume-paths",
            "200000",
            "--volume-cell-mm",
            "6",
            "--volume-strongest",
            "16",
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

/// Width and height of `wisp bench --plot`'s picture (its `--help`: 960 × 640).
const PLOT_SIZE: (u32, u32) = (960, 640);

#[test]
fn the_bench_quality_report_has_flip_and_tf_figures_and_draws_its_plot() {
    let dir = scratch_dir("cli-quality-plot");
    let style = crate::support::small_hairstyle(&dir);
    let (plot, json) = (dir.join("q.png"), dir.join("q.json"));
    let run = |levels: &str, extra: &[&str]| {
        let base = [
            "bench",
            "--hairstyle",
            style.to_str().unwrap(),
            "--frames",
            "1",
            "--width",
            "64",
            "--height",
            "48",
            "--threads-list",
            "1",
            "--quality-list",
            levels,
        ];
        wisp(&[&base[..], extra].concat())
    };
    // A flag given is written over every level's choice, as with `render --quality`.
    let o = run(
        "preview,final",
        &[
            "--plot",
            plot.to_str().unwrap(),
            "--json",
            json.to_str().unwrap(),
            "--volume-paths",
            "5000",
        ],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("FLIP") && stdout.contains("Tf MAE"),
        "{stdout}"
    );
    // A PNG of the plot's size: its decoder reads the signature and the IHDR chunk.
    let bytes = std::fs::read(&plot).expect("the plot");
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .expect("a PNG");
    assert_eq!((reader.info().width, reader.info().height), PLOT_SIZE);
    // The JSON has each level's map error and preview's ꟻLIP against final, in range.
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let levels = v["quality"].as_array().unwrap();
    assert_eq!(levels.len(), 2);
    for level in levels {
        let tf = level["tf_mae"].as_f64().unwrap();
        assert!((0.0..0.2).contains(&tf), "{level}");
        assert_eq!(level["shading"]["volume_paths"], 5000, "{level}");
    }
    assert_eq!(levels[0]["shading"]["mode"], "DualScattering");
    assert_eq!(levels[1]["shading"]["mode"], "Volume");
    // final's light paths at 6 builds a second: their late light and a build for every
    // frame's, both against converged paths, and only final has them.
    let rate = &levels[1]["paths_rate"];
    assert_eq!(rate["hz"], 6.0, "{rate}");
    for e in [rate, &rate["every_frame"]] {
        let mean = e["mean_rel_luminance"].as_f64().unwrap();
        assert!(mean > 0.0 && mean < 1.0, "{e}");
    }
    assert!(levels[0].get("paths_rate").is_none());
    let flip = levels[0]["vs_final"]["flip_mean"].as_f64().unwrap();
    assert!(flip > 0.0 && flip < 1.0, "preview against final: {flip}");
    assert!(v["quality_tf_reference"]["vertices"].as_u64().unwrap() > 0);
    // The report drawn again beside this run's scene (`--plot-with`).
    let both = dir.join("both.png");
    let o = run(
        "preview,final",
        &[
            "--plot",
            both.to_str().unwrap(),
            "--plot-with",
            json.to_str().unwrap(),
            "--volume-paths",
            "5000",
        ],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(
        &std::fs::read(&both).expect("the plot")[..8],
        b"\x89PNG\r\n\x1a\n"
    );
    // Refused before any work: a folder that does not exist, a run without the quality part,
    // levels that compare none.
    let missing = dir.join("no-such-folder").join("q.png");
    for (levels, extra) in [
        ("preview,final", vec!["--plot", missing.to_str().unwrap()]),
        (
            "preview,final",
            vec!["--plot", plot.to_str().unwrap(), "--parts", "scaling"],
        ),
        ("final", vec!["--plot", plot.to_str().unwrap()]),
        ("preview,final", vec!["--plot-with", json.to_str().unwrap()]),
        (
            "preview,final",
            vec![
                "--plot",
                plot.to_str().unwrap(),
                "--plot-with",
                plot.to_str().unwrap(),
            ],
        ),
    ] {
        let o = run(levels, &extra);
        assert_eq!(o.status.code(), Some(2), "{levels} {extra:?}");
        assert!(stderr(&o).contains("--plot"), "{extra:?}: {}", stderr(&o));
    }
}

/// `final` shades with light paths traced anew each frame from the same seed, so a still head
/// gives the same frames: no flicker (issue 61 asks for consecutive frames of `render --still`
/// identical, or within one 8-bit level in 99.9% of the pixels).
#[test]
fn final_light_paths_do_not_flicker_on_a_still_head() {
    let dir = scratch_dir("cli-quality-still");
    let out = dir.join("still");
    let o = wisp(&[
        "render",
        "--still",
        "--frames",
        "3",
        "--width",
        "96",
        "--height",
        "96",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let frame = |i: usize| std::fs::read(out.join(format!("frame_{i:05}.png"))).expect("frame");
    assert!(
        frame(0) == frame(1) && frame(1) == frame(2),
        "still frames differ"
    );
}
