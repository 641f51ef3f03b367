//! Multiply scattered light by light paths traced through the hair volume (Moon, Walter &
//! Marschner 2008's two-pass scheme, with their spherical harmonics replaced by the paths'
//! own directions): an alternative to dual scattering's global and local terms where light
//! reaches hair off its shadow ray.
//!
//! Why: dual scattering (Zinke 2008) carries forward-scattered light along the straight shadow
//! ray only. Against a path tracer, back-lit dense hair then leaves a band inside the
//! silhouette 5–20× too dark: it is lit by light scattered four or more times that diffuses in
//! from the rim (ACCURACY.md §2, "How many bounces light the back-lit band"). Light carried
//! through the volume lights it; a single scalar per cell gets the colours wrong, because the
//! fibre's response depends on where the light comes from (§2, "The volume solve,
//! prototyped"). So each cell keeps its light by direction and the fibre's far-field BCSDF
//! is integrated against it.
//!
//! How:
//! 1. **Cells.** A grid of `cell_m` cubes over the hair. Each render-strand point stands for a
//!    piece of fibre (its `lengths_m` times the strand's fibres), cut into pieces at most half a
//!    cell long, each filed under the cell of its middle with its tangent.
//! 2. **Paths** ([`trace`], started by `emit.rs`). A directional light's paths enter from the
//!    columns across it that a cell holding fibre reaches (a path anywhere else would cross
//!    no fibre), each with power E·A/N for the columns' area A; a point light's leave it into
//!    the directions of the cone of the grid's bounding sphere that a cell holding fibre
//!    subtends, each with I·Ω/N for their solid angle Ω. Each block of paths draws from
//!    its own stream (`rng::SplitMix64::stream`). A path flies by delta tracking (an empty
//!    cell costs a bit read, [`Cells::busy`]): the majorant of a
//!    cell is 2r·n·ℓ_max/V (n pieces, the longest ℓ_max); at a tentative collision a piece is
//!    drawn uniformly and hit with probability (ℓ/ℓ_max)·sin ψ (ψ between path and fibre), so
//!    real collisions occur at the fibres' cross-section per volume, 2r Σ ℓ sin ψ / V.
//!    At each hit the path scatters by the Chiang model (`fiber::chiang_sample`). Russian
//!    roulette ends weak paths without bias. A cell wholly inside a solid (head, body) absorbs
//!    what enters it (skin's own reflection is not carried).
//! 3. **Tallies.** After its first scattering, each straight flight through a cell leaves a
//!    record: the direction it came from and its power times the length flown in the cell.
//!    Σ records / V estimates ∫ L(ω) dω there, direction by direction (the track-length
//!    estimator), for light scattered at least once. Records are kept only in cells a seen
//!    point can gather from (a piece of fibre within one cell), merged wave by wave into 8 × 8
//!    direction bins per cell (`bins.rs`), each keeping its light and mean direction.
//! 4. **Gather** ([`PhotonVolume::indirect`]). A seen point adds Σ S(ωi, ωo) cos θi · light
//!    over the bins of one cell near it (drawn with trilinear probabilities from a hash
//!    of the point, so the cells blend without an 8× cost). The light that reaches it directly
//!    is the single-scattering shader's, as in MWM08: the two add up to all orders.
//!
//! Deterministic for any thread count: paths are traced in fixed blocks, each from its own
//! seed, and each wave's records are added to the bins in block order.

// `!(a < b)` on floats is meant: it is true for NaN, which must take the safe branch.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod bins;
mod emit;
mod trace;

use crate::fiber::{Fiber, LightAtPoint, ShadingMode};
use crate::light::Light;
use glam::{UVec3, Vec3};
use rayon::prelude::*;

/// Light that crossed no fibre: the gather takes the shader's S cos θi per unit irradiance.
const UNSHADOWED: LightAtPoint = LightAtPoint::UNSHADOWED;

/// Most cells per axis (a larger extent gets larger cells).
const MAX_CELLS_PER_AXIS: usize = 256;
/// Blocks of paths traced between two merges into the bins (64 × 1,024 paths): what bounds the
/// flights held at once.
const WAVE_BLOCKS: u32 = 64;
/// Flights a path leaves, for the memory estimate: measured 11 on average on dense blond hair
/// (the most scattering of the presets), held in vectors that may double: 32 covers it.
const FLIGHTS_PER_PATH: u64 = 32;

