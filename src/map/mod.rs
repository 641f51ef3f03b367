//! The light-oriented, modulo-indexed map (Bertails 2005 §2–3), carrying the dual-scattering
//! statistics of Zinke 2008 §4 instead of an opacity.
//!
//! ## Frame and cells
//! The map frame is (X = L, Y, Z) with L the direction the light travels (Bertails §2.1). A
//! point with map coordinates (x, y, z) belongs to cell Ψ(P) = (⌊x/ds⌋ mod N, ⌊y/ds⌋ mod N,
//! ⌊z/ds⌋ mod N) (Bertails §2.2). The map spans N·ds ≥ 2·lmax + hmax, so the hair always fits
//! and moving the hair never reallocates or re-centres anything.
//!
//! ## Sparse storage: cost O(samples + touched cells)
//! Instead of N³ voxels, the map stores only filled cells, grouped by column (j, k) in a
//! compressed-row layout: a counting sort of the sample pieces by column (N² counters, the
//! only per-frame cost that depends on N) followed, per column and in parallel, by a sort of
//! its pieces along X (relative to the first slice, wrapping modulo N as in Bertails Figure
//! 3), a merge of pieces falling in the same cell, and the sweep of Eq. 3 (`build.rs`). An
//! empty cell has the value of the last filled cell before it in its column (Bertails §3.2:
//! "otherwise cell (i,j,k) is given the transmittance prevTrans"); a lookup finds it through
//! a per-column slot table. A dense N³ grid at N = 128 would clear and sweep 2M cells (56 MB
//! at 7 floats) each frame for ~30K filled.
//!
//! ## What a cell holds (DESIGN.md "Fill")
//! Each render-strand sample stands for a length ℓ of F real fibres of radius r. A light ray
//! through a column of cross-section ds² meets it with probability ℓ·2r·sin ψ / ds² (ψ: angle
//! between fibre and L), so the expected number of crossings the sample adds is
//! n = F·ℓ·2r·sin ψ / ds². Each crossing forward-scatters with the fibre's ā_f(θ) and adds
//! β̄_f²(θ) of angular variance (Zinke 2008 Eqs. 6, 19, 20), θ being the light's inclination to
//! that fibre. With crossings Poisson-distributed along a ray of the column (fibres placed
//! independently), the column-averaged quantities after crossings of mean total n̄ are:
//!
//! - direct fraction (no crossing yet): P(N = 0) = exp(−n̄);
//! - forward transmittance: E[∏ ā_f] = exp(−Σ n·(1 − ā_f)) per colour channel;
//! - spread: σ̄f² = Σ n·β̄_f².
//!
//! The alternative reading ā^n̄ (`CountModel::MeanCount`) is kept for measurement: it is the
//! transmittance of a ray meeting exactly the mean number of fibres, and it is darker than the
//! ray average (by Jensen); `tests/map_reference.rs` measures both against ray shooting.
//! The sums are kept, not their exponentials, so a lookup can take any part of a cell exactly.
//!
//! ## Across the light: a bilinear splat and a bilinear read
//! A sample piece is shared by the four columns nearest to it, with bilinear (tent) weights
//! about their centres, and a lookup blends the four columns nearest to the point with the
//! same weights. A box fill (each piece into one column) makes the light jump where a strand
//! crosses a column boundary, which shows the grid as cell-sized blotches on front-lit hair
//! lying side by side; the splat removes them (measured on smooth at N = 129 against the exact
//! reference: T_f MAE 0.025 → 0.021, ACCURACY.md), at four shares per piece, taken as the
//! columns are merged (`build.rs`).
//!
//! ## Along the light: where a cell's hair lies, and what a point receives
//! A cell stores the running sums of the sweep up to its *far face* (the face away from the
//! light; Bertails' "light received by its back side"), and a histogram of where along the
//! light its crossings lie: 8 sub-slices, as a cumulative share (`Cell::depth_cdf`;
//! each piece spreads its crossings evenly over the depth it spans). A point inside a cell
//! receives the sums entering the cell plus only the share of the cell's crossings in front of
//! it, turned into exp(−n) and exp(−loss) per column: the front-most fibres of a cell are no
//! longer shadowed by hair lying beside or behind them (Bertails §6 names this family, adaptive
//! slicing along the light). Reading through a cell with a uniform spread (the filter of
//! Bertails §3.3) made lit hair 0.16–0.23 too dark against the exact reference. A slab of hair
//! perpendicular to L still reads exactly 1 in front of it and exactly the analytic attenuation
//! at every face behind it (`tests/map_slab.rs`).
//!
//! ## Opaque solids
//! The head and body are occluders in the same light frame ([`OccluderGrid`]: entry depth per
//! texel of a quarter cell), so they shadow the hair as the hair shadows them. A character's
//! skinned mesh is rasterised into the same grid.
//!
//! ## Contact shadows
//! For hair of one fibre per render strand, the fibres just in front of a vertex are taken
//! exactly ([`contact`]): the map gives the light reaching a window in front of the point, the
//! real fibres inside the window what gets through it.
//!
//! ## Measuring it
//! [`exact`] shoots rays through explicit fibre cylinders (no grid, no statistics), and
//! [`accuracy`] compares the map with it; `wisp accuracy` prints the tables of ACCURACY.md.

