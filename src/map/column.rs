//! One column of the map build (`build.rs` step 3): its entries sorted along the light, merged
//! into cells with where their crossings lie in depth, and swept from the light (Bertails 2005
//! Eq. 3 with the dual-scattering quantities).

use super::{Cell, DEPTH_BINS};
use glam::{Vec3, Vec4};

/// A sample's piece as the fill makes it: its slice, the first of the 2 × 2 columns it is
/// splatted to (the others follow by wrapping), and its place within that square.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Piece {
    /// Unwrapped slice ⌊x/ds⌋.
    pub(super) slice: i64,
    /// Base column (j0 mod N, k0 mod N) as j·N + k, or `u32::MAX` for a skipped (non-finite)
    /// sample or a piece none of whose shares is positive.
    pub(super) col: u32,
    /// The sample the piece belongs to (index into the per-sample statistics).
    pub(super) sample: u32,
    /// The piece's order among all pieces (sample × pieces per sample + piece).
    pub(super) id: u32,
    /// The piece's fractional place across the light from the base column's centre, in
    /// [0, 1] per axis: the bilinear shares follow ([`splat_weight`]).
    pub(super) frac: [f32; 2],
    /// The depth range along the light that the piece spans inside its cell, in 1/65535 of a
    /// cell from the light-side face.
    pub(super) depth: [u16; 2],
}

/// A piece after the counting sort by base column (the column is its place in the sorted
/// array), with its sample's statistics: the counting sort reads them in sample order, the
/// merge then reads them beside the piece (read there from the per-sample table, they were a
/// cache miss each, a quarter of the merge).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Placed {
    /// Slice relative to the first slice, wrapped modulo N (0..N).
    pub(super) slice: u32,
    pub(super) id: u32,
    pub(super) frac: [f32; 2],
    pub(super) depth: [u16; 2],
    pub(super) stats: PieceStats,
}

impl Placed {
    /// Its slice in the low [`MARK_SLICE_BITS`] bits (slices are below N, and N² columns of
    /// offsets could not be held long before N reaches 2^28), and above them, per share `t`,
    /// whether it is positive: 4 bytes that say which cells the piece opens.
    #[inline]
    pub(super) fn mark(&self) -> u32 {
        debug_assert!(self.slice < 1 << MARK_SLICE_BITS);
        (0..SPLAT).fold(self.slice, |m, t| {
            m | (u32::from(splat_weight(self.frac, t) > 0.0) << (MARK_SLICE_BITS as usize + t))
        })
    }

    /// The order the merge adds pieces in: by slice, then piece order.
    #[inline]
    fn key(&self) -> u64 {
        ((self.slice as u64) << 32) | self.id as u64
    }

    /// `piece` with its slice made relative (`slice`) and its sample's `stats`.
    #[inline]
    pub(super) fn new(piece: &Piece, slice: u32, stats: PieceStats) -> Placed {
        Placed {
            slice,
            id: piece.id,
            frac: piece.frac,
            depth: piece.depth,
            stats,
        }
    }
}

/// Columns a piece is shared between (2 × 2, bilinear weights): share `t` goes to the column
/// `t >> 1` further along j and `t & 1` further along k than the base column.
pub(super) const SPLAT: usize = 4;

/// Share `t` (0..[`SPLAT`]) of a piece at `frac` within its square of columns: the bilinear
/// (tent) weight of that column's centre.
#[inline]
pub(super) fn splat_weight(frac: [f32; 2], t: usize) -> f32 {
    let wx = if t >> 1 == 0 { 1.0 - frac[0] } else { frac[0] };
    let wy = if t & 1 == 0 { 1.0 - frac[1] } else { frac[1] };
    wx * wy
}

/// What one piece of a sample carries into a cell before its bilinear share: expected
/// crossings, their losses Σ n(1 − ā_f) and variance Σ n β̄_f², and hair volume fraction.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct PieceStats {
    pub(super) n: f32,
    pub(super) loss: [f32; 3],
    pub(super) sigma2: [f32; 3],
    pub(super) volume_fraction: f32,
}

/// Sorts one base column's pieces by (relative slice, piece order). The counting sort by
/// column keeps each column in piece order, so a stable sort by slice alone gives that order:
/// short columns by insertion, longer ones by counting slices into a per-thread buffer,
/// O(length + span) and allocation-free once the buffers have grown. (Measured: the general
/// unstable sort on the pair key was a quarter of the build.)
pub(super) fn sort_column(col: &mut [Placed]) {
    debug_assert!(col.windows(2).all(|w| w[0].id < w[1].id));
    if col.len() <= 16 {
        for i in 1..col.len() {
            let mut j = i;
            while j > 0 && col[j - 1].slice > col[j].slice {
                col.swap(j - 1, j);
                j -= 1;
            }
        }
        return;
    }
    let (lo, hi) = col.iter().fold((u32::MAX, u32::MIN), |(lo, hi), c| {
        (lo.min(c.slice), hi.max(c.slice))
    });
    if lo == hi {
        return;
    }
    thread_local! {
        static BUFFERS: std::cell::RefCell<(Vec<u32>, Vec<Placed>)> =
            const { std::cell::RefCell::new((Vec::new(), Vec::new())) };
    }
    BUFFERS.with_borrow_mut(|(count, copy)| {
        count.clear();
        count.resize((hi - lo) as usize + 1, 0);
        for c in col.iter() {
            count[(c.slice - lo) as usize] += 1;
        }
        let mut acc = 0u32;
        for k in count.iter_mut() {
            let n = *k;
            *k = acc;
            acc += n;
        }
        copy.clear();
        copy.extend_from_slice(col);
        for c in copy.iter() {
            let at = &mut count[(c.slice - lo) as usize];
            col[*at as usize] = *c;
            *at += 1;
        }
    });
}

