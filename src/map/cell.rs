//! What the map stores per filled cell ([`Cell`]): the running sums of the sweep of Bertails
//! 2005 Eq. 3 in its dual-scattering form (Σ n, Σ n(1 − ā_f), Σ n β̄_f² up to the cell's far
//! face) and where along the light its crossings lie, as a cumulative share over
//! [`DEPTH_BINS`] sub-slices. A point at depth λ inside the cell receives the sums entering it
//! plus share(λ) of the cell's own (module doc of `map`, "Along the light").

/// Sub-slices along the light in which a cell records where its hair lies (see
/// [`Cell::depth_cdf`]).
pub(crate) const DEPTH_BINS: usize = 8;

/// One filled cell after the sweep: the light leaving its far face, where its hair lies along
/// the light, and its hair content.
///
/// The light is stored as the running sums of the sweep (expected crossings, losses, variance),
/// not as their exponentials, so that a lookup can take any fraction of a cell's own
/// crossings exactly (exp of an interpolated sum) before converting to transmittance.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Cell {
    /// Slice index relative to the first slice (0..N).
    pub slice: u32,
    /// Expected crossings inside this cell (while merging), then Σ n up to the far face
    /// (after the sweep): the direct fraction leaving the cell is exp(−n_sum).
    pub n_sum: f32,
    /// Σ n·(1 − ā_f) (or Σ n·(−ln ā_f)) inside the cell, then up to the far face, RGB: T_f
    /// leaving the cell is exp(−loss).
    pub loss: [f32; 3],
    /// Σ n·β̄_f² inside the cell, then σ̄f² leaving the cell (rad²), RGB.
    pub sigma2: [f32; 3],
    /// Hair volume fraction of the cell (fibre volume / cell volume).
    pub volume_fraction: f32,
    /// After merging: the share of the cell's crossings that lie before each inner sub-slice
    /// boundary k/DEPTH_BINS (k = 1..DEPTH_BINS−1), in 1/255. Between boundaries the share
    /// grows linearly. A point inside the cell receives the light entering it minus only the
    /// crossings in front of it (a uniform spread through the cell would shadow the front-most
    /// fibres with hair lying beside and behind them).
    pub depth_cdf: [u8; DEPTH_BINS - 1],
}

impl Cell {
    /// Share of the cell's crossings before depth `lambda` ∈ [0, 1] (cell units from the
    /// light-side face): piecewise linear through the stored sub-slice boundaries.
    #[inline]
    pub fn share_before(&self, lambda: f32) -> f32 {
        let t = (lambda * DEPTH_BINS as f32).clamp(0.0, DEPTH_BINS as f32);
        let k = (t as usize).min(DEPTH_BINS - 1);
        let at = |b: usize| -> f32 {
            match b {
                0 => 0.0,
                DEPTH_BINS => 1.0,
                _ => self.depth_cdf[b - 1] as f32 * (1.0 / 255.0),
            }
        };
        let (a, b) = (at(k), at(k + 1));
        a + (b - a) * (t - k as f32)
    }
}
