//! Skipping a rebuild when nothing a pass builds from has changed.
//!
//! The hair map, the occluders and the skin texture are deterministic functions of their
//! inputs: the render strands (positions, tangents, lengths), the lights and the point the
//! point lights aim at, the solids and the character's posed mesh (the hairstyle's fibre and
//! fibres per strand are fixed for an engine). When a pass's inputs are bit-equal to those of
//! its last build, building again would give the same bits, so it keeps what it has: frames
//! are byte-identical with and without the reuse (`tests/lib/scenes.rs`). A still head whose hair
//! is at rest (the simulator holds settled guides exactly, `sim::step`), a paused window, or a
//! relit or re-framed still frame reuse them; a dancing head never does.
//!
//! Cost: copying and comparing the inputs, O(points), about 0.2 ms for the presets' 100K
//! points against a map build of tens of ms (BENCHMARKS.md). NaN never equals itself, so a
//! non-finite input always rebuilds.

/// A copy of the slices a pass last built from.
#[derive(Clone, Debug)]
pub(crate) struct Kept<T> {
    recorded: bool,
    items: Vec<Vec<T>>,
}

impl<T> Default for Kept<T> {
    fn default() -> Self {
        Self {
            recorded: false,
            items: Vec::new(),
        }
    }
}

impl<T: Copy + PartialEq> Kept<T> {
    /// Forgets the recorded inputs: the next check reports a change.
    pub fn forget(&mut self) {
        self.recorded = false;
    }

    /// True when `now` equals the recorded inputs slice for slice; otherwise records `now`
    /// (reusing the buffers, so after the first frame this allocates nothing) and returns
    /// false.
    pub fn unchanged_or_record(&mut self, now: &[&[T]]) -> bool {
        let same = self.recorded
            && self.items.len() == now.len()
            && self.items.iter().zip(now).all(|(a, b)| a[..] == **b);
        if !same {
            self.recorded = true;
            self.items.resize_with(now.len(), Vec::new);
            for (dst, src) in self.items.iter_mut().zip(now) {
                dst.clear();
                dst.extend_from_slice(src);
            }
        }
        same
    }

    /// The first slice last recorded (empty before any).
    pub fn first(&self) -> &[T] {
        self.items.first().map_or(&[], Vec::as_slice)
    }

    /// Bytes of the recorded copies at most, for `items` values in all.
    pub fn estimated_bytes(items: u64) -> u64 {
        items.saturating_mul(size_of::<T>() as u64)
    }
}

#[cfg(test)]
mod tests;
