//! The sort of a base column along the light against a plain sort on (slice, piece order).

use super::*;
use crate::map::build::piece::PieceStats;
use proptest::prelude::*;

proptest! {
    /// The column sort (insertion for short columns, a counting sort by slice for long
    /// ones) gives exactly the order of a sort on (slice, piece order) for any column in
    /// piece order, the order the counting sort by column leaves.
    #[test]
    fn column_sort_is_the_sort_on_slice_then_piece_order(
        slices in prop::collection::vec(0u32..40, 0..200),
        gaps in prop::collection::vec(1u32..4, 200),
    ) {
        let mut id = 0u32;
        let col: Vec<Placed> = slices
            .iter()
            .zip(&gaps)
            .map(|(&slice, &g)| {
                id += g;
                let stats = PieceStats { n: id as f32, ..PieceStats::default() };
                Placed { slice, id, frac: [g as f32, 0.0], depth: [g as u16, 0], stats }
            })
            .collect();
        let mut ours = col.clone();
        sort_column(&mut ours);
        let mut reference = col.clone();
        reference.sort_by_key(|p| (p.slice, p.id));
        let key = |p: &Placed| (p.slice, p.id, p.stats.n.to_bits(), p.frac.map(f32::to_bits), p.depth);
        prop_assert_eq!(
            ours.iter().map(key).collect::<Vec<_>>(),
            reference.iter().map(key).collect::<Vec<_>>()
        );
    }
}
