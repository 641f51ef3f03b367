//! The command-line tests: each runs the built `wisp` binary (`CARGO_BIN_EXE_wisp`) as a user
//! or a script would, one module per area, in one binary. Run an area with its module path as
//! the filter: `cargo test --release --test cli -- scene::`.
//!
//! The library tests are in `tests/lib/`.

#[path = "../support/mod.rs"]
mod support;

mod basics;
mod deploy;
mod export;
mod fiber;
mod hostile;
mod render_formats;
mod scene;
mod window;
