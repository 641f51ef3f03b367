//! `wisp::export::usd`: the curves file of three dance frames parses back (with the small
//! `.usda` reader below) as the engine's render strands, bit for bit, at the frames' time
//! codes; an unfinished or refused file leaves nothing under its name. The command's flag
//! (`render --curves`) is tested in `tests/cli/render_formats.rs`, and `tools/usd/check_usda.py`
//! reads the file with Pixar's own reader.

use glam::Vec3;
use std::path::Path;
use wisp::engine::{Engine, EngineConfig};
use wisp::export::usd::{CurveShape, CurvesLook, TimeCodes, UsdCurvesWriter};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

/// What the test reads back from a `.usda` file wisp wrote.
struct Parsed {
    start: f64,
    end: f64,
    per_second: f64,
    counts: Vec<usize>,
    /// Each points sample: time code and points.
    samples: Vec<(f64, Vec<Vec3>)>,
    widths: Vec<f32>,
    colors: Vec<Vec3>,
}

/// The number after `key = ` on the line that starts with it.
fn metadata(text: &str, key: &str) -> f64 {
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with(&format!("{key} = ")))
        .unwrap_or_else(|| panic!("no {key}"));
    line.split(" = ").nth(1).unwrap().trim().parse().unwrap()
}

/// The floats of `(a, b, c), (d, e, f)…` as points.
fn vec3s(list: &str) -> Vec<Vec3> {
    let numbers: Vec<f32> = list
        .split(['(', ')', ','])
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap_or_else(|_| panic!("not a float: {s}")))
        .collect();
    assert_eq!(numbers.len() % 3, 0);
    numbers.chunks(3).map(Vec3::from_slice).collect()
}

/// The inside of the `[...]` on the line that starts with `start`.
fn array_after<'a>(text: &'a str, start: &str) -> &'a str {
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with(start))
        .unwrap_or_else(|| panic!("no line starting with {start}"));
    let open = line.find("= [").unwrap();
    let close = line.rfind(']').unwrap();
    &line[open + 3..close]
}

fn parse(path: &Path) -> Parsed {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.starts_with("#usda 1.0\n"));
    assert!(text.contains("def BasisCurves \"hair\""));
    assert!(text.contains("uniform token type = \"linear\""));
    assert_eq!(metadata(&text, "metersPerUnit"), 1.0);
    assert!(text.contains("upAxis = \"Y\""));
    let counts = array_after(&text, "int[] curveVertexCounts")
        .split(", ")
        .map(|s| s.parse().unwrap())
        .collect();
    // The points' samples: the lines between `points.timeSamples = {` and its `}`.
    let body = text
        .split("point3f[] points.timeSamples = {\n")
        .nth(1)
        .unwrap();
    let body = &body[..body.find("\n    }\n").unwrap()];
    let samples = body
        .lines()
        .map(|l| {
            let (t, rest) = l.trim().split_once(": ").unwrap();
            let rest = rest.strip_prefix('[').unwrap().strip_suffix("],").unwrap();
            (t.parse().unwrap(), vec3s(rest))
        })
        .collect();
    Parsed {
        start: metadata(&text, "startTimeCode"),
        end: metadata(&text, "endTimeCode"),
        per_second: metadata(&text, "timeCodesPerSecond"),
        counts,
        samples,
        widths: array_after(&text, "float[] widths")
            .split(", ")
            .map(|s| s.parse().unwrap())
            .collect(),
        colors: vec3s(array_after(&text, "color3f[] primvars:displayColor")),
    }
}

/// 40 wisps of 8 strands: 320 curves, a few megabytes for three frames.
fn small_engine() -> Engine {
    let mut style = Hairstyle::default_smooth();
    style.wisps.count = 40;
    style.wisps.strands_per_wisp = 8;
    Engine::new(style, Motion::default_dance(), EngineConfig::sized(64, 64))
}

