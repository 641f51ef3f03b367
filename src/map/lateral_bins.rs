//! Items (fibre segments or their parts) listed by the bins of a uniform grid across the light
//! that their lateral boxes touch, each bin sorted by the items' nearest depth to the light,
//! ties by index: how the exact reference (`exact`) and the contact shadows (`contact`) find
//! the fibres near a ray. A counting sort, then each bin sorted in parallel; the total order
//! makes the lists independent of the thread count.

use crate::keysort::{sort_keys, total_order_bits};
use rayon::prelude::*;

/// An item's bins: rows `x0..=x1` and columns `y0..=y1`, or `None` for no bin.
pub(super) type BinRect = Option<([usize; 2], [usize; 2])>;

/// Lists items `0..count` in the bins of a grid of `dims` bins (row-major, `dims[1]` bins a
/// row) given by `rect(i)`, each bin ordered by `x_min(i)` (the item's nearest depth) then by
/// index. Returns the bins' starts (one more than the bins) and the concatenated lists.
pub(crate) fn list_by_depth(
    dims: [usize; 2],
    count: usize,
    rect: impl Fn(usize) -> BinRect,
    x_min: impl Fn(u32) -> f32 + Sync,
) -> (Vec<u32>, Vec<u32>) {
    let ny = dims[1];
    let mut start = vec![0u32; dims[0] * ny + 1];
    for ([x0, y0], [x1, y1]) in (0..count).filter_map(&rect) {
        for bx in x0..=x1 {
            for by in y0..=y1 {
                start[bx * ny + by + 1] += 1;
            }
        }
    }
    for i in 1..start.len() {
        start[i] += start[i - 1];
    }
    let mut cursor = start.clone();
    let mut items = vec![0u32; *start.last().unwrap_or(&0) as usize];
    for i in 0..count {
        if let Some(([x0, y0], [x1, y1])) = rect(i) {
            for bx in x0..=x1 {
                for by in y0..=y1 {
                    let c = &mut cursor[bx * ny + by];
                    items[*c as usize] = i as u32;
                    *c += 1;
                }
            }
        }
    }
    let mut bins: Vec<&mut [u32]> = Vec::with_capacity(start.len() - 1);
    let mut rest: &mut [u32] = &mut items;
    for w in start.windows(2) {
        let (a, b) = std::mem::take(&mut rest).split_at_mut((w[1] - w[0]) as usize);
        bins.push(a);
        rest = b;
    }
    // Each item's depth read once into a key whose integer order is (depth by `total_cmp`,
    // index), the items already in index order: the same total order as comparing depths in
    // the sort, without reading an item's record at every comparison.
    bins.into_par_iter().for_each_init(
        || (Vec::new(), Vec::new()),
        |(keys, tmp): &mut (Vec<u64>, Vec<u64>), bin| {
            keys.clear();
            keys.extend(
                bin.iter()
                    .map(|&i| (u64::from(total_order_bits(x_min(i))) << 32) | u64::from(i)),
            );
            sort_keys(keys, tmp);
            for (slot, key) in bin.iter_mut().zip(keys.iter()) {
                *slot = *key as u32;
            }
        },
    );
    (start, items)
}

#[cfg(test)]
mod tests;
