//! Building the map each frame: fill (Bertails 2005 §3.1) and transmittance sweep (§3.2, Eq. 3).
//!
//! 1. Fill, in parallel over samples: each sample's statistics once (expected fibre crossings,
//!    their forward-scattering losses and variance, hair volume), and per piece one record
//!    (slice, the first of the 2 × 2 columns it is splatted to, its place in that square, its
//!    depth range).
//! 2. Counting sort of the pieces by that base column, in parallel over fixed chunks
//!    (O(pieces + N²)), which keeps piece order inside a column and carries each sample's
//!    statistics beside its pieces (read in sample order here, not at random in step 3).
//! 3. Per base column, in parallel: a stable counting sort along the light (ties stay in piece
//!    order, so the float sums below always add in the same order whatever the thread count).
//!    Then per column: count its cells (the distinct slices its four base columns bring),
//!    lay the cells out column after column, and merge the four base columns' pieces into
//!    them, each with its bilinear share, sweeping from the first slice to accumulate Eq. 3 in
//!    its dual-scattering form (`column.rs`). Sorting pieces instead of one entry per piece
//!    and column moves a quarter of the bytes; the merge adds in the order that sort of
//!    entries would give, so the cells are the same bits.
//! 4. Slot tables and the per-column lookup index.

use super::column::{
    Piece, PieceStats, Placed, SPLAT, column_cells, merge_column, sort_column, splat_weight,
};
use super::{Cell, ColumnIndex, LightFrame, LightMap, MAX_CELL_COORD};
use crate::fiber::Fiber;
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// How expected crossing counts become transmittance (see the module doc of `map`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CountModel {
    /// Average over Poisson-distributed crossings: T_f = exp(−n̄(1 − ā_f)), direct = exp(−n̄).
    #[default]
    Poisson,
    /// A ray meeting exactly the mean count: T_f = ā_f^n̄, direct = 0^n̄ read as exp(−n̄).
    MeanCount,
}

/// What the map is built from: render-strand samples (world) and the fibre they are made of.
pub struct MapBuildInput<'a> {
    /// Sample positions, metres (world).
    pub positions: &'a [Vec3],
    /// Unit tangents at the samples.
    pub tangents: &'a [Vec3],
    /// Hair length each sample stands for, metres, times its fibre share: the length of
    /// *fibre*, in units of the strand's F fibres (`StrandGeometry::lengths_m`).
    pub lengths_m: &'a [f32],
    /// Share of its strand's fibres present at each sample, in (0, 1]
    /// (`StrandGeometry::fibre_share`; missing entries count as 1). The piece of strand a
    /// sample stands for is `lengths_m / share` long: a tapered tip's fewer fibres still run
    /// along its whole piece, so its crossings are spread over that length, not packed into a
    /// shorter one.
    pub fiber_share: &'a [f32],
    /// Real fibres per render strand.
    pub fibers_per_strand: f32,
    /// The light's geometry: the direction it travels, or where a point light is.
    pub light: MapLight,
    /// The fibre (radius and forward-scattering statistics).
    pub fiber: &'a Fiber,
}

impl MapBuildInput<'_> {
    /// Length of strand sample `s` stands for, metres: `lengths_m[s] / fibre_share[s]` (the
    /// fibre length it fills, undone of the taper), or `lengths_m[s]` where the share is
    /// missing, not in (0, 1) or gives no finite length.
    #[inline]
    pub fn span_m(&self, s: usize) -> f32 {
        let len = self.lengths_m.get(s).copied().unwrap_or(0.0);
        match self.fiber_share.get(s) {
            Some(&share) if share > 0.0 && share < 1.0 && (len / share).is_finite() => len / share,
            _ => len,
        }
    }
}

/// What the map needs to know of a light: where its rays go.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MapLight {
    /// Parallel rays travelling along this direction (need not be normalised).
    Directional(Vec3),
    /// Rays from `position_m`; the map's axis points from it toward `aim_m` (the middle of
    /// the hair: the head's centre).
    Point { position_m: Vec3, aim_m: Vec3 },
}