mod budget;
mod build;
mod column;
pub mod contact;
mod entry_depths;
pub(crate) mod lateral_bins;
mod lookup;
pub(crate) mod occluders;
mod shadows;
pub mod surface;

pub use build::{CountModel, MapBuildInput, MapLight, MapStats};
pub use occluders::{OccluderGrid, OccluderMesh, Solid};
pub use shadows::{Shadow, Shadows};

use glam::{Vec2, Vec3};

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
        let span = Self::span_m(max_length_m, head_size_m);
        let widen = (30.0 / fibers_per_strand.max(1e-3)).sqrt().max(1.0);
        let cell = 1.5 * strand_spacing_m.max(1e-6) * widen;
        let n = (span / cell).ceil().clamp(8.0, 1024.0) as u32;
        let geom = Self::with_resolution(span, n);
        let lateral = (geom.ds_m / (0.75 * strand_spacing_m.max(1e-6)))
            .round()
            .clamp(1.0, MAX_LATERAL_COLUMNS as f32) as u32;
        Self { lateral, ..geom }
    }

    /// The smallest span that always holds the hair: 2·lmax + hmax (Bertails §2.2), plus 2%
    /// so that a strand pulled exactly straight does not land on the wrap boundary.
    pub fn span_m(max_length_m: f32, head_size_m: f32) -> f32 {
        1.02 * (2.0 * max_length_m + head_size_m)
    }
}

/// Coordinates beyond this many cells are treated as invalid (keeps `as i64` well defined).
const MAX_CELL_COORD: f32 = 1.0e12;

/// Whether map coordinates `c` (in cells) can be read: finite and within [`MAX_CELL_COORD`].
#[inline]
fn on_map(c: Vec3) -> bool {
    c.is_finite() && c.abs().max_element() < MAX_CELL_COORD
}

/// Most columns per cell width across the light that [`MapGeometry::for_scene`] chooses.
pub const MAX_LATERAL_COLUMNS: u32 = 4;

/// Occluder texel size in cells.
const OCCLUDER_TEXEL_CELLS: f32 = 0.25;

/// Contact-shadow bins across the light, in map columns. Their count does not change the
/// parts a query visits much (a bin's parts shrink as the parts per query grow): measured on
/// smooth × 4 strands of one fibre (shading, 2 threads) 1 column 7.6 s, ½ 6.5 s, ¼ 6.9 s; but
/// the memory grows as 1/bin (the dense preset's 1.1 M segments make 13 M parts at a column).
pub const CONTACT_BIN_COLUMNS: f32 = 1.0;

