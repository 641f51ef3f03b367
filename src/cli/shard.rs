//! Frame ranges: the most frames an export writes, and `--shard I/N`, one of N contiguous
//! blocks of a render's frames, so N machines (or processes) render a cache's frames once
//! each between them.

/// Most frames one export writes (`--frames`, and the default of one loop of the clip); also
/// the most shards.
pub const MAX_FRAMES: u32 = 100_000;

/// One of N contiguous blocks of frames (`--shard I/N`, 1-based).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which block, 1..=count.
    pub index: u32,
    /// How many blocks.
    pub count: u32,
}

impl Shard {
    /// The frames of this block of `range`: block I of N is [⌊(I−1)·L/N⌋, ⌊I·L/N⌋) from the
    /// range's start (L frames), so blocks differ in length by at most one frame and together
    /// hold each frame once. More shards than frames leave some blocks empty.
    pub fn block(&self, range: std::ops::Range<u32>) -> std::ops::Range<u32> {
        let len = range.len() as u64;
        let at = |k: u32| range.start + (k as u64 * len / self.count as u64) as u32;
        at(self.index - 1)..at(self.index)
    }
}

/// `I/N` with 1 <= I <= N <= 100,000.
pub fn parse_shard(s: &str) -> Result<Shard, String> {
    let Some((i, n)) = s.trim().split_once('/') else {
        return Err(format!("expected I/N, e.g. 2/8 (got `{s}`)"));
    };
    let num = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|_| format!("`{v}` is not a whole number (expected I/N, e.g. 2/8)"))
    };
    let (index, count) = (num(i)?, num(n)?);
    if !(1..=MAX_FRAMES).contains(&count) {
        return Err(format!("N must be in 1..={MAX_FRAMES} (got {count})"));
    }
    if !(1..=count).contains(&index) {
        return Err(format!(
            "I must be in 1..={count}: shards are numbered from 1 (got {index})"
        ));
    }
    Ok(Shard { index, count })
}

#[cfg(test)]
mod tests;
