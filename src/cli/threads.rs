//! `--threads`: the worker threads of the parallel stages (one global rayon pool). The output
//! does not depend on their number; more than [`THREADS_PER_CORE`] per core are reduced to
//! that, with a warning.

use super::AppError;

/// Most worker threads per core. More only slows wisp down, and faster than linearly: on 2
/// cores, 2 frames at 160×120 took 0.25 s with 2 threads, 1.0 s with 256, 4.8 s with 512 and
/// 36 s with 1,000.
pub const THREADS_PER_CORE: usize = 4;

/// The most worker threads accepted on this machine.
pub fn max_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get()) * THREADS_PER_CORE
}

/// Starts the global pool with the `asked` number of threads (reduced to [`max_threads`]);
/// without it, rayon's default (one per core) stays.
pub fn start_pool(asked: Option<u32>) -> Result<(), AppError> {
    let Some(asked) = asked else {
        return Ok(());
    };
    let n = (asked as usize).min(max_threads());
    if n < asked as usize {
        eprintln!(
            "wisp: warning: --threads {asked} is more than {THREADS_PER_CORE} per core ({} cores here), which only slows wisp down; using {n}",
            max_threads() / THREADS_PER_CORE
        );
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build_global()
        .map_err(|e| AppError::other(anyhow::anyhow!("cannot start {n} threads: {e}")))
}