/// Bits of [`Placed::mark`] that hold the slice.
const MARK_SLICE_BITS: u32 = 28;

/// How many cells one column has: the distinct slices among the pieces of `sources` (their
/// [`Placed::mark`]s, in the order of [`merge_column`]'s sources) whose share in it is
/// positive. A bit per slice over the slices the sources span, in a per-thread buffer.
pub(super) fn column_cells(sources: [&[u32]; SPLAT]) -> usize {
    let slice = |m: u32| m & ((1 << MARK_SLICE_BITS) - 1);
    let lo = sources
        .iter()
        .filter_map(|s| s.first())
        .map(|&m| slice(m))
        .min();
    let hi = sources
        .iter()
        .filter_map(|s| s.last())
        .map(|&m| slice(m))
        .max();
    let (Some(lo), Some(hi)) = (lo, hi) else {
        return 0;
    };
    thread_local! {
        static BITS: std::cell::RefCell<Vec<u64>> = const { std::cell::RefCell::new(Vec::new()) };
    }
    BITS.with_borrow_mut(|bits| {
        bits.clear();
        bits.resize(((hi - lo) / 64 + 1) as usize, 0);
        for (t, source) in sources.iter().enumerate() {
            for &m in source.iter() {
                let at = slice(m) - lo;
                let set = u64::from(m >> (MARK_SLICE_BITS as usize + t) & 1);
                bits[(at / 64) as usize] |= set << (at % 64);
            }
        }
        bits.iter().map(|w| w.count_ones() as usize).sum()
    })
}

/// Merges the pieces that reach one column into its `cells` (one per distinct slice,
/// [`column_cells`] of them), each piece carrying its sample's statistics times its bilinear
/// share, and sweeps them from the light (Bertails Eq. 3 with the dual-scattering
/// quantities). `sources[t]` holds the pieces whose share `t` falls in this column (those of
/// the base column `t >> 1` back along j and `t & 1` back along k), each sorted by (slice,
/// piece order). They are merged in (slice, piece order, t) order: the order a sort of one
/// entry per piece and column would give, so every float sum adds in one fixed order.
pub(super) fn merge_column(sources: [&[Placed]; SPLAT], cells: &mut [Cell]) {
    let key = |t: usize, i: usize| sources[t].get(i).map_or(u64::MAX, Placed::key);
    let mut at = [0usize; SPLAT];
    let mut keys = [key(0, 0), key(1, 0), key(2, 0), key(3, 0)];
    let mut merge = CellMerge::new(cells);
    loop {
        // The lowest key; a tie (only where the columns wrap onto themselves) goes to the
        // lower share index.
        let mut t = 0;
        for u in 1..SPLAT {
            if keys[u] < keys[t] {
                t = u;
            }
        }
        if keys[t] == u64::MAX {
            break;
        }
        let p = &sources[t][at[t]];
        at[t] += 1;
        keys[t] = key(t, at[t]);
        let weight = splat_weight(p.frac, t);
        // A share of exactly 0 (a piece on a column centre line) makes no cell.
        if weight > 0.0 {
            merge.add(p.slice, &p.stats, weight, p.depth);
        }
    }
    merge.finish();
}

/// One column's cells as pieces are added in order: a new slice opens a cell, the same slice
/// adds to it, and where along the light its crossings lie is kept as a histogram over
/// [`DEPTH_BINS`] sub-slices.
pub(super) struct CellMerge<'a> {
    cells: &'a mut [Cell],
    /// Cells opened so far.
    open: usize,
    hist: [f32; DEPTH_BINS],
}

impl<'a> CellMerge<'a> {
    /// A merge into `cells`, as many as the distinct slices it will be given.
    pub(super) fn new(cells: &'a mut [Cell]) -> Self {
        CellMerge {
            cells,
            open: 0,
            hist: [0.0; DEPTH_BINS],
        }
    }