/// How the volume is built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightPathParams {
    /// Cell edge, metres (> 0).
    pub cell_m: f32,
    /// Light paths per light, each sent where it meets the hair's columns (`emit.rs`). The
    /// default, 2,000,000, is what dense hair's darkest tenth needs: with 1,000,000 brown
    /// side-lit read 0.49–1.24 of the path tracer's, with 2,000,000 0.57–1.46 (ACCURACY.md §2,
    /// "Paths sent where the hair is"): the fewer the paths, the noisier the dim cells, and
    /// noise darkens a darkest tenth.
    pub paths: u32,
    /// Seed of the paths' random numbers.
    pub seed: u64,
    /// A cell's flights merged into this many × this many direction bins (octahedral,
    /// `bins.rs`), 1..=16. Default 8: against keeping every flight, the gather 1.5× faster at
    /// 4 M paths, the means moved by at most 2% (ACCURACY.md §2), and the memory bounded.
    pub bins_per_axis: u32,
    /// Most bytes the bins may take: cells are enlarged (by 2^⅓ at a time) until the cells
    /// points gather from fit (dense one-fibre hair at 4 mm: 125,000 cells, 384 MB).
    pub max_bins_bytes: u64,
}

impl Default for LightPathParams {
    fn default() -> Self {
        Self {
            cell_m: 0.004,
            paths: 2_000_000,
            seed: 0x5EED_0F11_6A7E,
            bins_per_axis: 8,
            max_bins_bytes: 768_000_000,
        }
    }
}

/// The hair as fibre pieces filed by cell (step 1 of the module doc).
#[derive(Clone, Debug, Default)]
pub(crate) struct Cells {
    pub(crate) origin: Vec3,
    pub(crate) cell_m: f32,
    pub(crate) dims: UVec3,
    /// Per cell, its pieces' range: `starts[c]..starts[c + 1]`.
    pub(crate) starts: Vec<u32>,
    /// Pieces' unit tangents and lengths of fibre (metres × fibres), by cell.
    pub(crate) tangents: Vec<Vec3>,
    pub(crate) lengths: Vec<f32>,
    /// Per cell, the longest piece (metres of fibre).
    pub(crate) longest: Vec<f32>,
    /// Per cell, whether it lies wholly inside a solid (head, body): light that enters it is
    /// absorbed. Empty: no solids.
    pub(crate) solid: Vec<bool>,
    /// Per cell, its place among the cells a point can gather from (those with a piece of
    /// fibre within one cell: [`PhotonVolume::indirect`] picks among the 2×2×2 around a
    /// point), or [`NO_SLOT`]: light is kept only there.
    pub(crate) slot: Vec<u32>,
    pub(crate) slots: usize,
    /// One bit per cell (cell `i` is bit `i % 64` of word `i / 64`): set where a path's
    /// step reads anything (pieces, a slot or a solid). Most steps are through empty space
    /// (94% on the smooth dance), which then costs one bit read from a small array.
    pub(crate) busy: Vec<u64>,
}

/// [`Cells::slot`] of a cell no point gathers from.
pub(crate) const NO_SLOT: u32 = u32::MAX;

impl Cells {
    /// The cell holding `p`, or `None` outside the grid.
    pub(crate) fn cell_of(&self, p: Vec3) -> Option<usize> {
        let q = (p - self.origin) / self.cell_m;
        if !(q.x >= 0.0 && q.y >= 0.0 && q.z >= 0.0) {
            return None;
        }
        let (x, y, z) = (q.x as u32, q.y as u32, q.z as u32);
        let d = self.dims;
        (x < d.x && y < d.y && z < d.z).then(|| self.index(UVec3::new(x, y, z)))
    }

    pub(crate) fn index(&self, c: UVec3) -> usize {
        ((c.z * self.dims.y + c.y) * self.dims.x + c.x) as usize
    }

    /// The coordinates of cell `i` ([`Cells::index`]'s inverse).
    pub(crate) fn coords(&self, i: usize) -> UVec3 {
        let (i, d) = (i as u32, self.dims);
        UVec3::new(i % d.x, (i / d.x) % d.y, i / (d.x * d.y))
    }

    pub(crate) fn count(&self) -> usize {
        (self.dims.x * self.dims.y * self.dims.z) as usize
    }

