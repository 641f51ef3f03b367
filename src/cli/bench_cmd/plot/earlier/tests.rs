use super::read_report;
use wisp::quality::Quality;

fn write(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("wisp-plot-earlier-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// A report's levels come back with the total of their most threads and their errors; the
/// truths of the comparisons sit at 0.
#[test]
fn a_report_reads_back_as_its_scene() {
    let path = write(
        "ok.json",
        r#"{"hairstyle": "curly", "quality": [
            {"level": "preview", "timings": [{"threads": 1, "total_ms": 200.0},
                                             {"threads": 2, "total_ms": 120.0}],
             "vs_reference": {"mean_rel_luminance": 0.26}, "vs_final": {"mean_rel_luminance": 0.25}},
            {"level": "final", "timings": [{"threads": 2, "total_ms": 260.0}],
             "vs_reference": {"mean_rel_luminance": 0.1}},
            {"level": "reference", "timings": [{"threads": 2, "total_ms": 4000.0}]}]}"#,
    );
    let scene = read_report(&path).unwrap();
    assert_eq!(scene.name, "curly");
    let p = &scene.points;
    assert_eq!(p.len(), 3);
    assert_eq!((p[0].level, p[0].ms), (Quality::Preview, 120.0));
    assert_eq!((p[0].vs_reference, p[0].vs_final), (Some(0.26), Some(0.25)));
    assert_eq!((p[1].vs_reference, p[1].vs_final), (Some(0.1), Some(0.0)));
    assert_eq!((p[2].vs_reference, p[2].vs_final), (Some(0.0), None));
}

/// Not a report: the message names the file and the field.
#[test]
fn a_file_that_is_no_report_is_refused_by_field() {
    for (name, text, field) in [
        ("nojson.json", "{", "not JSON"),
        ("noname.json", r#"{"quality": []}"#, "`hairstyle`"),
        ("noquality.json", r#"{"hairstyle": "smooth"}"#, "`quality`"),
        (
            "badlevel.json",
            r#"{"hairstyle": "s", "quality": [{"level": "fast", "timings": []}]}"#,
            "quality[0].level",
        ),
        (
            "badms.json",
            r#"{"hairstyle": "s", "quality": [{"level": "final", "timings": [{"threads": 2, "total_ms": -1}]}]}"#,
            "quality[0].timings",
        ),
        (
            "baderr.json",
            r#"{"hairstyle": "s", "quality": [{"level": "final", "timings": [{"threads": 2, "total_ms": 1}],
                "vs_reference": {"mean_rel_luminance": "x"}}]}"#,
            "quality[0].vs_reference.mean_rel_luminance",
        ),
    ] {
        let path = write(name, text);
        let Err(e) = read_report(&path) else {
            panic!("{name} was accepted");
        };
        let msg = format!("{:#}", e.error);
        assert!(msg.contains(name) && msg.contains(field), "{name}: {msg}");
        assert_eq!(e.code, 2);
    }
    let missing = std::env::temp_dir().join("wisp-plot-earlier-none/absent.json");
    assert!(read_report(&missing).is_err());
}
