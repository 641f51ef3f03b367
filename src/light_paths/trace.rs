//! Light paths through the cells (`light_paths` module doc, steps 2 and 3): a grid walked
//! cell by cell (Amanatides & Woo 1987), delta tracking inside the cells that hold fibre,
//! Chiang scattering at each collision, Russian roulette.
//!
//! **Delta tracking** (Woodcock tracking). In a cell of volume V holding n pieces, the longest
//! ℓ_max, the majorant σ̄ = 2r·n·ℓ_max / V bounds the fibres' cross-section per volume. Free
//! flights s = −ln ξ / σ̄ give tentative collisions; at each, a piece j is drawn uniformly and
//! the collision accepted with probability (ℓ_j / ℓ_max)·sin ψ_j, ψ between the path and the
//! piece. The accepted collisions then occur at the rate Σ_j 2r ℓ_j sin ψ_j / V, the fibres'
//! projected cross-section per volume: the slab test pins it against Beer–Lambert. Why:
//! it needs no intersection with a fibre and is unbiased, whatever the pieces' spread.
//!
//! **Scattering.** At a collision the path's new direction and the factor its power takes come
//! from `fiber::chiang_sample::ScatterSampler`: Chiang et al. 2016's lobes sampled as pbrt-v3
//! §9.9.6 does, at a random offset across the fibre, so the factor's expectation is the
//! far-field ḡ the gather evaluates. After [`ROULETTE_AFTER`] scatterings a path whose largest
//! channel w has fallen below its start's w₀ survives with probability q = w / w₀ and is
//! divided by q: no bias, and no time spent on paths that carry almost nothing.
//!
//! **Determinism.** Paths are traced in blocks of [`BLOCK`], block b drawing from stream b of
//! the seed (`rng::SplitMix64::stream`), so the paths are the same for any thread count.

use super::LightPathParams;
use super::cells::{Cells, NO_SLOT};
use super::emit::{Emit, Emitter};
use super::records::{BlockRecords, Record};
use crate::fiber::Fiber;
use crate::fiber::chiang_sample::ScatterSampler;
use crate::rng::SplitMix64;
use glam::{IVec3, Vec3};
use rayon::prelude::*;

/// Paths per block: each block draws from its own seed, so the result is the same for any
/// thread count.
pub(super) const BLOCK: u32 = 1024;
/// Scatterings after which Russian roulette may end a path.
const ROULETTE_AFTER: u32 = 3;
/// A path is ended after this many scatterings whatever its power (never reached in practice:
/// a fibre absorbs or sends light out of the hair long before).
const MAX_SCATTERINGS: u32 = 100_000;

/// What the paths left: records per block, in block order.
pub(super) struct Traced {
    pub(super) blocks: Vec<BlockRecords>,
    pub(super) scatterings: u64,
}

/// Traces blocks `blocks` of the `params.paths` paths of `emitter` through `cells` (fibres of
/// radius `radius_m`): block b is paths b·BLOCK.. of the whole, from its own seed. Each
/// block's records come grouped by `ranges` ranges of `span` slots, the merge's jobs.
pub(super) fn trace(
    cells: &Cells,
    fiber: &Fiber,
    radius_m: f32,
    emitter: &Emitter,
    params: &LightPathParams,
    blocks: std::ops::Range<u32>,
    (span, ranges): (usize, usize),
) -> Traced {
    let scatter = ScatterSampler::new(fiber.chiang_constants());
    let walker = Walker {
        cells,
        sigma_per_len: 2.0 * radius_m / cells.cell_m.powi(3),
    };
    let (span, ranges) = (span.max(1), ranges.max(1));
    let results: Vec<(BlockRecords, u64)> = blocks
        .into_par_iter()
        .map(|block| {
            let mut rng = SplitMix64::stream(params.seed, block as u64);
            let mut records = Vec::new();
            let mut scatterings = 0u64;
            let end = ((block + 1) * BLOCK).min(params.paths);
            for _ in block * BLOCK..end {
                let start = emitter.emit(&mut rng);
                scatterings += walker.path(start, &scatter, &mut rng, &mut records);
            }
            (BlockRecords::new(records, span, ranges), scatterings)
        })
        .collect();
    let scatterings = results.iter().map(|r| r.1).sum();
    Traced {
        blocks: results.into_iter().map(|r| r.0).collect(),
        scatterings,
    }
}