    /// Adds share `weight` of a piece carrying `st` and lying over `depth` of its cell at
    /// `slice` (slices in non-decreasing order).
    #[inline]
    pub(super) fn add(&mut self, slice: u32, st: &PieceStats, weight: f32, depth: [u16; 2]) {
        let n = st.n * weight;
        let loss = (Vec3::from(st.loss) * weight).to_array();
        let sigma2 = (Vec3::from(st.sigma2) * weight).to_array();
        let vf = st.volume_fraction * weight;
        match self.open.checked_sub(1).map(|w| &mut self.cells[w]) {
            Some(m) if m.slice == slice => {
                m.n_sum += n;
                m.volume_fraction += vf;
                for ch in 0..3 {
                    m.loss[ch] += loss[ch];
                    m.sigma2[ch] += sigma2[ch];
                }
            }
            last => {
                if let Some(m) = last {
                    m.depth_cdf = depth_cdf(&self.hist);
                }
                self.hist = [0.0; DEPTH_BINS];
                self.cells[self.open] = Cell {
                    slice,
                    n_sum: n,
                    loss,
                    sigma2,
                    volume_fraction: vf,
                    depth_cdf: [0; DEPTH_BINS - 1],
                };
                self.open += 1;
            }
        }
        spread_depth(&mut self.hist, depth, n);
    }

    /// Closes the last cell and sweeps: running sums of crossings, losses and variance; each
    /// cell then holds what has been crossed up to its far face (the lookup takes
    /// exponentials).
    pub(super) fn finish(self) {
        debug_assert_eq!(self.open, self.cells.len());
        let cells = &mut self.cells[..self.open];
        if let Some(m) = cells.last_mut() {
            m.depth_cdf = depth_cdf(&self.hist);
        }
        let (mut n_sum, mut loss, mut var) = (0.0f32, [0.0f32; 3], [0.0f32; 3]);
        for c in cells.iter_mut() {
            n_sum += c.n_sum;
            c.n_sum = n_sum;
            for ch in 0..3 {
                loss[ch] += c.loss[ch];
                var[ch] += c.sigma2[ch];
            }
            c.loss = loss;
            c.sigma2 = var;
        }
    }
}

/// Adds `n` crossings spread evenly over the depth range `depth` (1/65535 of a cell) to the
/// sub-slice histogram `hist`.
#[inline]
fn spread_depth(hist: &mut [f32; DEPTH_BINS], depth: [u16; 2], n: f32) {
    let k = DEPTH_BINS as f32 / 65535.0;
    let (lo, hi) = (depth[0] as f32 * k, depth[1] as f32 * k);
    let width = hi - lo;
    if width < 1e-6 {
        hist[(lo as usize).min(DEPTH_BINS - 1)] += n;
        return;
    }
    // The first and last bins reached, as floats: lo and hi lie in [0, 8] (from u16 depths),
    // where floor is the truncation `as usize` did, without its saturating conversions.
    let last_bin = (DEPTH_BINS - 1) as f32;
    let (b0, b1) = (lo.floor().min(last_bin), hi.floor().min(last_bin));
    // The bins b0..=b1, four to a vector: each lane rounds its min, max, product and quotient
    // as the scalar `n * overlap / width` does (IEEE), and a lane outside b0..=b1 adds exactly
    // nothing, so this is the per-bin loop to the bit (also for a non-finite n) without its
    // scalar divisions, which were about a third of the merge.
    const _: () = assert!(DEPTH_BINS == 8);
    let (lo4, hi4, n4, width4) = (
        Vec4::splat(lo),
        Vec4::splat(hi),
        Vec4::splat(n),
        Vec4::splat(width),
    );
    for (half, start) in [(0, 0.0f32), (4, 4.0)] {
        let b = Vec4::new(start, start + 1.0, start + 2.0, start + 3.0);
        let overlap = (hi4.min(b + 1.0) - lo4.max(b)).max(Vec4::ZERO);
        let reached = b.cmpge(Vec4::splat(b0)) & b.cmple(Vec4::splat(b1));
        let add = Vec4::select(reached, n4 * overlap / width4, Vec4::ZERO);
        let h = Vec4::from_slice(&hist[half..half + 4]);
        Vec4::select(reached, h + add, h).write_to_slice(&mut hist[half..half + 4]);
    }
}

/// The cumulative shares of a sub-slice histogram at its inner boundaries, in 1/255. An empty
/// histogram (a cell whose pieces carry no crossings, e.g. fibres along the light) reads as
/// spread evenly.
fn depth_cdf(hist: &[f32; DEPTH_BINS]) -> [u8; DEPTH_BINS - 1] {
    let total: f32 = hist.iter().sum();
    let mut out = [0u8; DEPTH_BINS - 1];
    let mut acc = 0.0f32;
    for (k, o) in out.iter_mut().enumerate() {
        acc += hist[k];
        let share = if total > 0.0 {
            acc / total
        } else {
            (k + 1) as f32 / DEPTH_BINS as f32
        };
        *o = (share.clamp(0.0, 1.0) * 255.0).round() as u8;
    }
    out
}

#[cfg(test)]
mod sort_tests {
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

        /// Merging each column from the four base columns that reach it gives the cells, to
        /// the bit, of the plain build it replaced: one entry per piece and column with a
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
}
