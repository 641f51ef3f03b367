//! The live window (`wisp play`) under a virtual X server: it opens, runs frames with its
//! readout drawn and closes cleanly. No keys are pressed (the mouse camera and the keys are
//! unit-tested in src/cli/play_cmd). Skipped, with a message, where `xvfb-run` is not
//! installed (`.ci/run` installs it).

use std::path::Path;
use std::process::Command;

fn xvfb_missing() -> bool {
    if Command::new("xvfb-run").arg("--help").output().is_err() {
        println!("skipped: xvfb-run is not installed (apt-get install xvfb xauth)");
        return true;
    }
    false
}

/// `wisp play --frames N --width S --height S --screenshot shot`, under Xvfb; panics with
/// stderr unless it exits 0.
fn play(frames: u32, size_px: u32, shot: &Path) {
    let _ = std::fs::remove_file(shot);
    // minifb needs a 24-bit screen (it crashes on a 16-bit one).
    let out = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x720x24"])
        .arg(env!("CARGO_BIN_EXE_wisp"))
        .args(["play", "--frames", &frames.to_string()])
        .args([
            "--width",
            &size_px.to_string(),
            "--height",
            &size_px.to_string(),
        ])
        .arg("--screenshot")
        .arg(shot)
        .output()
        .expect("run xvfb-run");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "wisp play failed under Xvfb: {stderr}"
    );
}

#[test]
fn play_runs_in_a_window_under_xvfb() {
    if xvfb_missing() {
        return;
    }
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("window");
    std::fs::create_dir_all(&dir).unwrap();
    let shot = dir.join("play.png");
    play(15, 240, &shot);
    let bytes = std::fs::read(&shot).expect("the last frame shown was written");
    assert_eq!(&bytes[1..4], b"PNG");
    // The last frame shown has hair and a head on it: decode and count non-background pixels.
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let px = &buf[..info.buffer_size()];
    let bg = [px[0], px[1], px[2]];
    let drawn = px.chunks(3).filter(|c| c != &bg).count();
    assert!(
        drawn > 240 * 240 / 20,
        "only {drawn} pixels differ from the background"
    );
    // The screenshot is the engine's frame, without the readout: the readout's box (from
    // 4 px in) would darken the background there to 31%.
    let bg_linear = wisp::engine::EngineConfig::default().scene.background;
    let bg_srgb = bg_linear.to_array().map(wisp::output::linear_to_srgb8);
    for (x, y) in [(0, 0), (5, 5), (10, 6), (6, 10)] {
        let i = 3 * (y * 240 + x);
        assert_eq!(px[i..i + 3], bg_srgb, "pixel ({x}, {y})");
    }
}

/// The smallest window the flags allow, 16 × 16: the readout is larger than the window and is
/// clipped to it (a write outside the buffer would panic).
#[test]
fn play_runs_in_the_smallest_window() {
    if xvfb_missing() {
        return;
    }
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("window");
    std::fs::create_dir_all(&dir).unwrap();
    let shot = dir.join("play16.png");
    play(4, 16, &shot);
    let bytes = std::fs::read(&shot).expect("the last frame shown was written");
    let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (16, 16));
}