/// Flies paths through the cells (module doc).
pub(super) struct Walker<'a> {
    pub(super) cells: &'a Cells,
    /// 2r / V: a cell's cross-section per metre of fibre at right angles.
    pub(super) sigma_per_len: f32,
}

impl Walker<'_> {
    /// One path from its start (point, unit direction, power); appends its records, returns
    /// its scatterings.
    fn path(
        &self,
        (start, mut d, power): Emit,
        scatter: &ScatterSampler,
        rng: &mut SplitMix64,
        records: &mut Vec<Record>,
    ) -> u64 {
        let mut o = start;
        let mut weight = power;
        let full = power.max_element();
        let mut bounces = 0u32;
        loop {
            let Some((hit, u)) = self.fly(o, d, bounces > 0, weight, rng, records) else {
                return bounces as u64;
            };
            let xi = std::array::from_fn(|_| rng.open_unit_f64());
            let Some(s) = scatter.sample(u.as_dvec3(), -d.as_dvec3(), xi) else {
                return bounces as u64;
            };
            bounces += 1;
            weight *= Vec3::new(s.weight[0] as f32, s.weight[1] as f32, s.weight[2] as f32);
            d = s.dir.as_vec3().normalize_or_zero();
            o = hit;
            if d == Vec3::ZERO || !weight.is_finite() || bounces >= MAX_SCATTERINGS {
                return bounces as u64;
            }
            if bounces >= ROULETTE_AFTER && !survives_roulette(&mut weight, full, rng) {
                return bounces as u64;
            }
        }
    }

    /// Flies from `o` along `d` until a fibre is hit (its point and tangent) or the grid is
    /// left (`None`), recording each cell's flight when `scattered`.
    pub(super) fn fly(
        &self,
        o: Vec3,
        d: Vec3,
        scattered: bool,
        weight: Vec3,
        rng: &mut SplitMix64,
        records: &mut Vec<Record>,
    ) -> Option<(Vec3, Vec3)> {
        let cells = self.cells;
        let (mut walk, mut t) = Walk::enter(cells, o, d)?;
        let dims = cells.dims.as_ivec3();
        loop {
            if walk.cell.cmplt(IVec3::ZERO).any() || walk.cell.cmpge(dims).any() {
                return None;
            }
            let index = cells.index(walk.cell.as_uvec3());
            let t_exit = walk.t_max.min_element().max(t);
            if cells.is_busy(index) {
                if cells.solid.get(index).copied().unwrap_or(false) {
                    return None;
                }
                let t_cell = t;
                if let Some(u) = self.collide_in_cell(index, d, &mut t, t_exit, rng) {
                    if scattered {
                        record(cells, index, d, weight, t - t_cell, records);
                    }
                    return Some((o + d * t, u));
                }
                if scattered && t_exit > t_cell {
                    record(cells, index, d, weight, t_exit - t_cell, records);
                }
            }
            t = t_exit;
            walk.advance();
            if t >= walk.t_leave {
                return None;
            }
        }
    }

    /// Delta tracking through cell `index` from `*t` to `t_exit` (module doc): the tangent of
    /// the piece hit, with `*t` at the collision, or `None` when the flight leaves the cell
    /// (`*t` then at its last tentative collision).
    #[inline]
    fn collide_in_cell(
        &self,
        index: usize,
        d: Vec3,
        t: &mut f32,
        t_exit: f32,
        rng: &mut SplitMix64,
    ) -> Option<Vec3> {
        let cells = self.cells;
        let (first, last) = (
            cells.starts[index] as usize,
            cells.starts[index + 1] as usize,
        );
        let count = last.saturating_sub(first);
        if count == 0 {
            return None;
        }
        let majorant = self.sigma_per_len * (count as f32 * cells.longest[index]);
        loop {
            let s = -(rng.open_unit_f64() as f32).ln() / majorant;
            if !(*t + s < t_exit) {
                return None;
            }
            *t += s;
            let j = first + ((rng.open_unit_f64() * count as f64) as usize).min(count - 1);
            // Tangent, and length over the cell's longest.
            let piece = cells.pieces[j];
            let u = piece.truncate();
            let accept = piece.w * d.cross(u).length();
            if (rng.open_unit_f64() as f32) < accept {
                return Some(u);
            }
        }
    }
}