    /// The cells holding a piece of fibre, in cell order.
    pub(crate) fn filled(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.count()).filter(|&i| self.starts[i + 1] > self.starts[i])
    }

    /// Whether a path's step through cell `index` reads anything ([`Cells::busy`]).
    #[inline]
    pub(crate) fn is_busy(&self, index: usize) -> bool {
        self.busy[index / 64] >> (index % 64) & 1 != 0
    }

    fn mark_busy(&mut self, index: usize) {
        self.busy[index / 64] |= 1 << (index % 64);
    }

    /// Marks the cells whose centre lies deeper than half their diagonal inside a solid
    /// (`depth_m(p)`: how deep `p` lies inside one, metres, 0 outside), so wholly inside.
    fn mark_solids(&mut self, depth_m: &(impl Fn(Vec3) -> f32 + Sync)) {
        let half_diagonal = 0.5 * 3f32.sqrt() * self.cell_m;
        let cells = &*self;
        let solid = (0..self.count())
            .into_par_iter()
            .map(|i| {
                let centre = cells.origin + (cells.coords(i).as_vec3() + 0.5) * cells.cell_m;
                depth_m(centre) > half_diagonal
            })
            .collect();
        self.solid = solid;
        for i in 0..self.count() {
            if self.solid[i] {
                self.mark_busy(i);
            }
        }
    }

    /// Files the pieces of fibre the points stand for (module doc, step 1).
    fn build(
        positions: &[Vec3],
        tangents: &[Vec3],
        lengths_m: &[f32],
        fibers_per_strand: f32,
        cell_m: f32,
    ) -> Option<Cells> {
        let n = positions.len().min(tangents.len()).min(lengths_m.len());
        let usable = |i: usize| {
            positions[i].is_finite()
                && tangents[i].is_finite()
                && lengths_m[i].is_finite()
                && lengths_m[i] > 0.0
        };
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for i in (0..n).filter(|&i| usable(i)) {
            let reach = Vec3::splat(0.5 * lengths_m[i]);
            lo = lo.min(positions[i] - reach);
            hi = hi.max(positions[i] + reach);
        }
        if !(lo.is_finite() && hi.is_finite() && cell_m > 0.0 && fibers_per_strand > 0.0) {
            return None;
        }
        let extent = hi - lo;
        let cell_m = cell_m.max(extent.max_element() / (MAX_CELLS_PER_AXIS - 2) as f32);
        let origin = lo - Vec3::splat(cell_m);
        let dims = ((extent / cell_m).ceil() + Vec3::splat(2.0)).as_uvec3();
        let mut cells = Cells {
            origin,
            cell_m,
            dims,
            ..Default::default()
        };
        // Pieces of at most half a cell: (cell, tangent, length), then a counting sort by cell.
        let half = 0.5 * cell_m;
        let mut pieces: Vec<(u32, Vec3, f32)> = Vec::new();
        for i in (0..n).filter(|&i| usable(i)) {
            let (p, u, len) = (positions[i], tangents[i].normalize_or_zero(), lengths_m[i]);
            if u == Vec3::ZERO {
                continue;
            }
            let k = ((len / half).ceil() as usize).clamp(1, 64);
            let step = len / k as f32;
            for j in 0..k {
                let at = p + u * (step * (j as f32 + 0.5) - 0.5 * len);
                if let Some(c) = cells.cell_of(at) {
                    pieces.push((c as u32, u, step * fibers_per_strand));
                }
            }
        }
        let count = cells.count();
        let mut starts = vec![0u32; count + 1];
        for &(c, _, _) in &pieces {
            starts[c as usize + 1] += 1;
        }
        for c in 0..count {
            starts[c + 1] += starts[c];
        }
        let mut cursor = starts.clone();
        cells.tangents = vec![Vec3::ZERO; pieces.len()];
        cells.lengths = vec![0.0; pieces.len()];
        cells.longest = vec![0.0; count];
        for &(c, u, len) in &pieces {
            let at = &mut cursor[c as usize];
            cells.tangents[*at as usize] = u;
            cells.lengths[*at as usize] = len;
            *at += 1;
            let l = &mut cells.longest[c as usize];
            *l = l.max(len);
        }
        // The cells within one of a filled cell (the 2×2×2 a point picks from lie there),
        // numbered in cell order.
        let mut near = vec![false; count];
        let d = cells.dims.as_ivec3();
        for i in (0..count).filter(|&i| starts[i + 1] > starts[i]) {
            let c = cells.coords(i).as_ivec3();
            for k in 0..27 {
                let n = c + glam::IVec3::new(k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1);
                if n.cmpge(glam::IVec3::ZERO).all() && n.cmplt(d).all() {
                    near[cells.index(n.as_uvec3())] = true;
                }
            }
        }
        let mut slots = 0u32;
        cells.slot = near
            .iter()
            .map(|&n| {
                if !n {
                    return NO_SLOT;
                }
                slots += 1;
                slots - 1
            })
            .collect();
        cells.slots = slots as usize;
        cells.busy = vec![0; count.div_ceil(64)];
        for i in 0..count {
            if near[i] || starts[i + 1] > starts[i] {
                cells.mark_busy(i);
            }
        }
        cells.starts = starts;
        Some(cells)
    }
}