/// Orthonormal light frame: `x` is the direction the light travels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightFrame {
    pub x: Vec3,
    pub y: Vec3,
    pub z: Vec3,
}

impl LightFrame {
    /// The frame for light travelling along `l` (normalised here; a zero vector falls back to
    /// light travelling down, −Y).
    pub fn new(l: Vec3) -> Self {
        let x = l.normalize_or(Vec3::NEG_Y);
        let (y, z) = x.any_orthonormal_pair();
        Self { x, y, z }
    }

    /// World point -> map coordinates in metres.
    #[inline]
    pub fn to_map(&self, p: Vec3) -> Vec3 {
        Vec3::new(self.x.dot(p), self.y.dot(p), self.z.dot(p))
    }

    /// Map coordinates in metres -> world point.
    #[inline]
    pub fn to_world(&self, m: Vec3) -> Vec3 {
        self.x * m.x + self.y * m.y + self.z * m.z
    }
}

/// Closest depth along a point light's axis at which the map places anything, metres: nearer
/// points (and those behind the light) are not in the map (skipped when filling, unshadowed
/// when read).
pub const CENTRAL_MIN_DEPTH_M: f32 = 1e-4;

/// How world points become map coordinates (metres): X along the light's rays, Y and Z across
/// them, so that every ray of the light is a line of constant (Y, Z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// A directional light: parallel rays along `frame.x`; map coordinates are the frame's.
    Parallel { frame: LightFrame },
    /// A point light at `origin` (Bertails 2005 §6: a light-oriented map for a point source
    /// is angular). Depth is the distance along the axis `frame.x` (from the light toward the
    /// hair); across the axis a point's offset is scaled by `ref_depth_m / depth`, its
    /// central projection onto the plane at `ref_depth_m`. Rays from the light are then lines
    /// of constant (Y, Z), and the whole map (fill, sweep, lookup) works unchanged. A strand
    /// piece keeps its crossing count: its length across the rays and its fibres' width both
    /// shrink by that scale while a column stands for a cone whose cross-section grows with
    /// depth² (see `LightMap::build`).
    Central {
        frame: LightFrame,
        origin: Vec3,
        ref_depth_m: f32,
    },
}

impl Projection {
    /// The light frame (its X is the light's direction, or a point light's axis).
    #[inline]
    pub fn frame(&self) -> LightFrame {
        match *self {
            Projection::Parallel { frame } | Projection::Central { frame, .. } => frame,
        }
    }

    /// Map coordinates of world point `p`, metres (non-finite for a point not in front of a
    /// point light).
    #[inline]
    pub fn point(&self, p: Vec3) -> Vec3 {
        match *self {
            Projection::Parallel { frame } => frame.to_map(p),
            Projection::Central { .. } => match self.central(p) {
                Some((q, s)) => Vec3::new(q.x, q.y * s, q.z * s),
                None => Vec3::NAN,
            },
        }
    }

    /// For a point light: `p` in the light's frame relative to the light, and the lateral
    /// scale ref/depth there; `None` for parallel light or a point not in front of the light.
    #[inline]
    fn central(&self, p: Vec3) -> Option<(Vec3, f32)> {
        match *self {
            Projection::Parallel { .. } => None,
            Projection::Central {
                frame,
                origin,
                ref_depth_m,
            } => {
                let q = frame.to_map(p - origin);
                (q.x > CENTRAL_MIN_DEPTH_M).then(|| (q, ref_depth_m / q.x))
            }
        }
    }

    /// World point of map coordinates `m` (the inverse of [`Projection::point`]).
    pub fn to_world(&self, m: Vec3) -> Vec3 {
        match *self {
            Projection::Parallel { frame } => frame.to_world(m),
            Projection::Central {
                frame,
                origin,
                ref_depth_m,
            } => {
                let s = m.x / ref_depth_m;
                origin + frame.to_world(Vec3::new(m.x, m.y * s, m.z * s))
            }
        }
    }

