//! The records the build passes from phase to phase: a sample's statistics ([`PieceStats`]),
//! its pieces as the fill makes them ([`Piece`]) and as the counting sort places them
//! ([`Placed`]), and the bilinear shares by which a piece is split between the 2 × 2 columns
//! nearest to it ([`splat_weight`]): with (f_y, f_z) ∈ [0, 1]² its place from the base
//! column's centre, share t gets (1 − f_y or f_y) × (1 − f_z or f_z).

/// A sample's piece as the fill makes it: its slice, the first of the 2 × 2 columns it is
/// splatted to (the others follow by wrapping), and its place within that square.
#[derive(Clone, Copy, Debug, Default)]
pub(in crate::map) struct Piece {
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
/// merge then reads them beside the piece (read from the per-sample table instead, they are a
/// cache miss each, a quarter of the merge).
#[derive(Clone, Copy, Debug, Default)]
pub(in crate::map) struct Placed {
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
    pub(super) fn key(&self) -> u64 {
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
pub(in crate::map) const SPLAT: usize = 4;

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
pub(in crate::map) struct PieceStats {
    pub(super) n: f32,
    pub(super) loss: [f32; 3],
    pub(super) sigma2: [f32; 3],
    pub(super) volume_fraction: f32,
}

/// Bits of [`Placed::mark`] that hold the slice.
pub(super) const MARK_SLICE_BITS: u32 = 28;
