//! The `wisp` command line: see `wisp --help`. A thin layer over the `wisp` library: argument
//! parsing (clap), error reporting (anyhow), the window (minifb) and file formats at the edge
//! live here only, so the library carries none of them.
//!
//! `unsafe` is denied here as in the library; one module allows it: `cli/process.rs`, two libc
//! calls at the start, a signal's disposition and the allocator's thresholds.

#![deny(unsafe_code)]

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
