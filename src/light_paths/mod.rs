//! Multiply scattered light from light paths traced through the hair: paths of light leave
//! each light, scatter from fibre to fibre, and leave a record of every straight flight through
//! a cell with the direction it came from; a seen point gathers the records of a cell near it
//! through the fibre's BCSDF. This is Moon, Walter & Marschner 2008's two-pass scheme, with
//! their spherical harmonics replaced by the paths' own directions, and the alternative to
//! dual scattering's global and local terms where light reaches hair off its shadow ray.
//!
//! Why: dual scattering (Zinke 2008) carries forward-scattered light along the straight shadow
//! ray only. Against a path tracer, back-lit dense silhouettes then read a stop dark and a
//! side-lit far third 1–2 stops bright (ACCURACY.md §2: 36–48% of 8 px hair blocks within
//! 1.5× side-lit and point-lit): light scattered four or more times diffuses there from
//! where it entered (paths of up to three bounces bring a tenth of a back-lit rim's light).
//! Paths that scatter through the hair carry that light (64–93% of those blocks, the rest
//! mostly the path tracer's own noise). A single scalar per cell gets the colours 17–22% wrong,
//! because the fibre's response depends on where the light comes from; so each cell keeps its
//! light by direction and the fibre's far-field BCSDF is integrated against it (ACCURACY.md,
//! "Decisions and their evidence", the light paths).
//!
//! How:
//! 1. **Cells** (`cells.rs`). A grid of `cell_m` cubes over the hair. Each render-strand
//!    point stands for a piece of fibre (its `lengths_m` times the strand's fibres), cut into
//!    pieces at most half a cell long, each filed under the cell of its middle with its
//!    tangent.
//! 2. **Paths** (`emit.rs`, `trace.rs`). A directional light's paths enter from the columns
//!    across it that a cell holding fibre reaches (a path anywhere else would cross no fibre),
//!    each with power E·A/N for the columns' area A; a point light's leave it into the
//!    directions of the cone of the grid's bounding sphere that a cell holding fibre subtends,
//!    each with I·Ω/N for their solid angle Ω. A path flies by delta tracking: the majorant of
//!    a cell is 2r·n·ℓ_max/V (n pieces, the longest ℓ_max); at a tentative collision a piece
//!    is drawn uniformly and hit with probability (ℓ/ℓ_max)·sin ψ (ψ between path and fibre),
//!    so real collisions occur at the fibres' cross-section per volume, 2r Σ ℓ sin ψ / V. At
//!    each hit the path scatters by the Chiang model (`fiber::chiang_sample`). Russian
//!    roulette ends weak paths without bias. A cell wholly inside a solid (head, body) absorbs
//!    what enters it (skin's own reflection is not carried).
//! 3. **Records** (`records.rs`, `bins.rs`). After its first scattering, each straight flight
//!    through a cell leaves a record: the direction it came from and its power times the
//!    length flown in the cell. Σ records / V estimates ∫ L(ω) dω there, direction by
//!    direction (the track-length estimator), for light scattered at least once. Records are
//!    kept only in cells a seen point can gather from (a piece of fibre within one cell),
//!    merged wave by wave into 8 × 8 direction bins per cell, each keeping its light and mean
//!    direction.
//! 4. **Gather** (`gather.rs`, [`LightPaths::indirect`]). A seen point adds
//!    Σ S(ωi, ωo) cos θi · light over the bins of one cell near it (drawn with trilinear
//!    probabilities from a hash of the point, so the cells blend without an 8× cost). The
//!    light that reaches it directly is the single-scattering shader's, as in Moon et al.: the
//!    two add up to all orders. With [`Directions::Strongest`] only a cell's strongest bins
//!    are gathered so, and the rest from their moments to the second order through tables of
//!    the fibre's integrals (`moments.rs`, `response.rs`): a bounded gather, since the light
//!    away from the strongest bins is spread enough for the second order.
//!
//! Deterministic for any thread count: paths are traced in fixed blocks, each from its own
//! seed, and each wave's records are added to the bins in block order.

