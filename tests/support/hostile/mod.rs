//! Hostile inputs shared by the `hostile*` tests of both test binaries: a seeded generator,
//! input mutators and the table of input formats. The library tests run each case in process
//! under a time and memory bound (`tests/lib/bounded.rs`); the command-line tests feed a
//! sample of the same cases to the `wisp` binary.
//!
//! A new input format (a groom file; the simulation cache did) plugs in with one [`formats::Format`] entry:
//! a name, valid seed files and a loader that returns accepted or refused (see `formats.rs`).

pub mod cache;
pub mod formats;
pub mod frames;
pub mod headers;
pub mod mutate;
pub mod scene;

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
