//! Columns in parallel: fixed tasks of [`COLUMNS_PER_TASK`] columns, each handed the disjoint
//! `&mut` runs that its columns own in buffers laid out column after column (offsets
//! `starts[c]..starts[c + 1]`). The buffers are split in two at a task boundary and the halves
//! run with `rayon::join` until one task is left, so the split is safe code and allocates
//! nothing. A column's result depends on its own run only, so it is the same for any thread
//! count. The hair fills few of the columns, so a task is one job (`raster::lines` on rayon's
//! splitting).

/// Columns sorted, counted or merged by one parallel task.
pub(super) const COLUMNS_PER_TASK: usize = 1024;

/// The first column of task `task`.
pub(super) fn task_start(task: usize) -> usize {
    task * COLUMNS_PER_TASK
}

/// Buffers laid out column after column that split at an offset: a slice, or a pair of them
/// with the same layout.
pub(super) trait Runs: Send + Sized {
    /// The parts before and after offset `at`.
    fn split_runs(self, at: usize) -> (Self, Self);
}

impl<T: Send> Runs for &mut [T] {
    fn split_runs(self, at: usize) -> (Self, Self) {
        self.split_at_mut(at)
    }
}

impl<A: Runs, B: Runs> Runs for (A, B) {
    fn split_runs(self, at: usize) -> (Self, Self) {
        let (a0, a1) = self.0.split_runs(at);
        let (b0, b1) = self.1.split_runs(at);
        ((a0, b0), (a1, b1))
    }
}

/// Calls `f(c, runs of column c)` for every column `c` of `starts` (one more entry than the
/// columns, non-decreasing, from 0), in parallel over tasks. `runs` hold at least
/// `starts[last]` items; a bad layout panics.
pub(super) fn for_each_column<R: Runs>(runs: R, starts: &[u32], f: &(impl Fn(usize, R) + Sync)) {
    let cols = starts.len().saturating_sub(1);
    columns(runs, starts, 0, cols, f);
}

/// [`for_each_column`] over columns `c0..c1`, whose runs start at `starts[c0]`.
fn columns<R: Runs>(runs: R, starts: &[u32], c0: usize, c1: usize, f: &(impl Fn(usize, R) + Sync)) {
    let tasks = (c1 - c0).div_ceil(COLUMNS_PER_TASK);
    if tasks > 1 {
        let mid = c0 + tasks / 2 * COLUMNS_PER_TASK;
        let (left, right) = runs.split_runs(run_len(starts, c0, mid));
        rayon::join(
            || columns(left, starts, c0, mid, f),
            || columns(right, starts, mid, c1, f),
        );
        return;
    }
    let mut rest = runs;
    for c in c0..c1 {
        let (run, after) = rest.split_runs(run_len(starts, c, c + 1));
        f(c, run);
        rest = after;
    }
}

/// Items of columns `c0..c1`: `starts[c1] − starts[c0]`, which must not be negative.
fn run_len(starts: &[u32], c0: usize, c1: usize) -> usize {
    let len = starts[c1].checked_sub(starts[c0]);
    len.expect("column offsets do not decrease") as usize
}