impl From<Vec3> for MapLight {
    fn from(travel: Vec3) -> Self {
        MapLight::Directional(travel)
    }
}

impl MapLight {
    /// The map geometry of `light`, a point light aimed at `aim_m`.
    pub fn of(light: &crate::light::Light, aim_m: Vec3) -> Self {
        match *light {
            crate::light::Light::Directional { travel, .. } => MapLight::Directional(travel.get()),
            crate::light::Light::Point { position_m, .. } => MapLight::Point { position_m, aim_m },
        }
    }

    /// The projection for hair at `positions`: for a point light, the reference plane is at
    /// the nearest hair along the axis, so no hair is magnified across the light (the modulo
    /// map cannot overflow for it) and the nearest hair keeps the map's full resolution. The
    /// plane is at least a tenth of the way to the aim point (a light inside the hair, which
    /// scene files refuse, would otherwise put it at the light). The minimum is exact, so the
    /// projection does not depend on the thread count.
    pub fn projection(&self, positions: &[Vec3]) -> super::Projection {
        match *self {
            MapLight::Directional(travel) => super::Projection::Parallel {
                frame: LightFrame::new(travel),
            },
            MapLight::Point { position_m, aim_m } => {
                let axis = aim_m - position_m;
                let dist = axis.length();
                let frame = LightFrame::new(if dist > 0.0 { axis } else { Vec3::NEG_Y });
                let nearest = positions
                    .par_iter()
                    .with_min_len(4096)
                    .map(|p| frame.x.dot(*p - position_m))
                    .filter(|d| d.is_finite())
                    .reduce(|| f32::INFINITY, f32::min);
                let ref_depth_m = nearest
                    .min(dist)
                    .max(0.1 * dist)
                    .max(super::CENTRAL_MIN_DEPTH_M);
                super::Projection::Central {
                    frame,
                    origin: position_m,
                    ref_depth_m,
                }
            }
        }
    }
}

/// Figures of the last build.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MapStats {
    /// Samples filled (non-finite samples are skipped and counted in `skipped`).
    pub samples: usize,
    pub skipped: usize,
    /// Filled cells after merging.
    pub filled_cells: usize,
    /// Columns holding at least one filled cell.
    pub columns: usize,
    /// Largest hair volume fraction of a cell.
    pub peak_volume_fraction: f32,
    /// Volume of the filled cells, m³ (a measure of the hair's volume at map resolution).
    pub hair_volume_m3: f32,
    /// True when the hair extends over more than N cells along an axis, so the modulo
    /// indexing aliases distant hair (the map is too small for the scene).
    pub overflow: bool,
}

/// Bounding box of filled cells in unwrapped cell indices (x, y, z).
#[derive(Clone, Copy, Debug)]
struct Extent {
    lo: [i64; 3],
    hi: [i64; 3],
}

impl Extent {
    const EMPTY: Extent = Extent {
        lo: [i64::MAX; 3],
        hi: [i64::MIN; 3],
    };

    #[inline]
    fn include(&mut self, c: [i64; 3]) {
        for ((lo, hi), v) in self.lo.iter_mut().zip(&mut self.hi).zip(c) {
            *lo = (*lo).min(v);
            *hi = (*hi).max(v);
        }
    }

    fn union(a: Extent, b: Extent) -> Extent {
        if b.lo[0] > b.hi[0] {
            return a; // b is empty
        }
        let mut u = a;
        u.include(b.lo);
        u.include(b.hi);
        u
    }
}

