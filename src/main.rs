//! The `wisp` command line: see `wisp --help`.
fn main() -> std::process::ExitCode {
    wisp::app::main()
}
