//! Must-not-panic machinery shared by the `hostile_*` tests: a seeded generator, a counting
//! allocator with a per-thread cap, a runner that bounds each case in time and memory, input
//! mutators and the table of input formats.
//!
//! A new input format (a groom file; the simulation cache did) plugs in with one [`formats::Format`] entry:
//! a name, valid seed files and a loader that returns accepted or refused (see `formats.rs`).
#![allow(dead_code)]

pub mod cache;
pub mod formats;
pub mod mutate;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// Deterministic generator: a case is reproduced from its seed alone.
pub struct Rng(wisp::hairstyle::SplitMix64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(wisp::hairstyle::SplitMix64::new(seed))
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }
    /// Uniform in [0, n) (0 when n is 0).
    pub fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next_u64() % n as u64) as usize
        }
    }
    pub fn chance(&mut self, p: f64) -> bool {
        ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64) < p
    }
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

// ---------------------------------------------------------------------------------------------
// Memory: live bytes per thread, with a hard cap while a case runs.

thread_local! {
    static LIVE: Cell<isize> = const { Cell::new(0) };
    static PEAK: Cell<isize> = const { Cell::new(0) };
    static CAP: Cell<isize> = const { Cell::new(isize::MAX) };
}

/// Counts the bytes each thread holds. A thread armed with [`arm`] that asks for more than its
/// cap gets a null pointer, which aborts the test binary with "memory allocation of N bytes
/// failed": a case that tries to allocate gigabytes fails loudly instead of swapping the
/// machine.
pub struct Counting;

/// Adds `delta` to this thread's live bytes; false (nothing added) when it would pass the cap.
fn account(delta: isize) -> bool {
    LIVE.try_with(|live| {
        let v = live.get() + delta;
        if delta > 0 && v > CAP.try_with(Cell::get).unwrap_or(isize::MAX) {
            return false;
        }
        live.set(v);
        let _ = PEAK.try_with(|p| p.set(p.get().max(v)));
        true
    })
    .unwrap_or(true)
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !account(layout.size() as isize) {
            return std::ptr::null_mut();
        }
        let p = unsafe { System.alloc(layout) };
        if p.is_null() {
            account(-(layout.size() as isize));
        }
        p
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !account(layout.size() as isize) {
            return std::ptr::null_mut();
        }
        let p = unsafe { System.alloc_zeroed(layout) };
        if p.is_null() {
            account(-(layout.size() as isize));
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        account(-(layout.size() as isize));
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let delta = new_size as isize - layout.size() as isize;
        if !account(delta) {
            return std::ptr::null_mut();
        }
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if p.is_null() {
            account(-delta);
        }
        p
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Starts counting this thread from zero, refusing allocations beyond `cap_bytes` live.
pub fn arm(cap_bytes: usize) {
    LIVE.with(|l| l.set(0));
    PEAK.with(|p| p.set(0));
    CAP.with(|c| c.set(cap_bytes as isize));
}

/// Stops refusing; returns the peak live bytes since [`arm`].
pub fn disarm() -> usize {
    CAP.with(|c| c.set(isize::MAX));
    PEAK.with(|p| p.get().max(0) as usize)
}

/// Peak live bytes of this thread since [`arm`] (for tests that run on their own thread).
pub fn peak_bytes() -> usize {
    PEAK.with(|p| p.get().max(0) as usize)
}

// ---------------------------------------------------------------------------------------------
// Running one case.

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

/// Directory for this test binary's files under target/.
pub fn scratch_dir(name: &str) -> std::path::PathBuf {
    let d = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("create scratch dir");
    d
}
