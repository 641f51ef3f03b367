use super::*;
use proptest::prelude::*;

proptest! {
    /// Each bin lists exactly the items whose box touches it, in (depth, index) order, as
    /// a comparison sort on the depths gives.
    #[test]
    fn bins_hold_their_items_by_depth_then_index(
        boxes in proptest::collection::vec((0usize..4, 0usize..2, 0usize..3, 0usize..2, -3i32..3), 0..300)
    ) {
        let dims = [5, 4];
        let rect = |i: usize| {
            let (x0, dx, y0, dy, _) = boxes[i];
            Some(([x0, y0], [(x0 + dx).min(4), (y0 + dy).min(3)]))
        };
        // Few distinct depths, so ties (broken by index) are common; up to 300 items, so
        // some bins hold 64 or more and take the radix passes.
        let depth = |i: u32| boxes[i as usize].4 as f32 * 0.5;
        let (start, items) = list_by_depth(dims, boxes.len(), rect, depth);
        for bx in 0..dims[0] {
            for by in 0..dims[1] {
                let c = bx * dims[1] + by;
                let got = &items[start[c] as usize..start[c + 1] as usize];
                let mut want: Vec<u32> = (0..boxes.len())
                    .filter(|&i| {
                        let ([x0, y0], [x1, y1]) = rect(i).unwrap();
                        (x0..=x1).contains(&bx) && (y0..=y1).contains(&by)
                    })
                    .map(|i| i as u32)
                    .collect();
                want.sort_by(|a, b| depth(*a).total_cmp(&depth(*b)).then(a.cmp(b)));
                prop_assert_eq!(got, &want[..]);
            }
        }
    }
}