/// One straight flight of scattered light through one cell (module doc, step 3).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Record {
    /// The cell's [`Cells::slot`].
    pub(crate) slot: u32,
    /// Unit direction the light came from (against its travel).
    pub(crate) from: Vec3,
    /// Its power times the length flown in the cell, W·m, RGB.
    pub(crate) power_m: Vec3,
}

/// The multiply scattered light of one directional light in the hair (module doc).
#[derive(Clone, Debug, Default)]
pub struct LightPaths {
    cells: Cells,
    /// Per slot ([`Cells::slot`]), its merged records' range: `starts[s]..starts[s + 1]`.
    starts: Vec<u32>,
    from: Vec<Vec3>,
    /// Power × length ÷ cell volume (W/m², RGB): each record's share of ∫ L dω.
    fluence: Vec<Vec3>,
    /// The cell edge used, metres (`VolumeParams::cell_m`, or larger to fit the bins).
    pub cell_m: f32,
    /// Scatterings the paths met (two runs that agree meet the same number).
    pub scatterings: u64,
}

impl LightPaths {
    /// Traces `params.paths` light paths of `light` through the hair the points stand for
    /// (`lengths_m`: metres of fibre each, in units of the strand's `fibers_per_strand`
    /// fibres), with `fiber`'s Chiang constants. `solid_depth_m(p)`, when given, says how deep
    /// `p` lies inside a solid (0 outside): light that enters one is absorbed. `None` when
    /// there is no hair.
    #[allow(clippy::too_many_arguments)]
    pub fn build<D: Fn(Vec3) -> f32 + Sync>(
        fiber: &Fiber,
        positions: &[Vec3],
        tangents: &[Vec3],
        lengths_m: &[f32],
        fibers_per_strand: f32,
        light: &Light,
        params: &LightPathParams,
        solid_depth_m: Option<D>,
    ) -> Option<LightPaths> {
        let n = params.bins_per_axis.max(1) as u64;
        let mut cell_m = params.cell_m;
        let mut cells = loop {
            let cells = Cells::build(positions, tangents, lengths_m, fibers_per_strand, cell_m)?;
            if bins::Bins::estimated_bytes(cells.slots as u64, n) <= params.max_bins_bytes
                || cells.slots == 0
            {
                break cells;
            }
            cell_m = cells.cell_m * 2f32.cbrt();
        };
        if let Some(depth) = &solid_depth_m {
            cells.mark_solids(depth);
        }
        let radius_m = fiber.params().radius_m;
        // In waves of paths, each wave's flights merged into the bins in block order: the
        // same sums for any thread count, and only one wave's flights held at once.
        let mut bins = bins::Bins::new(cells.slots, params.bins_per_axis.max(1) as usize);
        let inv_volume = 1.0 / cells.cell_m.powi(3);
        // No emitter: the light cannot reach the hair, and no path is traced.
        let emitter = emit::Emitter::new(&cells, light, params.paths);
        let blocks = params.paths.div_ceil(trace::BLOCK);
        let mut scatterings = 0u64;
        // The merge's ranges of slots, one per thread: each block files its flights by them.
        let ranges = bins.span();
        for wave in (0..blocks).step_by(WAVE_BLOCKS as usize) {
            let Some(emitter) = &emitter else {
                break;
            };
            let traced = trace::trace(
                &cells,
                fiber,
                radius_m,
                emitter,
                params,
                wave..(wave + WAVE_BLOCKS).min(blocks),
                ranges,
            );
            bins.add_all(ranges.0, |job| {
                traced
                    .blocks
                    .iter()
                    .flat_map(move |b| b.range(job))
                    .map(|r| (r.slot, r.from, r.power_m * inv_volume))
            });
            scatterings += traced.scatterings;
        }
        let (starts, from, fluence) = bins.finish();
        Some(LightPaths {
            cell_m: cells.cell_m,
            cells,
            starts,
            from,
            fluence,
            scatterings,
        })
    }

