//! Light paths through the cells (`volume` module doc, steps 2 and 3): delta tracking across a
//! grid walked cell by cell (Amanatides & Woo 1987), Chiang scattering, Russian roulette.

use super::emit::Emitter;
use super::{Cells, LightPathParams, NO_SLOT, Record};
use crate::fiber::Fiber;
use crate::fiber::chiang::TrimmedLogistic;
use crate::fiber::chiang_sample::sample_scatter;
use crate::rng::SplitMix64;
use glam::Vec3;
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

/// One block's records, grouped by range of `span` slots (range j: slots j·span..), each
/// range's in the order the paths left them.
pub(super) struct BlockRecords {
    records: Vec<Record>,
    /// Range j's records: `records[ends[j - 1]..ends[j]]` (from 0 for j = 0).
    ends: Vec<u32>,
}

impl BlockRecords {
    /// Groups `records` by range of `span` slots, `ranges` ranges (a stable counting sort).
    pub(super) fn new(records: Vec<Record>, span: usize, ranges: usize) -> BlockRecords {
        let range_of = |r: &Record| (r.slot as usize / span).min(ranges - 1);
        let mut ends = vec![0u32; ranges];
        for r in &records {
            ends[range_of(r)] += 1;
        }
        let mut at = 0;
        let mut cursor: Vec<u32> = ends
            .iter_mut()
            .map(|e| {
                let start = at;
                at += *e;
                *e = at;
                start
            })
            .collect();
        let mut grouped = records.clone();
        for r in records {
            let c = &mut cursor[range_of(&r)];
            grouped[*c as usize] = r;
            *c += 1;
        }
        BlockRecords {
            records: grouped,
            ends,
        }
    }