// `!(a < b)` on floats is meant: it is true for NaN, which must take the safe branch.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod bins;
mod cells;
mod emit;
mod gather;
mod moments;
mod records;
mod response;
mod trace;

pub use cells::StrandPoints;
pub use gather::pick_of;
pub use response::AngularResponse;

use crate::fiber::Fiber;
use crate::light::Light;
use cells::{Cells, MAX_CELLS_PER_AXIS};
use glam::Vec3;
use records::Record;

/// Blocks of paths traced between two merges into the bins (64 × 1,024 paths): what bounds the
/// flights held at once.
const WAVE_BLOCKS: u32 = 64;
/// Flights a path leaves, for the memory estimate: measured 11 on average on dense blond hair
/// (the most scattering of the presets), held in vectors that may double: 32 covers it.
const FLIGHTS_PER_PATH: u64 = 32;

/// How many light paths are traced, and how their light is kept.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightPathParams {
    /// Cell edge, metres (> 0).
    pub cell_m: f32,
    /// Light paths per light, each sent where it meets the hair's columns (`emit.rs`). The
    /// default, 2,000,000, is what dense hair's darkest tenth needs: with 1,000,000 brown
    /// side-lit read 0.49–1.24 of the path tracer's, with 2,000,000 0.57–1.46, as with 4,000,000
    /// (ACCURACY.md §2 and its decisions): the fewer the paths, the noisier the dim cells, and
    /// noise darkens a darkest tenth. The `final` quality level traces 200,000 in 6 mm cells
    /// (`engine::quality`), as close to the path tracer's blocks as these.
    pub paths: u32,
    /// Seed of the paths' random numbers.
    pub seed: u64,
    /// A cell's flights merged into this many × this many direction bins (octahedral,
    /// `bins.rs`), 1..=16. Default 8: against keeping every flight, the gather 1.5× faster at
    /// 4 M paths, the means moved by at most 2% (ACCURACY.md, decisions), and the memory bounded.
    pub bins_per_axis: u32,
    /// Most bytes the bins may take: cells are enlarged (by 2^⅓ at a time) until the cells
    /// points gather from fit (dense one-fibre hair at 4 mm: 125,000 cells, 384 MB).
    pub max_bins_bytes: u64,
    /// How each cell's light by direction is gathered: every bin through the fibre's BCSDF,
    /// or only its strongest and the rest through their moments.
    pub directions: Directions,
}

/// The solids (head, body) that stop light paths.
#[derive(Clone, Debug)]
pub struct Solids<'a, D> {
    /// How deep a point lies inside a solid, metres (0 outside).
    pub depth_m: D,
    /// Boxes (lowest and highest corners, metres) that hold every point of positive depth:
    /// only cells there are asked.
    pub within_m: &'a [(Vec3, Vec3)],
}

/// How a cell keeps the light that crosses it by direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Directions {
    /// Every non-empty one of its `bins_per_axis`² octahedral bins, each gathered through the
    /// BCSDF (`bins.rs`).
    #[default]
    Bins,
    /// Its strongest bins, at most this many, each gathered through the BCSDF, and the rest as
    /// moments up to the second order gathered through tabulated integrals of the BCSDF
    /// (`moments.rs`, `response.rs`): a bounded gather.
    Strongest(u32),
}

impl Default for LightPathParams {
    fn default() -> Self {
        Self {
            cell_m: 0.004,
            paths: 2_000_000,
            seed: 0x5EED_0F11_6A7E,
            bins_per_axis: 8,
            max_bins_bytes: 768_000_000,
            directions: Directions::Bins,
        }
    }
}

