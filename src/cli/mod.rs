//! The `wisp` command line: the commands, their flags and how the flags become a run, and the
//! messages and exit codes a user sees. Argument parsing (clap), error reporting (anyhow),
//! degrees and file formats live here, nowhere deeper.
//!
//! ```text
//! mod.rs          the commands and the dispatch
//! scene_args/     the flags of a run -> hairstyle, motion, EngineConfig (one file per part)
//! *_cmd           one command each
//! parse           the flags' number and vector parsers
//! shard, threads  frame ranges and shards; the worker pool
//! errors, terminal, output_file   exit codes; stdout, and stderr printed safely; output paths
//! process         SIGXFSZ ignored (a write over `ulimit -f` is an error naming the file);
//!                 freed memory kept for the next frame
//! ```
//!
//! Exit codes: 0 success, 2 bad input (flags, files, output paths, or a run over its memory or
//! work budget), 1 any other failure, 141 when standard output was closed early (`wisp … |
//! head`: the reader had what it wanted; wisp stops quietly, as a program killed by SIGPIPE).
//!
//! Every flag's help is one line: what it sets, its unit and range, its default. What a flag
//! does in depth is in the user guide (docs/GUIDE.md).

#[macro_use]
mod terminal;

pub mod accuracy_cmd;
pub mod bench_cmd;
pub mod cache_cmd;
pub mod export_cmd;
pub mod fiber_cmd;
pub mod play_cmd;
pub mod render_cmd;
pub mod shard;

mod errors;
mod output_file;
mod parse;
mod process;
mod scene_args;
mod threads;

pub use errors::AppError;
pub use output_file::check_output_file;
pub use parse::*;
pub use scene_args::{ImportedHair, SceneArgs, engine};
pub use terminal::printable;
pub use threads::{THREADS_PER_CORE, max_threads};

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser, Debug)]
#[command(
    name = "wisp",
    version,
    about = "Animate and render human hair on the CPU"
)]
pub struct Cli {
    /// Worker threads, ≤ 4 per core (same output) [default: all cores]
    #[arg(long, global = true, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub threads: Option<u32>,
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render the dance to image frames (PNG, 16-bit PNG or OpenEXR)
    #[command(allow_negative_numbers = true)]
    Render(render_cmd::RenderArgs),
    /// Simulate the hair once into a cache file, for `render --cache`
    #[command(allow_negative_numbers = true)]
    Simulate(cache_cmd::SimulateArgs),
    /// Play the dance live in a window
    #[command(allow_negative_numbers = true)]
    Play(play_cmd::PlayArgs),
    /// Time the stages over thread counts, and speed against error over map resolutions
    #[command(allow_negative_numbers = true)]
    Bench(bench_cmd::BenchArgs),
    /// Inspect the fibre scattering model: evaluate, tabulate, plot
    #[command(allow_negative_numbers = true)]
    Fiber(fiber_cmd::FiberArgs),
    /// Measure the light map against exact ray shooting, over map resolutions
    #[command(allow_negative_numbers = true)]
    Accuracy(accuracy_cmd::AccuracyArgs),
    /// Write one frame as a path tracer's reference scene, with wisp's own EXR of it
    #[command(allow_negative_numbers = true)]
    Export(export_cmd::ExportArgs),
}

/// Parses the command line and runs it; errors go to stderr with their exit code.
pub fn main() -> ExitCode {
    process::ignore_file_size_limit_signal();
    process::keep_freed_memory_for_reuse();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if e.use_stderr() => {
            // Plain text through the safe `eprint!`: clap echoes the value it refused.
            eprint!("{}", e.render());
            return ExitCode::from(2);
        }
        Err(e) => {
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
    };
    match threads::start_pool(cli.threads).and_then(|()| run(cli.command)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("wisp: error: {:#}", e.error);
            ExitCode::from(e.code)
        }
    }
}

/// Runs a command.
fn run(command: Command) -> Result<(), AppError> {
    match command {
        Command::Render(args) if args.cache.is_some() => cache_cmd::render_from_cache(args),
        Command::Render(args) => render_cmd::run(args),
        Command::Simulate(args) => cache_cmd::simulate(args),
        Command::Play(args) => play_cmd::run(args),
        Command::Bench(args) => bench_cmd::run(args),
        Command::Fiber(args) => fiber_cmd::run(args),
        Command::Accuracy(args) => accuracy_cmd::run(args),
        Command::Export(args) => export_cmd::run(args),
    }
}
