//! The live window (`wisp play`) under a virtual X server: it opens, runs frames and closes
//! cleanly. Skipped, with a message, where `xvfb-run` is not installed (`.ci/run` installs it).

use std::process::Command;

#[test]
fn play_runs_in_a_window_under_xvfb() {
    if Command::new("xvfb-run").arg("--help").output().is_err() {
        println!("skipped: xvfb-run is not installed (apt-get install xvfb xauth)");
        return;
    }
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("window");
    std::fs::create_dir_all(&dir).unwrap();
    let shot = dir.join("play.png");
    let _ = std::fs::remove_file(&shot);
    // minifb needs a 24-bit screen (it crashes on a 16-bit one).
    let out = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x720x24"])
        .arg(env!("CARGO_BIN_EXE_wisp"))
        .args([
            "play",
            "--frames",
            "15",
            "--width",
            "240",
            "--height",
            "240",
            "--screenshot",
        ])
        .arg(&shot)
        .output()
        .expect("run xvfb-run");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "wisp play failed under Xvfb: {stderr}"
    );
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
}
