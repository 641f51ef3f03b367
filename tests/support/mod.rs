//! Helpers that both test binaries compile: the library tests (`tests/lib/main.rs`) and the
//! command-line tests (`tests/cli/main.rs`) each declare this module with
//! `#[path = "../support/mod.rs"]`. Cargo builds one crate per test binary, so code that two
//! binaries share is either a module each compiles or a separate crate; a crate depending on
//! `wisp` as a dev-dependency would make even `cargo test --lib` build the library twice.
//!
//! What lives here is only what both need (the switch to full-size tests, scratch folders and
//! the hostile-input generators); helpers of one binary live in that binary. Each binary uses a
//! part of the hostile inputs (the command line neither loads nor sizes them), so the rest is
//! dead code there.
#![allow(dead_code)]

pub mod hostile;
pub mod rig_variants;
pub mod strand_files;

/// True when `WISP_FULL_TESTS=1`: the slow accuracy and simulation tests then run at their
/// full size (each says it in its doc comment) instead of the reduced size CI runs.
pub fn full_size() -> bool {
    std::env::var_os("WISP_FULL_TESTS").is_some_and(|v| v == "1")
}

/// Directory for this test binary's files under target/.
pub fn scratch_dir(name: &str) -> std::path::PathBuf {
    let d = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("create scratch dir");
    d
}

/// Writes `hairstyles/smooth.json` cut down to 40 wisps of 8 strands of 10 fibres (320 strands,
/// a fifth of the default's strands on a third of its fibres) into `dir`, and returns its path:
/// a scene that runs every part of a command in a fraction of the time, for tests that check
/// what a command writes rather than what the default hair looks like.
pub fn small_hairstyle(dir: &std::path::Path) -> std::path::PathBuf {
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("hairstyles/smooth.json");
    let mut style: serde_json::Value =
        serde_json::from_slice(&std::fs::read(src).expect("read smooth.json")).expect("JSON");
    style["wisps"]["count"] = 40.into();
    style["wisps"]["strands_per_wisp"] = 8.into();
    style["strands"]["fibers_per_strand"] = 10.into();
    let path = dir.join("small.json");
    std::fs::write(&path, serde_json::to_vec_pretty(&style).expect("JSON")).expect("write");
    path
}