/// Reusable buffers: after the first frame, a build allocates nothing.
#[derive(Clone, Debug, Default)]
pub(super) struct Scratch {
    /// Per sample: what each of its pieces carries.
    stats: Vec<PieceStats>,
    /// Per sample: the forward attenuation ā_f (clamped to [0, 1]) its pieces carry, NaN for a
    /// sample the fill skipped; the skin's texture reads it instead of evaluating it again.
    pub(super) forward_a: Vec<Vec3>,
    /// Per sample piece: the fill's output, in piece order.
    entries: Vec<Piece>,
    /// The filled pieces grouped by base column (counting sort), each column in piece order.
    sorted: Vec<Placed>,
    /// Where each base column's pieces start in `sorted` (N² + 1).
    base_start: Vec<u32>,
    /// Per piece of `sorted`: its [`Placed::mark`] (what counting a column's cells reads).
    marks: Vec<u32>,
    col_count: Vec<u32>,
}

/// Most slots a column's slot table may hold per filled cell (a sparser column is read by binary
/// search): bounds the tables by the cells, whatever the span of a column.
pub(super) const SLOT_SPAN_PER_CELL: usize = 4;

/// Columns sorted, counted or merged by one parallel task.
const COLUMNS_PER_TASK: usize = 1024;

/// The columns `c0..c1` of merge task `task` of `cols`.
fn task_columns(task: usize, cols: usize) -> (usize, usize) {
    (
        task * COLUMNS_PER_TASK,
        ((task + 1) * COLUMNS_PER_TASK).min(cols),
    )
}

/// Most pieces a sample is split into (a sample longer than 8 cells still makes 8).
pub(super) const MAX_PIECES: usize = 8;

