//! The library tests' global allocator: the system allocator, counting per thread.
//!
//! Two kinds of test read it, and both count per thread so that the other tests of this
//! binary, running at the same time, cannot disturb them:
//! - a bounded run (`bounded.rs`) arms its case's thread with a cap on the bytes it holds and
//!   reads that thread's peak;
//! - the simulator's no-allocation test (`sim_alloc.rs`) counts the allocations made on the
//!   threads it watches (those of its own rayon pool) while [`ARMED`].

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

// ---------------------------------------------------------------------------------------------
// Allocations on watched threads.

/// While true, allocations on watched threads add to [`ALLOCATIONS`].
pub static ARMED: AtomicBool = AtomicBool::new(false);
/// Allocations made on watched threads while [`ARMED`].
pub static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    static WATCHED: Cell<bool> = const { Cell::new(false) };
}

/// Marks the calling thread as watched (a rayon pool's `start_handler`).
pub fn watch_this_thread() {
    WATCHED.with(|w| w.set(true));
}

/// Adds one allocation to [`ALLOCATIONS`] when armed and on a watched thread.
fn count_allocation() {
    if ARMED.load(Ordering::Relaxed) && WATCHED.try_with(Cell::get).unwrap_or(false) {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
    }
}

// ---------------------------------------------------------------------------------------------
// Memory: live bytes per thread, with a hard cap while a case runs.

thread_local! {
    static LIVE: Cell<isize> = const { Cell::new(0) };
    static PEAK: Cell<isize> = const { Cell::new(0) };
    static CAP: Cell<isize> = const { Cell::new(isize::MAX) };
}

/// Counts the bytes each thread holds, and the allocations of watched threads. A thread armed
/// with [`arm`] that asks for more than its cap gets a null pointer, which aborts the test
/// binary with "memory allocation of N bytes failed": a case that tries to allocate gigabytes
/// fails loudly instead of swapping the machine.
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
        count_allocation();
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
        count_allocation();
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
        count_allocation();
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