/// The multiply scattered light of one light in the hair, kept by cell and direction (module
/// doc).
#[derive(Clone, Debug, Default)]
pub struct LightPaths {
    cells: Cells,
    /// Per slot ([`Cells::slot`]), its merged records' range: `starts[s]..starts[s + 1]`.
    starts: Vec<u32>,
    from: Vec<Vec3>,
    /// Power × length ÷ cell volume (W/m², RGB): each record's share of ∫ L dω.
    fluence: Vec<Vec3>,
    /// Per slot, the moments of the bins not kept as records ([`Directions::Strongest`];
    /// empty when every bin is).
    moments: Vec<moments::Moment>,
    /// The cell edge used, metres (`LightPathParams::cell_m`, or larger to fit the bins).
    pub cell_m: f32,
    /// Scatterings the paths met (two runs that agree meet the same number).
    pub scatterings: u64,
}

impl LightPaths {
    /// Traces `params.paths` light paths of `light` through the hair `points` stand for, with
    /// `fiber`'s Chiang constants. Light that enters one of the `solids`, when given, is
    /// absorbed. `None` when there is no hair.
    pub fn build<D: Fn(Vec3) -> f32 + Sync>(
        fiber: &Fiber,
        points: &StrandPoints,
        light: &Light,
        params: &LightPathParams,
        solids: Option<Solids<D>>,
    ) -> Option<LightPaths> {
        let mut cells = cells_within_budget(points, params)?;
        if let Some(solids) = &solids {
            cells.mark_solids(&solids.depth_m, solids.within_m);
        }
        let mut bins = bins::Bins::new(cells.slots, params.bins_per_axis.max(1) as usize);
        // No emitter: the light cannot reach the hair, and no path is traced.
        let scatterings = match emit::Emitter::new(&cells, light, params.paths) {
            Some(emitter) => trace_in_waves(&cells, fiber, &emitter, params, &mut bins),
            None => 0,
        };
        let strongest = match params.directions {
            Directions::Bins => None,
            Directions::Strongest(k) => Some(k as usize),
        };
        let bins::Finished {
            starts,
            from,
            light: fluence,
            rest: moments,
        } = bins.finish(strongest);
        Some(LightPaths {
            cell_m: cells.cell_m,
            cells,
            starts,
            from,
            fluence,
            moments,
            scatterings,
        })
    }

    /// Bytes one light's paths hold at most, for `points` render points whose samples are at
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
}

/// The cells of `points` at `params.cell_m`, enlarged by 2^⅓ at a time until the bins of the
/// cells points gather from fit `params.max_bins_bytes`.
fn cells_within_budget(points: &StrandPoints, params: &LightPathParams) -> Option<Cells> {
    let n = params.bins_per_axis.max(1) as u64;
    let mut cell_m = params.cell_m;
    loop {
        let cells = Cells::build(points, cell_m)?;
        if bins::Bins::estimated_bytes(cells.slots as u64, n) <= params.max_bins_bytes
            || cells.slots == 0
        {
            return Some(cells);
        }
        cell_m = cells.cell_m * 2f32.cbrt();
    }
}

/// Traces the paths of `emitter` in waves of [`WAVE_BLOCKS`] blocks, each wave's flights
/// merged into `bins` in block order: the same sums for any thread count, and only one wave's
/// flights held at once. Returns the scatterings the paths met.
fn trace_in_waves(
    cells: &Cells,
    fiber: &Fiber,
    emitter: &emit::Emitter,
    params: &LightPathParams,
    bins: &mut bins::Bins,
) -> u64 {
    let radius_m = fiber.params().radius_m;
    let inv_volume = 1.0 / cells.cell_m.powi(3);
    let blocks = params.paths.div_ceil(trace::BLOCK);
    let mut scatterings = 0u64;
    // The merge's ranges of slots, one per thread: each block files its flights by them.
    let ranges = bins.span();
    for wave in (0..blocks).step_by(WAVE_BLOCKS as usize) {
        let traced = trace::trace(
            cells,
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
    scatterings
}

#[cfg(test)]
mod tests;