impl LightMap {
    /// Rebuilds the map for `input` (fill + sweep). Allocation-free once warmed up.
    pub fn build(&mut self, input: &MapBuildInput) {
        self.proj = input.light.projection(input.positions);
        let n = self.geom.n as i64;
        let ncol = self.geom.columns_per_axis() as i64;
        let ds = self.geom.ds_m;
        let dc = self.geom.column_m();
        let r = input.fiber.params().radius_m;
        // n = F·ℓ·2r·sinψ / dc² crossings over a column of cross-section dc²; volume fraction
        // = F·ℓ·πr² / (ds·dc²).
        let crossing_scale = input.fibers_per_strand * 2.0 * r / (dc * dc);
        let volume_scale = input.fibers_per_strand * std::f32::consts::PI * r * r / (ds * dc * dc);
        let count = input
            .positions
            .len()
            .min(input.tangents.len())
            .min(input.lengths_m.len());
        let proj = self.proj;
        let inv_cell = self.inv_cell;
        let model = self.model;
        let fiber = input.fiber;

        // 1. Fill. A sample stands for a piece of strand of length ℓ along its tangent; when ℓ
        // exceeds a cell, it is split into `pieces` equal parts spread along the tangent,
        // so a strand fills every cell it passes through instead of a dotted line of them (at
        // the default resolution samples are 11 mm apart and cells 7.4 mm).
        let max_len = (0..count)
            .map(|s| input.span_m(s))
            .filter(|l| l.is_finite())
            .fold(0.0f32, f32::max);
        let pieces = ((max_len / ds).ceil() as usize).clamp(1, MAX_PIECES);
        let entries = &mut self.scratch.entries;
        let stats = &mut self.scratch.stats;
        // Exact reservations: a vector that grows by `resize` may double its capacity, which
        // the memory budget would have to count twice.
        entries.reserve_exact((count * pieces).saturating_sub(entries.len()));
        entries.resize(count * pieces, Piece::default());
        stats.reserve_exact(count.saturating_sub(stats.len()));
        stats.resize(count, PieceStats::default());
        let forward_a = &mut self.scratch.forward_a;
        forward_a.reserve_exact(count.saturating_sub(forward_a.len()));
        forward_a.resize(count, Vec3::NAN);
        // Per sample: the fibre's per-crossing statistics once, then its pieces. The extent of
        // the filled cells (first slice, overflow check) comes from an exact min/max reduce,
        // so the reduction order does not matter.
        let extent = entries
            .par_chunks_mut(pieces)
            .zip(stats.par_iter_mut().zip(forward_a.par_iter_mut()))
            .enumerate()
            .with_min_len(512)
            .map(|(s, (out, (stat, forward)))| {
                let u = input.tangents[s];
                let len_total = input.lengths_m[s];
                let span_total = input.span_m(s);
                let p = input.positions[s];
                let p0 = proj.point(p) * inv_cell;
                if !(p0.abs().max_element() < MAX_CELL_COORD
                    && u.is_finite()
                    && len_total.is_finite()
                    && len_total >= 0.0)
                {
                    out.iter_mut().for_each(|e| e.col = u32::MAX);
                    *forward = Vec3::NAN;
                    return (Extent::EMPTY, 1usize);
                }
                // The strand's image in map coordinates; for a point light its crossing and
                // volume weights carry the lateral scale (see `Projection::strand`).
                let (u_map, across, volume_weight) = proj.strand(p, u);
                let len = len_total / pieces as f32;
                let crossings = crossing_scale * len * across;
                let fs = fiber.forward_scatter(u.dot(proj.toward_light(p)).clamp(-1.0, 1.0));
                let a = fs.a_f.clamp(Vec3::ZERO, Vec3::ONE);
                *forward = a;
                let loss = match model {
                    CountModel::Poisson => Vec3::ONE - a,
                    CountModel::MeanCount => -a.max(Vec3::splat(1e-30)).ln(),
                };
                *stat = PieceStats {
                    n: crossings,
                    loss: (loss * crossings).to_array(),
                    sigma2: (fs.beta_f2 * crossings).to_array(),
                    volume_fraction: volume_scale * len * volume_weight,
                };
                let u_cells = u_map * inv_cell;
                // Half the depth a piece spans along the light, in cells (its whole length of
                // strand, also where a tapered tip has fewer fibres).
                let half_depth = 0.5 * (u_cells.x * span_total / pieces as f32).abs();
                let mut ext = Extent::EMPTY;
                for (q, e) in out.iter_mut().enumerate() {
                    let along = ((q as f32 + 0.5) / pieces as f32 - 0.5) * span_total;
                    // The piece's offset, in cells, is rounded to 1/1024 of a cell (7 µm at the
                    // default size): then moving the hair by whole cells moves every piece by
                    // exactly whole cells too (adding numbers on that grid is exact in f32),
                    // which keeps the modulo map's translation invariance exact.
                    let offset = (u_cells * along * 1024.0).round() / 1024.0;
                    let at = p0 + offset;
                    let c = at.floor();
                    let i = c.x as i64;
                    // The piece's depth range inside its slice (the part of it beyond the
                    // slice's faces is counted at the face: pieces are at most a cell long).
                    let lambda = at.x - c.x;
                    let q16 = |v: f32| (v.clamp(0.0, 1.0) * 65535.0).round() as u16;
                    let depth = [q16(lambda - half_depth), q16(lambda + half_depth)];
                    // Across the light, the piece is shared by the four nearest columns with
                    // bilinear (tent) weights about their centres, so a strand moving across
                    // a column boundary changes the light smoothly (a box fill shows the cell
                    // grid as blotches on hair lying side by side). The piece keeps the first
                    // of them and its place in their square; the merge takes the shares.
                    let lat = Vec2::new(at.y, at.z) - Vec2::splat(0.5);
                    let l0 = lat.floor();
                    let frac = (lat - l0).to_array();
                    let (j0, k0) = (l0.x as i64, l0.y as i64);
                    ext.include([i, j0, k0]);
                    ext.include([i, j0 + 1, k0 + 1]);
                    let shared = (0..SPLAT).any(|t| splat_weight(frac, t) > 0.0);
                    *e = Piece {
                        slice: i,
                        col: if shared {
                            (j0.rem_euclid(ncol) * ncol + k0.rem_euclid(ncol)) as u32
                        } else {
                            u32::MAX
                        },
                        sample: s as u32,
                        id: (s * pieces + q) as u32,
                        frac,
                        depth,
                    };
                }
                (ext, 0usize)
            })
            .reduce(
                || (Extent::EMPTY, 0),
                |a, b| (Extent::union(a.0, b.0), a.1 + b.1),
            );
        let (extent, skipped) = extent;
        let filled_pieces = entries.par_iter().filter(|e| e.col != u32::MAX).count();
        self.first_slice = if filled_pieces > 0 { extent.lo[0] } else { 0 };
        // Where the hair is, unwrapped: a lookup outside it must not read hair that the
        // modulo indexing aliases there (a dancer's body reaches far beyond the hair's span).
        self.hair_lo = if filled_pieces > 0 {
            extent.lo
        } else {
            [i64::MAX; 3]
        };
        self.hair_hi = if filled_pieces > 0 {
            extent.hi
        } else {
            [i64::MIN; 3]
        };
        let overflow = filled_pieces > 0
            && (extent.hi[0] - extent.lo[0] >= n
                || (1..3).any(|a| extent.hi[a] - extent.lo[a] >= ncol));
        let samples = count - skipped;

        // 2. Counting sort by base column, in parallel over fixed chunks of the pieces: each
        // chunk counts its pieces per column, the counts become per-chunk write cursors (chunk
        // k writes after chunks 0..k in every column), and the chunks scatter side by side
        // into disjoint places. Within a column the pieces keep their order, so the result is
        // the sequential sort's whatever the chunking or the thread count.
        let cols = (ncol * ncol) as usize;
        let chunks = sort_chunks(entries.len(), cols);
        let chunk_len = entries.len().div_ceil(chunks).max(1);
        let col_count = &mut self.scratch.col_count;
        col_count.clear();
        col_count.resize(cols * chunks, 0);
        col_count
            .par_chunks_mut(cols)
            .zip(entries.par_chunks(chunk_len))
            .for_each(|(count, part)| {
                for e in part.iter().filter(|e| e.col != u32::MAX) {
                    count[e.col as usize] += 1;
                }
            });
        // Per-chunk counts become write cursors, in passes that walk the counters in memory
        // order (a column-major walk strides over the chunks' rows): column totals, their
        // exclusive prefix, then each chunk's cursor after the earlier chunks' pieces.
        let base_start = &mut self.scratch.base_start;
        base_start.clear();
        base_start.resize(cols + 1, 0);
        for row in col_count.chunks_exact(cols) {
            for (base, n) in base_start.iter_mut().zip(row) {
                *base += n;
            }
        }
        let mut acc = 0u32;
        for base in base_start.iter_mut() {
            (*base, acc) = (acc, acc + *base);
        }
        // The cursors run in `col_start`, which takes the cells' offsets afterwards.
        let col_base = &mut self.col_start[..cols];
        col_base.copy_from_slice(&base_start[..cols]);
        for row in col_count.chunks_exact_mut(cols) {
            for (base, count) in col_base.iter_mut().zip(row) {
                let n_k = *count;
                *count = *base; // becomes this chunk's write cursor in the column
                *base += n_k;
            }
        }
        let sorted = &mut self.scratch.sorted;
        sorted.reserve_exact(filled_pieces.saturating_sub(sorted.len()));
        sorted.resize(filled_pieces, Placed::default());
        let first = self.first_slice;
        let stats = &self.scratch.stats;
        let out = SharedSlice(sorted.as_mut_ptr());
        let out = &out;
        col_count
            .par_chunks_mut(cols)
            .zip(entries.par_chunks(chunk_len))
            .for_each(|(cursor, part)| {
                for e in part.iter().filter(|e| e.col != u32::MAX) {
                    let at = cursor[e.col as usize] as usize;
                    cursor[e.col as usize] += 1;
                    // Relative slice, wrapping modulo N (Bertails Figure 3).
                    let rel = (e.slice - first).rem_euclid(n) as u32;
                    // SAFETY: `at` < filled_pieces (the cursors partition 0..filled_pieces:
                    // chunk k's cursor in column c runs over its own count of places after the
                    // column's start and the earlier chunks' counts), so every place is written
                    // by exactly one chunk, once, and `sorted` is not otherwise touched here.
                    let placed = Placed::new(e, rel, stats[e.sample as usize]);
                    unsafe { out.0.add(at).write(placed) };
                }
            });

        // 3. Per base column: sort along the light (ties in piece order, so the float sums
        // below always add in the same order whatever the thread count), and mark each piece
        // with its slice and which of its shares are positive. Then per column: count its
        // cells from the marks of the four base columns that share into it, lay the cells out
        // column after column, and merge those base columns' pieces into them and sweep them
        // (`column.rs`).
        let tasks = cols.div_ceil(COLUMNS_PER_TASK);
        let base_start = &self.scratch.base_start;
        let marks = &mut self.scratch.marks;
        marks.reserve_exact(filled_pieces.saturating_sub(marks.len()));
        marks.resize(filled_pieces, 0);
        let out = SharedSlice(sorted.as_mut_ptr());
        let out = &out;
        let marks_out = SharedSlice(marks.as_mut_ptr());
        let marks_out = &marks_out;
        // One job per task: the hair fills few of the columns (`raster::lines` on rayon's
        // splitting); the same below.
        (0..tasks).into_par_iter().with_max_len(1).for_each(|task| {
            let (c0, c1) = task_columns(task, cols);
            for c in c0..c1 {
                let (a, b) = (base_start[c] as usize, base_start[c + 1] as usize);
                // SAFETY: base columns own disjoint ranges a..b of `sorted` and `marks` (the
                // prefix sums of their counts), each is handled by one task only, and neither
                // is otherwise touched here.
                let (col, col_marks) = unsafe {
                    (
                        std::slice::from_raw_parts_mut(out.0.add(a), b - a),
                        std::slice::from_raw_parts_mut(marks_out.0.add(a), b - a),
                    )
                };
                sort_column(col);
                for (m, p) in col_marks.iter_mut().zip(col.iter()) {
                    *m = p.mark();
                }
            }
        });
        let (sorted, marks) = (&self.scratch.sorted[..], &self.scratch.marks[..]);
        let ncol_u = ncol as usize;
        // The row or column before `m`, wrapping.
        let back = |m: usize| if m == 0 { ncol_u - 1 } else { m - 1 };
        // Where the four base columns whose pieces share into column (j, k) lie, by share
        // index.
        let sources = |j: usize, k: usize| {
            let base = |j: usize, k: usize| {
                let c = j * ncol_u + k;
                base_start[c] as usize..base_start[c + 1] as usize
            };
            [
                base(j, k),
                base(j, back(k)),
                base(back(j), k),
                base(back(j), back(k)),
            ]
        };
        let col_cells = &mut col_count[..cols];
        let columns = col_cells
            .par_chunks_mut(COLUMNS_PER_TASK)
            .enumerate()
            .with_max_len(1)
            .map(|(task, counts)| {
                let c0 = task_columns(task, cols).0;
                let mut filled_columns = 0;
                // Row by row of columns; a row whose base rows (its own and the one before)
                // hold no piece has no cell.
                let mut at = 0;
                while at < counts.len() {
                    let (j, k0) = ((c0 + at) / ncol_u, (c0 + at) % ncol_u);
                    let run = (ncol_u - k0).min(counts.len() - at);
                    let row_pieces =
                        |j: usize| base_start[(j + 1) * ncol_u] - base_start[j * ncol_u];
                    let row = &mut counts[at..at + run];
                    if row_pieces(j) == 0 && row_pieces(back(j)) == 0 {
                        row.fill(0);
                    } else {
                        for (k, count) in (k0..).zip(row.iter_mut()) {
                            *count = column_cells(sources(j, k).map(|r| &marks[r])) as u32;
                            filled_columns += usize::from(*count > 0);
                        }
                    }
                    at += run;
                }
                filled_columns
            })
            .sum::<usize>();
        let mut acc = 0u32;
        for (c, cells) in col_cells.iter().enumerate() {
            self.col_start[c] = acc;
            acc += cells;
        }
        self.col_start[cols] = acc;
        let filled = acc as usize;
        self.cells
            .reserve_exact(filled.saturating_sub(self.cells.len()));
        self.cells.resize(filled, Cell::default());
        let cells_out = SharedSlice(self.cells.as_mut_ptr());
        let cells_out = &cells_out;
        let col_start = &self.col_start;
        (0..tasks).into_par_iter().with_max_len(1).for_each(|task| {
            let (c0, c1) = task_columns(task, cols);
            for c in c0..c1 {
                let (a, b) = (col_start[c] as usize, col_start[c + 1] as usize);
                if a < b {
                    // SAFETY: columns own disjoint ranges a..b of `cells` (the prefix sums of
                    // their cell counts), each column is merged by one task only, and `cells`
                    // is not otherwise touched here.
                    let cells =
                        unsafe { std::slice::from_raw_parts_mut(cells_out.0.add(a), b - a) };
                    merge_column(sources(c / ncol_u, c % ncol_u).map(|r| &sorted[r]), cells);
                }
            }
        });

        // The lookup index, one record per column, and the slot tables: per column, the last
        // filled cell at or before each slice of its span. A sparse column (span over
        // SLOT_SPAN_PER_CELL slices per filled cell) gets none and is read by binary search,
        // so the tables never hold more than that many slots per cell.
        self.slots.clear();
        self.index.resize(cols, ColumnIndex::EMPTY);
        for c in 0..cols {
            let (a, b) = (self.col_start[c] as usize, self.col_start[c + 1] as usize);
            if a == b {
                self.index[c] = ColumnIndex::EMPTY;
                continue;
            }
            let slot_start = self.slots.len();
            let base = self.cells[a].slice;
            let span = (self.cells[b - 1].slice - base) as usize + 1;
            if span <= SLOT_SPAN_PER_CELL * (b - a) {
                let mut idx = a;
                for cell in a..b {
                    let s = self.cells[cell].slice;
                    while self.slots.len() - slot_start < (s - base) as usize {
                        self.slots.push(idx as u32);
                    }
                    self.slots.push(cell as u32);
                    idx = cell;
                }
            }
            self.index[c] = ColumnIndex {
                start: a as u32,
                len: (b - a) as u32,
                slot_start: slot_start as u32,
                slot_len: (self.slots.len() - slot_start) as u32,
                base,
                total_n: self.cells[b - 1].n_sum,
            };
        }

        // A maximum does not depend on the order of the reduction.
        let peak = self
            .cells
            .par_iter()
            .map(|c| c.volume_fraction)
            .reduce(|| 0.0f32, f32::max);
        self.stats = MapStats {
            samples,
            skipped: count - samples,
            filled_cells: filled,
            columns,
            peak_volume_fraction: peak,
            hair_volume_m3: filled as f32 * ds * dc * dc,
            overflow,
        };
    }
}

/// Chunks of the counting sort: as many as fit with their per-column counters in no more memory
/// than the entries' own count (so a huge sparse map sorts in one chunk, as before), at most 8.
/// The result does not depend on it.
fn sort_chunks(entries: usize, cols: usize) -> usize {
    (entries / cols.max(1)).clamp(1, MAX_SORT_CHUNKS)
}

/// Most chunks of the parallel counting sort.
pub(super) const MAX_SORT_CHUNKS: usize = 8;

/// A buffer as a raw pointer that parallel chunks write through, each to its own places (see
/// the SAFETY notes at the writes).
struct SharedSlice<T>(*mut T);
// SAFETY: the chunks write disjoint places of one live allocation, which outlives the scope.
unsafe impl<T: Send> Sync for SharedSlice<T> {}
