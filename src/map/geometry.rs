//! The map's size: N slices of ds along the light, and N × `lateral` columns of ds / `lateral`
//! across it per axis, chosen from the scene (Bertails 2005 §2.2: the span N·ds ≥ 2·lmax + hmax
//! holds the hair wherever it moves, so the modulo-indexed map never reallocates or
//! re-centres), with the cell and column sizes that the measurements against the exact
//! reference favour ([`MapGeometry::for_scene`]).

/// Size of the map: N slices of `ds_m` along the light, and `lateral` × N columns across it
/// per axis (each `ds_m / lateral` wide).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapGeometry {
    /// Cells per axis along the light (slices).
    pub n: u32,
    /// Cell size along the light in metres.
    pub ds_m: f32,
    /// Columns per cell width across the light (1: cubic cells). Along the light each cell
    /// already knows where its hair lies (8 sub-slices); across it, what a column averages is
    /// all it knows, so finer columns than slices resolve slanted hair surfaces at no cost in
    /// pieces (a piece is no longer than a slice).
    pub lateral: u32,
}

impl MapGeometry {
    /// A map that spans `span_m` with `n` cubic cells per axis.
    pub fn with_resolution(span_m: f32, n: u32) -> Self {
        let n = n.max(1);
        Self {
            n,
            ds_m: span_m / n as f32,
            lateral: 1,
        }
    }

    /// Columns per lateral axis (N × `lateral`).
    pub fn columns_per_axis(&self) -> u32 {
        self.n.saturating_mul(self.lateral.max(1))
    }

    /// Column width across the light, metres.
    pub fn column_m(&self) -> f32 {
        self.ds_m / self.lateral.max(1) as f32
    }

    /// A map sized from the scene (Bertails §2.2): span 2·lmax + hmax, and a cell of
    /// 1.5 × the spacing between render strands at the scalp, widened by √(30/F) when each
    /// render strand holds fewer than F = 30 fibres. Chosen from the measurements of
    /// ACCURACY.md against the exact reference:
    /// - the error falls as cells shrink towards the strand spacing (smooth, 30 fibres per strand:
    ///   T_f MAE 0.020 at 2 spacings, 0.016 at 1.5, 0.014 at 1), and the cost grows with the
    ///   filled cells; 1.5 spacings (N = 172 for the presets) meets MAE ≤ 0.02 with margin;
    /// - across the light, columns about ¾ of a strand spacing wide (at most
    ///   [`MAX_LATERAL_COLUMNS`] per cell width; 2 for the presets): the pictures of a path
    ///   tracer (tools/reference, ACCURACY.md) show the hair the camera sees, which lies at the
    ///   hair's surface, where a column averages hair beside the point at other depths. One
    ///   fibre per strand, single scattering against Mitsuba: back-lit 1.25 → 1.00 and
    ///   front-lit 0.79 → 0.91 with 4 columns per cell, curly back-lit 1.88 → 1.19 with 3;
    ///   narrower columns than ¾ spacing resolve single strands and the per-vertex error rises
    ///   (smooth: MAE 0.0132 at 2.5 mm columns, 0.0154 at 1.8, 0.0207 at 1.2). The pieces do
    ///   not change (a piece is no longer than a slice); the filled cells grow;
    /// - with one fibre per render strand, a cell a few strands wide no longer averages enough
    ///   fibres, and finer cells stop paying: against the hair within 3.7 mm, smooth with 12
    ///   one-fibre strands per preset strand has MAE 0.031 at 8.8 mm cells, 0.026 at 7.4,
    ///   0.025 at 5, 0.026 at 3.7 and 0.030 at 2.1 mm (where 2 strand spacings put it), while
    ///   its calibration turns bright below 5 mm. The cell therefore spans as many fibres as a
    ///   preset's (about 68 across a cell at the scalp), not as many render strands: 87,500
    ///   one-fibre strands get N ≈ 160, not 657.
    pub fn for_scene(
        max_length_m: f32,
        head_size_m: f32,
        strand_spacing_m: f32,
        fibers_per_strand: f32,
    ) -> Self {
        Self::for_scene_scaled(
            max_length_m,
            head_size_m,
            strand_spacing_m,
            fibers_per_strand,
            1.0,
        )
    }

    /// [`MapGeometry::for_scene`] with cells and columns `cell_scale` times as wide (the same
    /// columns per cell): a coarser map for a quicker frame (the `preview` level), whose T_f
    /// error against the exact reference ACCURACY.md gives. A scale that is not finite and
    /// positive is taken as 1.
    pub fn for_scene_scaled(
        max_length_m: f32,
        head_size_m: f32,
        strand_spacing_m: f32,
        fibers_per_strand: f32,
        cell_scale: f32,
    ) -> Self {
        Self::for_span_scaled(
            Self::span_m(max_length_m, head_size_m),
            strand_spacing_m,
            fibers_per_strand,
            cell_scale,
        )
    }

    /// [`MapGeometry::for_scene_scaled`] over a span of `span_m` given whole (hair whose reach
    /// is not a swing about roots on the head: an imported groom's, `Hairstyle::reach_m`).
    pub fn for_span_scaled(
        span_m: f32,
        strand_spacing_m: f32,
        fibers_per_strand: f32,
        cell_scale: f32,
    ) -> Self {
        let scale = if cell_scale.is_finite() && cell_scale > 0.0 {
            cell_scale
        } else {
            1.0
        };
        let span = span_m;
        let widen = (30.0 / fibers_per_strand.max(1e-3)).sqrt().max(1.0);
        let cell = 1.5 * strand_spacing_m.max(1e-6) * widen;
        let lateral_of = |n: f32| {
            let ds_m = span / n;
            (ds_m / (0.75 * strand_spacing_m.max(1e-6)))
                .round()
                .clamp(1.0, MAX_LATERAL_COLUMNS as f32) as u32
        };
        let lateral = lateral_of((span / cell).ceil().clamp(8.0, 1024.0));
        let n = (span / (cell * scale)).ceil().clamp(8.0, 1024.0) as u32;
        Self {
            lateral,
            ..Self::with_resolution(span, n)
        }
    }

    /// The smallest span that always holds the hair: 2·lmax + hmax (Bertails §2.2), plus 2%
    /// so that a strand pulled exactly straight does not land on the wrap boundary.
    pub fn span_m(max_length_m: f32, head_size_m: f32) -> f32 {
        1.02 * (2.0 * max_length_m + head_size_m)
    }

    /// The span that holds hair reaching `reach_m` from the head's centre in every direction:
    /// twice the reach, plus the same 2% as [`MapGeometry::span_m`].
    pub fn span_for_reach_m(reach_m: f32) -> f32 {
        1.02 * (2.0 * reach_m)
    }
}

/// Most columns per cell width across the light that [`MapGeometry::for_scene`] chooses.
pub const MAX_LATERAL_COLUMNS: u32 = 4;
