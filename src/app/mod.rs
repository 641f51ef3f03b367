//! Command-line edge: argument parsing, degrees and file formats live here, nowhere deeper.
//!
//! Exit codes: 0 success, 2 bad input (flags or files), 1 any other failure.

pub mod fiber_cmd;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser, Debug)]
#[command(
    name = "wisp",
    version,
    about = "Animate and render human hair on the CPU"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Inspect the fibre scattering model: evaluate, tabulate, plot.
    Fiber(fiber_cmd::FiberArgs),
}

/// An error with its exit code: 2 for bad input, 1 otherwise.
#[derive(Debug)]
pub struct AppError {
    pub code: u8,
    pub error: anyhow::Error,
}

impl AppError {
    pub fn input(error: impl Into<anyhow::Error>) -> Self {
        Self {
            code: 2,
            error: error.into(),
        }
    }
    pub fn other(error: impl Into<anyhow::Error>) -> Self {
        Self {
            code: 1,
            error: error.into(),
        }
    }
}

/// Parses the command line and runs it; errors go to stderr with their exit code.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    let result = match cli.command {
        Command::Fiber(args) => fiber_cmd::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("wisp: error: {:#}", e.error);
            ExitCode::from(e.code)
        }
    }
}