    /// Unit direction from world point `p` toward the light.
    #[inline]
    pub fn toward_light(&self, p: Vec3) -> Vec3 {
        match *self {
            Projection::Parallel { frame } => -frame.x,
            Projection::Central { frame, origin, .. } => (origin - p).normalize_or(-frame.x),
        }
    }

    /// A point light's reference depth (lateral lengths at depth x are scaled by ref/x), or
    /// `None` for parallel light.
    #[inline]
    pub fn central_ref_depth_m(&self) -> Option<f32> {
        match *self {
            Projection::Parallel { .. } => None,
            Projection::Central { ref_depth_m, .. } => Some(ref_depth_m),
        }
    }

    /// The point of a fibre's surface nearest the light, in map coordinates: map point `m`
    /// on the fibre's axis moved by the fibre's radius `radius_m` along the part of the
    /// direction toward the light that is across the fibre, whose tangent is the chord from
    /// map point `prev_m` to `next_m`. The path tracer lights a fibre's surface, not its
    /// axis: a ray from the axis also meets the fibres touching the lit side, which the lit
    /// side sees past (ACCURACY.md §2, "Converged strands"). For a point light taken in world
    /// space, so its direction and lateral scale are exact; for parallel light in the
    /// (orthonormal) map frame. Light along the fibre has no lit side, and a point the
    /// projection cannot take stays at `m`.
    pub fn lit_side(&self, m: Vec3, prev_m: Vec3, next_m: Vec3, radius_m: f32) -> Vec3 {
        if let Projection::Parallel { .. } = self {
            // The frame is orthonormal: the same geometry in map coordinates, the light
            // toward −X, without the trip through world space.
            let t = (next_m - prev_m).normalize_or_zero();
            let across = (Vec3::NEG_X + t * t.x).normalize_or_zero();
            let q = m + across * radius_m;
            return if q.is_finite() { q } else { m };
        }
        let p = self.to_world(m);
        let t = (self.to_world(next_m) - self.to_world(prev_m)).normalize_or_zero();
        let l = self.toward_light(p);
        let across = (l - t * t.dot(l)).normalize_or_zero();
        if across == Vec3::ZERO {
            return m;
        }
        let q = self.point(p + across * radius_m);
        if q.is_finite() { q } else { m }
    }

    /// A strand of unit tangent `u` at world point `p`, in map coordinates: the image of `u`
    /// (the map displacement per metre along the strand), the share of a metre of strand that
    /// crosses the light's rays (sin ψ for parallel light; the lateral length of the image
    /// times the width scale for a point light: its fibres' width shrinks with the lateral
    /// scale too), and the factor of its fibre volume per map volume (1, or the lateral
    /// scale²).
    #[inline]
    pub fn strand(&self, p: Vec3, u: Vec3) -> (Vec3, f32, f32) {
        match *self {
            Projection::Parallel { frame } => {
                let cos_psi = u.dot(frame.x).clamp(-1.0, 1.0);
                let sin_psi = (1.0 - cos_psi * cos_psi).max(0.0).sqrt();
                (frame.to_map(u), sin_psi, 1.0)
            }
            Projection::Central { frame, .. } => {
                let Some((q, s)) = self.central(p) else {
                    return (Vec3::NAN, 0.0, 0.0);
                };
                let v = frame.to_map(u);
                // d(s·y)/dt = s·(v.y − (y/x)·v.x): the derivative of the central projection.
                let img = Vec3::new(
                    v.x,
                    s * (v.y - q.y / q.x * v.x),
                    s * (v.z - q.z / q.x * v.x),
                );
                let lateral = (img.y * img.y + img.z * img.z).sqrt();
                (img, lateral * s, s * s)
            }
        }
    }
}

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

