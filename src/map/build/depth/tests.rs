//! The vector depth spread against the plain per-bin loop, to the bit.

use super::*;
use proptest::prelude::*;

/// The depth spread as a plain loop over the bins the piece reaches, one division each:
/// what the vector version must give to the bit.
fn spread_depth_per_bin(hist: &mut [f32; DEPTH_BINS], depth: [u16; 2], n: f32) {
    let k = DEPTH_BINS as f32 / 65535.0;
    let (lo, hi) = (depth[0] as f32 * k, depth[1] as f32 * k);
    let width = hi - lo;
    if width < 1e-6 {
        hist[(lo as usize).min(DEPTH_BINS - 1)] += n;
        return;
    }
    let (b0, b1) = (
        (lo as usize).min(DEPTH_BINS - 1),
        (hi as usize).min(DEPTH_BINS - 1),
    );
    for (b, h) in hist.iter_mut().enumerate().take(b1 + 1).skip(b0) {
        let overlap = (hi.min(b as f32 + 1.0) - lo.max(b as f32)).max(0.0);
        *h += n * overlap / width;
    }
}

proptest! {
    /// Spreading pieces over the depth bins gives the plain per-bin loop's bits, for any
    /// depth range (empty, within one bin, ending on a bin's edge, the whole cell), any
    /// crossings (0, tiny, huge, infinite) and any sums already in the bins.
    #[test]
    fn depth_spread_is_the_per_bin_loop_to_the_bit(
        pieces in prop::collection::vec(
            (0u16..=65535, 0u16..=65535, prop_oneof![
                Just(0.0f32), Just(1e-30), Just(3.0e38), Just(f32::INFINITY),
                0.0f32..10.0,
            ], any::<bool>()),
            1..12,
        ),
    ) {
        let (mut ours, mut reference) = ([0.0f32; DEPTH_BINS], [0.0f32; DEPTH_BINS]);
        for (a, b, n, on_edge) in pieces {
            // Depths on a bin's edge (multiples of 65535/8 rounded) as well as anywhere.
            let edge = |v: u16| ((v as u32 * 8 / 65536) * 65535 / 8) as u16;
            let (a, b) = if on_edge { (edge(a), edge(b)) } else { (a, b) };
            let depth = [a.min(b), a.max(b)];
            spread_depth(&mut ours, depth, n);
            spread_depth_per_bin(&mut reference, depth, n);
        }
        prop_assert_eq!(ours.map(f32::to_bits), reference.map(f32::to_bits));
    }
}