    /// The records of range `j`, in the paths' order.
    pub(super) fn range(&self, j: usize) -> &[Record] {
        let start = j
            .checked_sub(1)
            .and_then(|i| self.ends.get(i))
            .map_or(0, |&e| e as usize);
        let end = self.ends.get(j).map_or(start, |&e| e as usize);
        &self.records[start..end.max(start)]
    }
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
    let c = *fiber.chiang_constants();
    let logistic = TrimmedLogistic::new(c.s);
    let sigma_per_len = 2.0 * radius_m / cells.cell_m.powi(3);
    let walker = Walker {
        cells,
        sigma_per_len,
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
                let (start, d, power) = emitter.emit(&mut rng);
                scatterings += walker.path(start, d, power, &c, &logistic, &mut rng, &mut records);
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

pub(super) struct Walker<'a> {
    pub(super) cells: &'a Cells,
    /// 2r / V: a cell's cross-section per metre of fibre at right angles.
    pub(super) sigma_per_len: f32,
}

impl Walker<'_> {
    /// One path from `start` along unit `d` with `power`; appends its records, returns its
    /// scatterings.
    #[allow(clippy::too_many_arguments)]
    fn path(
        &self,
        start: Vec3,
        mut d: Vec3,
        power: Vec3,
        c: &crate::fiber::chiang::ChiangConstants,
        logistic: &TrimmedLogistic,
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
            let Some(s) = sample_scatter(c, logistic, u.as_dvec3(), -d.as_dvec3(), xi) else {
                return bounces as u64;
            };
            bounces += 1;
            weight *= Vec3::new(s.weight[0] as f32, s.weight[1] as f32, s.weight[2] as f32);
            d = s.dir.as_vec3().normalize_or_zero();
            o = hit;
            if d == Vec3::ZERO || !weight.is_finite() || bounces >= MAX_SCATTERINGS {
                return bounces as u64;
            }
            if bounces >= ROULETTE_AFTER {
                let keep = weight.max_element() / full;
                if keep < 1.0 {
                    if rng.open_unit_f64() as f32 >= keep {
                        return bounces as u64;
                    }
                    weight /= keep;
                }
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
        let size = cells.dims.as_vec3() * cells.cell_m;
        // Enter the grid's box.
        let inv = d.recip();
        let t0 = (cells.origin - o) * inv;
        let t1 = (cells.origin + size - o) * inv;
        let (tn, tf) = (t0.min(t1), t0.max(t1));
        let t_enter = tn.max_element().max(0.0);
        let t_leave = tf.min_element();
        if !(t_enter < t_leave) {
            return None;
        }
        // The walk: cell coordinates and the distances to the next boundaries.
        let p = o + d * t_enter;
        let q = ((p - cells.origin) / cells.cell_m)
            .clamp(Vec3::ZERO, cells.dims.as_vec3() - Vec3::splat(1e-3));
        let mut cell = q.floor().as_ivec3();
        let step = d.signum().as_ivec3();
        let next_edge = |c: i32, s: i32| (c + i32::from(s > 0)) as f32;
        let mut t_max = Vec3::new(
            axis_t(
                o.x,
                d.x,
                cells.origin.x,
                cells.cell_m,
                next_edge(cell.x, step.x),
            ),
            axis_t(
                o.y,
                d.y,
                cells.origin.y,
                cells.cell_m,
                next_edge(cell.y, step.y),
            ),
            axis_t(
                o.z,
                d.z,
                cells.origin.z,
                cells.cell_m,
                next_edge(cell.z, step.z),
            ),
        );
        let t_delta = (Vec3::splat(cells.cell_m) * inv).abs();
        let dims = cells.dims.as_ivec3();
        let mut t = t_enter;
        loop {
            if cell.cmplt(glam::IVec3::ZERO).any() || cell.cmpge(dims).any() {
                return None;
            }
            let index = cells.index(cell.as_uvec3());
            let t_exit = t_max.min_element().max(t);
            if cells.is_busy(index) {
                if cells.solid.get(index).copied().unwrap_or(false) {
                    return None;
                }
                let (first, last) = (
                    cells.starts[index] as usize,
                    cells.starts[index + 1] as usize,
                );
                let t_cell = t;
                if last > first {
                    let longest = cells.longest[index];
                    let majorant = self.sigma_per_len * (last - first) as f32 * longest;
                    loop {
                        let s = -(rng.open_unit_f64() as f32).ln() / majorant;
                        if !(t + s < t_exit) {
                            break;
                        }
                        t += s;
                        let j = first
                            + ((rng.open_unit_f64() * (last - first) as f64) as usize)
                                .min(last - first - 1);
                        let u = cells.tangents[j];
                        let sin = d.cross(u).length();
                        let accept = cells.lengths[j] / longest * sin;
                        if (rng.open_unit_f64() as f32) < accept {
                            let slot = cells.slot[index];
                            if scattered && slot != NO_SLOT {
                                records.push(Record {
                                    slot,
                                    from: -d,
                                    power_m: weight * (t - t_cell),
                                });
                            }
                            return Some((o + d * t, u));
                        }
                    }
                }
                let slot = cells.slot[index];
                if scattered && t_exit > t_cell && slot != NO_SLOT {
                    records.push(Record {
                        slot,
                        from: -d,
                        power_m: weight * (t_exit - t_cell),
                    });
                }
            }
            t = t_exit;
            // The next cell along the axis whose boundary comes first.
            if t_max.x <= t_max.y && t_max.x <= t_max.z {
                cell.x += step.x;
                t_max.x += t_delta.x;
            } else if t_max.y <= t_max.z {
                cell.y += step.y;
                t_max.y += t_delta.y;
            } else {
                cell.z += step.z;
                t_max.z += t_delta.z;
            }
            if t >= t_leave {
                return None;
            }
        }
    }
}

/// Distance along the ray from `o` (direction component `d`) to the plane at grid coordinate
/// `edge` (cells from `origin`, `cell_m` each): +∞ when the ray runs parallel to it.
fn axis_t(o: f32, d: f32, origin: f32, cell_m: f32, edge: f32) -> f32 {
    if d == 0.0 {
        f32::INFINITY
    } else {
        (origin + edge * cell_m - o) / d
    }
}