#[test]
fn three_dance_frames_read_back_as_the_engine_strands() {
    let dir = crate::support::scratch_dir("usd-curves");
    let path = dir.join("hair.usda");
    let mut engine = small_engine();
    // Frames 30 to 32 of a run at 24 fps starting at 1.25 s: t = 1.25 + i / 24.
    let (fps, start_s, first) = (24.0, 1.25, 30u32);
    let time_code = |i: u32| start_s * fps + f64::from(i);
    let shape = CurveShape {
        curves: engine.strands().strand_count(),
        points_per_curve: engine.strands().points_per_strand,
    };
    let time = TimeCodes {
        start: time_code(first),
        end: time_code(first + 2),
        per_second: fps,
    };
    let mut writer = UsdCurvesWriter::create(&path, shape, time, "test \"3 frames\"").unwrap();
    let mut expected = Vec::new();
    for i in first..first + 3 {
        engine.advance(start_s + f64::from(i) / fps);
        engine.render();
        writer
            .write_sample(time_code(i), &engine.strands().positions)
            .unwrap();
        expected.push(engine.strands().positions.clone());
        assert!(!path.exists(), "the file is named only once finished");
    }
    engine.shade();
    let (widths, colors) = (engine.widths_m().to_vec(), engine.colors().to_vec());
    let look = CurvesLook {
        widths_m: &widths,
        colors: Some(&colors),
    };
    let bytes = writer.finish(look).unwrap();
    assert_eq!(bytes, std::fs::metadata(&path).unwrap().len());
    assert!(!dir.join("hair.usda.tmp").exists());

    let parsed = parse(&path);
    // 320 curves of the strands' points each; their sum is every sample's point count.
    assert_eq!(parsed.counts.len(), 320);
    assert!(parsed.counts.iter().all(|c| *c == shape.points_per_curve));
    let total: usize = parsed.counts.iter().sum();
    assert_eq!(parsed.samples.len(), 3);
    // 30 + 1.25 · 24 = 60: time codes 60, 61, 62 at 24 a second.
    assert_eq!(
        (parsed.start, parsed.end, parsed.per_second),
        (60.0, 62.0, 24.0)
    );
    for (k, (t, points)) in parsed.samples.iter().enumerate() {
        assert_eq!(*t, 60.0 + k as f64);
        assert_eq!(points.len(), total);
        // Shortest round-trip digits: the floats read back bit for bit.
        assert_eq!(points, &expected[k], "sample {k}");
    }
    // The hair moves in the dance, so the samples are not one frame repeated.
    assert_ne!(expected[0], expected[2]);
    assert_eq!(parsed.widths, widths);
    assert_eq!(parsed.colors, colors);
    assert!(
        parsed.colors.iter().all(|c| c.max_element() > 0.0),
        "every point shaded"
    );
}

#[test]
fn an_unfinished_or_refused_file_leaves_the_old_one_alone() {
    let dir = crate::support::scratch_dir("usd-curves-refused");
    let path = dir.join("hair.usda");
    std::fs::write(&path, "old").unwrap();
    let shape = CurveShape {
        curves: 2,
        points_per_curve: 3,
    };
    let time = TimeCodes {
        start: 0.0,
        end: 1.0,
        per_second: 30.0,
    };
    let points = vec![Vec3::ONE; 6];
    // Dropped after one of two samples: the export was interrupted.
    let mut w = UsdCurvesWriter::create(&path, shape, time, "").unwrap();
    w.write_sample(0.0, &points).unwrap();
    assert!(dir.join("hair.usda.tmp").exists());
    drop(w);
    assert!(!dir.join("hair.usda.tmp").exists());
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");

    let mut w = UsdCurvesWriter::create(&path, shape, time, "").unwrap();
    let wrong_count = w.write_sample(0.0, &points[..5]).unwrap_err().to_string();
    assert!(
        wrong_count.contains("5 points, the curves have 6"),
        "{wrong_count}"
    );
    let mut nan = points.clone();
    nan[4].y = f32::NAN;
    let not_finite = w.write_sample(0.0, &nan).unwrap_err().to_string();
    assert!(not_finite.contains("point 4 is not finite"), "{not_finite}");
    w.write_sample(0.0, &points).unwrap();
    let backwards = w.write_sample(0.0, &points).unwrap_err().to_string();
    assert!(backwards.contains("does not come after"), "{backwards}");
    // One sample of the two the header promised: finish refuses and removes the file.
    let widths = [0.001f32; 6];
    let look = CurvesLook {
        widths_m: &widths,
        colors: None,
    };
    let short = w.finish(look).unwrap_err().to_string();
    assert!(
        short.contains("span 0 to 0, the header says 0 to 1"),
        "{short}"
    );
    assert!(!dir.join("hair.usda.tmp").exists());
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");

    let one_point = CurveShape {
        curves: 1,
        points_per_curve: 1,
    };
    let e = UsdCurvesWriter::create(&path, one_point, time, "")
        .err()
        .unwrap();
    assert!(e.to_string().contains("at least 2 points"), "{e}");
}
