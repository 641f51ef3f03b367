//! Bounded runs for the must-not-panic tests: a case runs on its own thread with the memory cap
//! of `alloc.rs` armed and a time limit (a hang detector, not a speed test), and reports its
//! value, its peak heap and its time.

use std::sync::mpsc;
use std::time::{Duration, Instant};

use crate::alloc::{arm, disarm};

/// Hard per-case memory cap (the abort threshold); cases are asserted against tighter bounds.
pub const HARD_CAP_BYTES: usize = 2 << 30;

/// What a finished case did.
#[derive(Debug)]
pub struct Report<T> {
    pub value: T,
    pub peak_bytes: usize,
    pub elapsed: Duration,
}

/// Runs `f` on its own thread with the memory cap armed. `Err` when it panicked or did not
/// finish within `limit` (the thread is then left behind; the test fails anyway).
pub fn run_bounded<T, F>(f: F, limit: Duration) -> Result<Report<T>, String>
where
    T: Send + 'static,
    F: FnOnce() -> T + Send + 'static,
{
    let (tx, rx) = mpsc::channel();
    let handle = std::thread::Builder::new()
        .name("hostile-case".into())
        .spawn(move || {
            arm(HARD_CAP_BYTES);
            let start = Instant::now();
            let value = f();
            let elapsed = start.elapsed();
            let peak_bytes = disarm();
            let _ = tx.send(Report {
                value,
                peak_bytes,
                elapsed,
            });
        })
        .map_err(|e| format!("cannot spawn a case thread: {e}"))?;
    match rx.recv_timeout(limit) {
        Ok(report) => {
            let _ = handle.join();
            Ok(report)
        }
        Err(mpsc::RecvTimeoutError::Timeout) => Err(format!(
            "did not finish within {} s (a hang)",
            limit.as_secs_f64()
        )),
        Err(mpsc::RecvTimeoutError::Disconnected) => {
            let payload = handle.join().err();
            let msg = payload
                .as_ref()
                .and_then(|p| {
                    p.downcast_ref::<String>()
                        .cloned()
                        .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                })
                .unwrap_or_else(|| "(no message)".into());
            Err(format!("panicked: {msg}"))
        }
    }
}
