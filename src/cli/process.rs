//! What `wisp` sets for the whole process at its start: a signal disposition and the
//! allocator's thresholds. Each takes one libc call, which Rust marks `unsafe`: this is the
//! one module of the binary allowed it (`main.rs` denies it).
//!
//! **SIGXFSZ.** A write past the file-size limit (`ulimit -f`) raises SIGXFSZ, whose default
//! action ends the process at once (exit status 153 in a shell) with no word of which file or
//! why. Ignored, the write fails with EFBIG instead, and the output's error path reports it,
//! naming the file, with exit code 1.
//!
//! **The allocator.** glibc's malloc serves a block of 32 MiB or more (less, before its
//! dynamic threshold has grown) with its own `mmap` and returns it at `free`, and trims the
//! heap's top back to the system: a frame's large buffers (the light paths' bins, about 56 MB
//! on the smooth dance at `final`; the cells, the records) are then faulted in page by page,
//! every frame. Kept in the heap, the next frame reuses them: `final`'s frame 9% faster on the
//! smooth dance (BENCHMARKS.md, "Allocator"), with the same peak memory, since the frames
//! need the same buffers again.

#![allow(unsafe_code)]

/// Ignores SIGXFSZ for the rest of the process (see the module doc). Call it before any
/// thread starts.
pub fn ignore_file_size_limit_signal() {
    #[cfg(unix)]
    // SAFETY: `signal` with `SIG_IGN` installs no handler, so no code of ours runs in signal
    // context; it is called once, before any other thread exists; SIGXFSZ is a valid signal
    // number on every Unix.
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
}

/// Keeps freed blocks of any size in glibc's heap for reuse (see the module doc). Call it
/// before any thread starts. A no-op where the C library is not glibc.
pub fn keep_freed_memory_for_reuse() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: `mallopt` only changes two of malloc's tunables (valid parameter numbers, values
    // in range); it is called once, before any other thread exists or allocates.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, i32::MAX);
        libc::mallopt(libc::M_TRIM_THRESHOLD, i32::MAX);
    }
}
