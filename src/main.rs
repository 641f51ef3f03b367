//! The `wisp` command line: see `wisp --help`. A thin layer over the `wisp` library: argument
//! parsing (clap), error reporting (anyhow), the window (minifb) and file formats at the edge
//! live here only, so the library carries none of them.

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
