//! The signal dispositions `wisp` sets at its start.
//!
//! A write past the file-size limit (`ulimit -f`) raises SIGXFSZ, whose default action ends
//! the process at once (exit status 153 in a shell) with no word of which file or why.
//! Ignored, the write fails with EFBIG instead, and the output's error path reports it,
//! naming the file, with exit code 1. Setting a disposition takes one libc call, which Rust
//! marks `unsafe`: this is the one module of the binary allowed it (`main.rs` denies it).

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