    /// Bytes one light's volume holds at most, for `points` render points whose samples are at
    /// most `sample_len_m` long in hair spanning at most `extent_m` along each axis: the pieces
    /// (and their filing), the cells, the bins (at most `max_bins_bytes`), and one wave's
    /// flights at [`FLIGHTS_PER_PATH`] a path.
    pub fn estimated_bytes(
        points: u64,
        sample_len_m: f32,
        extent_m: f32,
        params: &LightPathParams,
    ) -> u64 {
        let cell_m = params
            .cell_m
            .max(extent_m / (MAX_CELLS_PER_AXIS - 2) as f32)
            .max(1e-6);
        let per_axis = ((extent_m / cell_m).ceil() as u64 + 2).min(MAX_CELLS_PER_AXIS as u64);
        let cells = per_axis.pow(3);
        let cuts = ((sample_len_m / (0.5 * cell_m)).ceil() as u64).clamp(1, 64);
        let pieces = points.saturating_mul(cuts);
        // Filed: tangent + length; while filing: cell + tangent + length.
        let piece_bytes = pieces.saturating_mul(16 + 20);
        // Starts, longest, slot (4 B each), solid (1 B), busy (a bit).
        let cell_bytes = cells.saturating_mul(14);
        let bin_bytes = params.max_bins_bytes;
        let wave =
            (WAVE_BLOCKS * trace::BLOCK) as u64 * FLIGHTS_PER_PATH * 2 * size_of::<Record>() as u64;
        piece_bytes
            .saturating_add(cell_bytes)
            .saturating_add(bin_bytes)
            .saturating_add(wave)
    }

    /// Records kept (for reports and memory).
    pub fn records(&self) -> usize {
        self.from.len()
    }

    /// The multiply scattered radiance toward unit `wo` of a fibre of unit tangent `u` at `p`
    /// (W/(m²·sr), RGB): Σ S(ωi, ωo) cos θi × the record's share of ∫ L dω, over the records
    /// of one cell near `p`, chosen with trilinear probabilities by `pick` ∈ [0, 1)³.
    pub fn indirect(&self, fiber: &Fiber, p: Vec3, u: Vec3, wo: Vec3, pick: Vec3) -> Vec3 {
        let Some(c) = self.pick_cell(p, pick) else {
            return Vec3::ZERO;
        };
        let slot = self.cells.slot[c] as usize;
        let (Some(&a), Some(&b)) = (self.starts.get(slot), self.starts.get(slot + 1)) else {
            return Vec3::ZERO;
        };
        let (a, b) = (a as usize, b as usize);
        let mut sum = Vec3::ZERO;
        for (wi, e) in self.from[a..b].iter().zip(&self.fluence[a..b]) {
            // S cos θi: single scattering of unshadowed light from ωi.
            sum += fiber.shade(ShadingMode::SingleScattering, u, *wi, wo, &UNSHADOWED) * *e;
        }
        if sum.is_finite() {
            sum.max(Vec3::ZERO)
        } else {
            Vec3::ZERO
        }
    }

    /// The cell of the 2×2×2 around `p` (between cell centres) that `pick` draws with
    /// trilinear probabilities: its expectation is the trilinear blend of the cells' values.
    fn pick_cell(&self, p: Vec3, pick: Vec3) -> Option<usize> {
        let cells = &self.cells;
        let q = (p - cells.origin) / cells.cell_m - Vec3::splat(0.5);
        if !q.is_finite() {
            return None;
        }
        let f = q.floor();
        let t = q - f;
        let step = |t: f32, r: f32| if r < t { 1.0 } else { 0.0 };
        let c = f + Vec3::new(step(t.x, pick.x), step(t.y, pick.y), step(t.z, pick.z));
        let d = cells.dims.as_vec3();
        if c.x < 0.0 || c.y < 0.0 || c.z < 0.0 || c.x >= d.x || c.y >= d.y || c.z >= d.z {
            return None;
        }
        Some(cells.index(c.as_uvec3()))
    }
}

/// Three numbers in [0, 1) from a hash of `i` (SplitMix64's finaliser), for
/// [`PhotonVolume::indirect`]'s cell choice: the same point picks the same cell every run.
pub fn pick_of(i: usize) -> Vec3 {
    let mut rng = crate::rng::SplitMix64::new(i as u64 ^ 0xC0FF_EE00_D15C_0BA1);
    Vec3::new(rng.unit(), rng.unit(), rng.unit())
}

#[cfg(test)]
mod tests;
