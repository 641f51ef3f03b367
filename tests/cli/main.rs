//! The command-line tests: each runs the built `wisp` binary (`CARGO_BIN_EXE_wisp`) as a user
//! or a script would, one module per area, in one binary. Run an area with its module path as
//! the filter: `cargo test --release --test cli -- scene::`.
//!
//! The library tests are in `tests/lib/`.

#[path = "../support/mod.rs"]
mod support;

mod basics;
mod curves;
mod deploy;
mod export;
mod fiber;
mod groom_formats;
mod hostile;
mod hostile_output;
mod hostile_scene;
mod hostile_work_flags;
mod quality;
mod render_formats;
mod scene;
mod window;

use std::process::{Command, Output};

/// Runs the built `wisp` with `args` and returns what it printed and its exit status.
fn wisp(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wisp"))
        .args(args)
        .output()
        .expect("run wisp")
}

/// What a run printed on stderr, as text.
fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}
