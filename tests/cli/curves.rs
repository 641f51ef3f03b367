//! `wisp render --curves FILE.usda`, through the binary: the file holds one points sample per
//! rendered frame at the run's time codes, the frames are the bytes a run without the flag
//! writes, and a file name of another format, a path that cannot be written or a flag it
//! cannot go with is refused with exit code 2 naming `--curves`. The file's contents are
//! checked number by number in `tests/lib/usd_curves.rs`.

use crate::support::{scratch_dir, small_hairstyle};
use crate::{stderr, wisp};
use std::path::Path;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The value after `key = ` in the layer's metadata.
fn metadata(text: &str, key: &str) -> String {
    text.lines()
        .find_map(|l| l.trim_start().strip_prefix(&format!("{key} = ")))
        .unwrap_or_else(|| panic!("no {key}"))
        .to_string()
}

#[test]
fn curves_of_two_frames_beside_unchanged_frames() {
    let dir = scratch_dir("cli-curves");
    let style = small_hairstyle(&dir);
    let usda = dir.join("hair.usda");
    let common = [
        "render",
        "--hairstyle",
        s(&style),
        "--frames",
        "2",
        "--width",
        "64",
        "--height",
        "64",
        "--fps",
        "24",
        "--start-s",
        "0.5",
    ];
    let (a, b) = (dir.join("a"), dir.join("b"));
    let with = [&common[..], &["--curves", s(&usda), "--out", s(&a)]].concat();
    let o = wisp(&with);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("wrote the curves of 2 frames"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.join("hair.usda.tmp").exists());
    let text = std::fs::read_to_string(&usda).unwrap();
    // 0.5 s at 24 frames a second is time code 12; the second frame is 13.
    assert_eq!(metadata(&text, "startTimeCode"), "12");
    assert_eq!(metadata(&text, "endTimeCode"), "13");
    assert_eq!(metadata(&text, "timeCodesPerSecond"), "24");
    // small_hairstyle: 40 wisps of 8 strands = 320 curves.
    let counts = metadata(&text, "int[] curveVertexCounts");
    let counts: Vec<usize> = counts
        .trim_matches(['[', ']'])
        .split(", ")
        .map(|c| c.parse().unwrap())
        .collect();
    assert_eq!(counts.len(), 320);
    let per_sample: usize = counts.iter().sum();
    // The points' samples come before the extents' (which have the same time codes).
    let points = &text[..text.find("extent.timeSamples").unwrap()];
    let samples: Vec<&str> = points
        .lines()
        .filter(|l| l.starts_with("        12: [(") || l.starts_with("        13: [("))
        .collect();
    assert_eq!(samples.len(), 2, "one points sample per frame");
    for sample in samples {
        assert_eq!(sample.matches('(').count(), per_sample);
    }

    let without = [&common[..], &["--out", s(&b)]].concat();
    let o = wisp(&without);
    assert!(o.status.success(), "{}", stderr(&o));
    for f in ["frame_00000.png", "frame_00001.png"] {
        let with = std::fs::read(a.join(f)).unwrap();
        let without = std::fs::read(b.join(f)).unwrap();
        assert!(with == without, "{f} differs with --curves");
    }
}

#[test]
fn curves_refused_naming_the_flag() {
    let dir = scratch_dir("cli-curves-refused");
    let out = dir.join("frames");
    let missing = dir.join("no-such-dir").join("hair.usda");
    let cases: [(&[&str], &str); 5] = [
        (&["--curves", "hair.abc"], "Alembic is not written"),
        (&["--curves", "hair.usdc"], "only USD ASCII"),
        (&["--curves", "hair"], "give a file ending in .usda"),
        (&["--curves", "hair.usda", "--resume"], "--resume"),
        (&["--curves", s(&missing)], "no-such-dir does not exist"),
    ];
    for (extra, says) in cases {
        let args = [
            &["render", "--frames", "1", "--width", "32", "--height", "32"][..],
            &["--out", s(&out)],
            extra,
        ]
        .concat();
        let o = wisp(&args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {e}");
        assert!(e.contains("--curves"), "{extra:?}: {e}");
        assert!(e.contains(says), "{extra:?}: {e}");
        assert!(!e.contains("panicked"), "{e}");
    }
    assert!(!missing.parent().unwrap().exists());
}