/// The map: geometry, light frame, and the filled cells of the last build.
#[derive(Clone, Debug)]
pub struct LightMap {
    geom: MapGeometry,
    /// World -> map coordinates (the light frame, and for a point light its central
    /// projection).
    proj: Projection,
    inv_ds: f32,
    /// Map metres to cells along X and to columns along Y, Z.
    inv_cell: Vec3,
    model: CountModel,
    /// Unwrapped index ⌊x/ds⌋ of the first slice in light order.
    first_slice: i64,
    /// Unwrapped cell indices (slice, column j, column k) of the filled cells' bounding box
    /// (`lo > hi` when the map is empty).
    hair_lo: [i64; 3],
    hair_hi: [i64; 3],
    /// Column offsets into `cells` (N² + 1 entries; column c = j·N + k).
    col_start: Vec<u32>,
    /// Filled cells grouped by column, each column sorted by relative slice.
    cells: Vec<Cell>,
    /// For each column, one slot per slice from its first to its last filled slice: the index
    /// in `cells` of the last filled cell at or before that slice. Makes a lookup O(1). Sparse
    /// columns (span over 4 slices per filled cell) have none and are read by binary search,
    /// so the slots never exceed 4 per filled cell, whatever N is.
    slots: Vec<u32>,
    /// Per column, what a lookup needs in one 32-byte record (one cache line holds two): its
    /// cells, its slot table, its first slice and its total crossings.
    index: Vec<ColumnIndex>,
    scratch: build::Scratch,
    stats: MapStats,
    /// The exact fibres in front of each vertex, for one-fibre-per-strand hair
    /// ([`LightMap::build_contact`]).
    contact: Option<contact::ContactShadows>,
}

impl LightMap {
    /// An empty map of the given geometry (allocates N² + 1 column offsets).
    pub fn new(geom: MapGeometry, model: CountModel) -> Self {
        let cols = geom.columns_per_axis() as usize * geom.columns_per_axis() as usize;
        Self {
            geom,
            proj: Projection::Parallel {
                frame: LightFrame::new(Vec3::NEG_Y),
            },
            inv_ds: 1.0 / geom.ds_m,
            inv_cell: Vec3::new(
                1.0 / geom.ds_m,
                1.0 / geom.column_m(),
                1.0 / geom.column_m(),
            ),
            model,
            first_slice: 0,
            hair_lo: [i64::MAX; 3],
            hair_hi: [i64::MIN; 3],
            col_start: vec![0; cols + 1],
            cells: Vec::new(),
            slots: Vec::new(),
            index: vec![ColumnIndex::EMPTY; cols],
            scratch: build::Scratch::default(),
            stats: MapStats::default(),
            contact: None,
        }
    }

    /// Builds (or with `None` drops) the map's contact shadows: the fibres of `input` binned in
    /// the map's current light frame (call after [`LightMap::build`], which sets the frame).
    /// Bins are [`CONTACT_BIN_COLUMNS`] columns wide across the light.
    pub fn build_contact(&mut self, input: Option<&contact::ContactInput>) {
        self.contact = input.map(|i| {
            contact::ContactShadows::build(
                i,
                &self.proj,
                CONTACT_BIN_COLUMNS * self.geom.column_m(),
            )
        });
    }

    pub fn geometry(&self) -> MapGeometry {
        self.geom
    }
    pub fn frame(&self) -> LightFrame {
        self.proj.frame()
    }
    pub fn stats(&self) -> &MapStats {
        &self.stats
    }

    /// The texel size of the solids' entry depths in this map's light frame
    /// ([`OccluderGrid::build`]): a quarter of a cell, metres.
    pub fn occluder_texel_m(&self) -> f32 {
        OCCLUDER_TEXEL_CELLS * self.geom.ds_m
    }

    /// The map's projection of world points into its light frame.
    pub fn projection(&self) -> &Projection {
        &self.proj
    }

