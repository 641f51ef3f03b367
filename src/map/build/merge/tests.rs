//! Merging a column from its four base columns against the plain build of one entry per piece
//! and column, to the bit.

use super::*;
use crate::map::build::cell_merge::CellMerge;
use crate::map::build::piece::{PieceStats, SPLAT, splat_weight};
use crate::map::build::sort::sort_column;
use proptest::prelude::*;

proptest! {
    /// Merging each column from the four base columns that reach it gives the cells, to
    /// the bit, of the plain per-column build: one entry per piece and column with a
    /// positive share, all of them sorted by (column, slice, piece order, share) and each
    /// column's run added in that order. Small grids (2 to 5 columns a side, so shares
    /// wrap around), pieces on column centre lines (shares of 0), repeated slices and
    /// several pieces per sample.
    #[test]
    fn merging_from_base_columns_is_the_per_column_entry_build_to_the_bit(
        ncol in 2usize..6,
        pieces in prop::collection::vec(
            (0usize..36, 0u32..6, 0usize..5, 0u8..4, 0u8..4, 0u16..=65535, 0u16..=65535),
            0..120,
        ),
    ) {
        let stats: Vec<PieceStats> = (0..5)
            .map(|s| {
                let v = 0.1 + s as f32 * 0.37;
                PieceStats {
                    n: v,
                    loss: [v * 0.3, v * 0.5, v * 0.7],
                    sigma2: [v * 0.01, v * 0.02, v * 0.03],
                    volume_fraction: v * 0.001,
                }
            })
            .collect();
        // Fractions on a quarter grid (0 and 1 give zero shares) or anywhere.
        let frac = |q: u8, seed: u16| match q {
            0 => 0.0,
            1 => 1.0,
            2 => 0.25 * (seed % 4) as f32,
            _ => seed as f32 / 65536.0,
        };
        let cols = ncol * ncol;
        let placed: Vec<(usize, Placed)> = pieces
            .iter()
            .enumerate()
            .map(|(id, &(col, slice, sample, qx, qy, a, b))| {
                let p = Placed {
                    slice,
                    id: id as u32,
                    frac: [frac(qx, a), frac(qy, b)],
                    depth: [a.min(b), a.max(b)],
                    stats: stats[sample],
                };
                (col % cols, p)
            })
            .collect();
        // Ours: pieces grouped by base column, each sorted by (slice, piece order).
        let mut by_base: Vec<Vec<Placed>> = vec![Vec::new(); cols];
        for &(c, p) in &placed {
            by_base[c].push(p);
        }
        by_base.iter_mut().for_each(|col| sort_column(col));
        let back = |m: usize, d: usize| (m + ncol - d) % ncol;
        // The reference: one entry per piece and column with a positive share.
        let mut entries = Vec::new();
        for &(c, p) in &placed {
            for t in 0..SPLAT {
                let (j, k) = ((c / ncol + (t >> 1)) % ncol, (c % ncol + (t & 1)) % ncol);
                let weight = splat_weight(p.frac, t);
                if weight > 0.0 {
                    entries.push((j * ncol + k, p.slice, p.id, t, weight, p));
                }
            }
        }
        entries.sort_by_key(|e| (e.0, e.1, e.2, e.3));
        for c in 0..cols {
            let (j, k) = (c / ncol, c % ncol);
            let sources = [
                by_base[c].as_slice(),
                &by_base[j * ncol + back(k, 1)],
                &by_base[back(j, 1) * ncol + k],
                &by_base[back(j, 1) * ncol + back(k, 1)],
            ];
            let column: Vec<_> = entries.iter().filter(|e| e.0 == c).collect();
            let slices = column.windows(2).filter(|w| w[0].1 != w[1].1).count()
                + usize::from(!column.is_empty());
            let marks: Vec<Vec<u32>> =
                sources.iter().map(|s| s.iter().map(Placed::mark).collect()).collect();
            let marks = [&marks[0][..], &marks[1][..], &marks[2][..], &marks[3][..]];
            prop_assert_eq!(column_cells(marks), slices, "column {}", c);
            let mut ours = vec![Cell::default(); slices];
            merge_column(sources, &mut ours);
            let mut reference = vec![Cell::default(); slices];
            let mut merge = CellMerge::new(&mut reference);
            for e in column {
                merge.add(e.1, &e.5.stats, e.4, e.5.depth);
            }
            merge.finish();
            let bits = |cells: &[Cell]| -> Vec<_> {
                cells
                    .iter()
                    .map(|c| {
                        (
                            c.slice,
                            c.n_sum.to_bits(),
                            c.loss.map(f32::to_bits),
                            c.sigma2.map(f32::to_bits),
                            c.volume_fraction.to_bits(),
                            c.depth_cdf,
                        )
                    })
                    .collect()
            };
            prop_assert_eq!(bits(&ours), bits(&reference), "column {}", c);
        }
    }
}