/// Russian roulette on a path of `weight` that started at `full` (its largest channel): it
/// survives with probability q = max(weight) / full, its weight divided by q. Whether it
/// survives; a path at or above its start's weight always does, unchanged.
#[inline]
fn survives_roulette(weight: &mut Vec3, full: f32, rng: &mut SplitMix64) -> bool {
    let keep = weight.max_element() / full;
    if keep < 1.0 {
        if rng.open_unit_f64() as f32 >= keep {
            return false;
        }
        *weight /= keep;
    }
    true
}

/// Appends the record of a flight of `length_m` along `d` with `weight` through cell `index`,
/// if a point gathers from that cell.
#[inline]
fn record(
    cells: &Cells,
    index: usize,
    d: Vec3,
    weight: Vec3,
    length_m: f32,
    records: &mut Vec<Record>,
) {
    let slot = cells.slot[index];
    if slot != NO_SLOT {
        records.push(Record {
            slot,
            from: -d,
            power_m: weight * length_m,
        });
    }
}

/// A ray's walk through the grid's cells (Amanatides & Woo 1987): the cell it is in, and the
/// distances along it to each axis's next cell boundary and between two boundaries.
struct Walk {
    cell: IVec3,
    step: IVec3,
    t_max: Vec3,
    t_delta: Vec3,
    /// Where the ray leaves the grid's box.
    t_leave: f32,
}

impl Walk {
    /// The walk of the ray from `o` along `d` from where it enters the grid's box, and that
    /// distance; `None` when it misses the box.
    #[inline]
    fn enter(cells: &Cells, o: Vec3, d: Vec3) -> Option<(Walk, f32)> {
        let size = cells.dims.as_vec3() * cells.cell_m;
        let inv = d.recip();
        let t0 = (cells.origin - o) * inv;
        let t1 = (cells.origin + size - o) * inv;
        let (tn, tf) = (t0.min(t1), t0.max(t1));
        let t_enter = tn.max_element().max(0.0);
        let t_leave = tf.min_element();
        if !(t_enter < t_leave) {
            return None;
        }
        let p = o + d * t_enter;
        let q = ((p - cells.origin) / cells.cell_m)
            .clamp(Vec3::ZERO, cells.dims.as_vec3() - Vec3::splat(1e-3));
        let cell = q.floor().as_ivec3();
        let step = d.signum().as_ivec3();
        let next_edge = |k: usize| (cell[k] + i32::from(step[k] > 0)) as f32;
        let axis = |k: usize| axis_t(o[k], d[k], cells.origin[k], cells.cell_m, next_edge(k));
        let walk = Walk {
            cell,
            step,
            t_max: Vec3::new(axis(0), axis(1), axis(2)),
            t_delta: (Vec3::splat(cells.cell_m) * inv).abs(),
            t_leave,
        };
        Some((walk, t_enter))
    }

    /// Steps into the next cell, along the axis whose boundary comes first.
    #[inline]
    fn advance(&mut self) {
        let t = self.t_max;
        if t.x <= t.y && t.x <= t.z {
            self.cell.x += self.step.x;
            self.t_max.x += self.t_delta.x;
        } else if t.y <= t.z {
            self.cell.y += self.step.y;
            self.t_max.y += self.t_delta.y;
        } else {
            self.cell.z += self.step.z;
            self.t_max.z += self.t_delta.z;
        }
    }
}

/// Distance along the ray from `o` (direction component `d`) to the plane at grid coordinate
/// `edge` (cells from `origin`, `cell_m` each): +∞ when the ray runs parallel to it.
#[inline]
fn axis_t(o: f32, d: f32, origin: f32, cell_m: f32, edge: f32) -> f32 {
    if d == 0.0 {
        f32::INFINITY
    } else {
        (origin + edge * cell_m - o) / d
    }
}