    /// The lateral extent of the filled columns (map metres, Y and Z: low and high corners),
    /// or `None` when the map holds no hair.
    pub(crate) fn hair_extent_m(&self) -> Option<(Vec2, Vec2)> {
        if self.hair_lo[1] > self.hair_hi[1] {
            return None;
        }
        let dc = self.geom.column_m();
        let lo = Vec2::new(self.hair_lo[1] as f32, self.hair_lo[2] as f32) * dc;
        let hi = Vec2::new(self.hair_hi[1] as f32 + 1.0, self.hair_hi[2] as f32 + 1.0) * dc;
        Some((lo, hi))
    }

    /// Each sample's clamped ā_f as the last build's fill evaluated it (NaN where it did not).
    pub(crate) fn sample_forward_a(&self) -> &[Vec3] {
        &self.scratch.forward_a
    }

    /// How far a point on an occluder's surface should be moved along its normal before a
    /// lookup, so the solid does not shadow itself: one and a half occluder texels, metres.
    pub fn surface_offset_m(&self) -> f32 {
        1.5 * OCCLUDER_TEXEL_CELLS * self.geom.ds_m
    }

    /// Cell-space coordinates (unwrapped: slices along X, columns along Y and Z) of a world
    /// point.
    #[inline]
    fn cell_coords(&self, p: Vec3) -> Vec3 {
        self.proj.point(p) * self.inv_cell
    }

    /// A key that orders points by the map column they read (the first of their bilinear
    /// taps), so that lookups made in key order walk the map's memory in order; `u32::MAX` for
    /// points off the map. Any order gives the same lookups; this one only makes them faster.
    pub fn lookup_order_key(&self, p: Vec3) -> u32 {
        let c = self.cell_coords(p);
        if !on_map(c) {
            return u32::MAX;
        }
        self.column((c.y - 0.5).floor() as i64, (c.z - 0.5).floor() as i64) as u32
    }

    /// Column index of unwrapped (j, k).
    #[inline]
    fn column(&self, j: i64, k: i64) -> usize {
        let n = self.geom.columns_per_axis() as i64;
        (j.rem_euclid(n) * n + k.rem_euclid(n)) as usize
    }

    /// The filled cells of column `c`, sorted by slice.
    #[inline]
    #[cfg(test)]
    fn column_cells(&self, c: usize) -> &[Cell] {
        &self.cells[self.col_start[c] as usize..self.col_start[c + 1] as usize]
    }

    /// Index in `cells` of the last filled cell of column `c` at or before relative slice
    /// `rel`, or `None` when the column has no cell that early.
    #[inline]
    fn last_at_or_before(&self, c: usize, rel: u32) -> Option<usize> {
        let col = &self.index[c];
        if col.len == 0 || rel < col.base {
            return None;
        }
        let a = col.start as usize;
        if col.slot_len == 0 {
            // A sparse column without a slot table: binary search.
            let k = self.cells[a..a + col.len as usize].partition_point(|x| x.slice <= rel);
            return Some(a + k - 1);
        }
        let off = ((rel - col.base) as usize).min(col.slot_len as usize - 1);
        Some(self.slots[col.slot_start as usize + off] as usize)
    }
}

/// One column's entry in the lookup index: where its cells and slot table are, its first
/// slice, and the crossings of a ray through all of it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub(crate) struct ColumnIndex {
    /// First cell in `cells`, and how many.
    pub start: u32,
    pub len: u32,
    /// First slot in `slots`, and how many (0: no slot table, read by binary search).
    pub slot_start: u32,
    pub slot_len: u32,
    /// Relative slice of the column's first cell.
    pub base: u32,
    /// Σ n of the whole column (the running sum of its last cell), 0 when empty.
    pub total_n: f32,
}

impl ColumnIndex {
    pub(crate) const EMPTY: ColumnIndex = ColumnIndex {
        start: 0,
        len: 0,
        slot_start: 0,
        slot_len: 0,
        base: 0,
        total_n: 0.0,
    };
}

#[cfg(test)]
mod tests;
