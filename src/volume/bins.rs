//! A cell's records merged by direction (`volume` module doc, step 3): the gather evaluates the
//! fibre's BCSDF once per record, so a cell of thousands of flights costs thousands of
//! evaluations. Records are merged into the bins of an octahedral map of the sphere
//! (Praun & Hoppe 2003's layout: |x| + |y| + |z| = 1 unfolded onto a square), each bin
//! keeping its summed light and the light-weighted mean of its directions, so the light's
//! total and its first angular moment within the bin are kept exactly.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// Cells merged per parallel job.
const CELLS_PER_JOB: usize = 1024;

/// The bin of unit `d` in an octahedral map of `n` × `n` bins.
pub(super) fn octahedral_bin(d: Vec3, n: usize) -> usize {
    let s = d.x.abs() + d.y.abs() + d.z.abs();
    let mut p = Vec2::new(d.x, d.y) / s.max(1e-30);
    if d.z < 0.0 {
        let sign = Vec2::new(p.x.signum(), p.y.signum());
        p = (Vec2::ONE - Vec2::new(p.y.abs(), p.x.abs())) * sign;
    }
    let q =
        ((p * 0.5 + Vec2::splat(0.5)) * n as f32).clamp(Vec2::ZERO, Vec2::splat(n as f32 - 1.0));
    q.y as usize * n + q.x as usize
}

/// Merges each cell's records (`starts[c]..starts[c + 1]` of `from`, `fluence`) into at most
/// `n`² (cells with fewer records keep them as they are). Returns the new starts, directions
/// and light, in cell order; the same bits for any thread count (cells are independent, each
/// merged in its records' order).
pub(super) fn merge_by_direction(
    starts: &[u32],
    from: &[Vec3],
    fluence: &[Vec3],
    n: usize,
) -> (Vec<u32>, Vec<Vec3>, Vec<Vec3>) {
    let cells = starts.len().saturating_sub(1);
    let jobs: Vec<(Vec<u32>, Vec<Vec3>, Vec<Vec3>)> = (0..cells.div_ceil(CELLS_PER_JOB))
        .into_par_iter()
        .map(|job| {
            let (mut counts, mut dirs, mut light) = (Vec::new(), Vec::new(), Vec::new());
            let mut sum = vec![Vec3::ZERO; n * n];
            let mut moment = vec![Vec3::ZERO; n * n];
            for c in job * CELLS_PER_JOB..((job + 1) * CELLS_PER_JOB).min(cells) {
                let (a, b) = (starts[c] as usize, starts[c + 1] as usize);
                if b - a <= n * n {
                    dirs.extend_from_slice(&from[a..b]);
                    light.extend_from_slice(&fluence[a..b]);
                    counts.push((b - a) as u32);
                    continue;
                }
                sum.fill(Vec3::ZERO);
                moment.fill(Vec3::ZERO);
                for (d, e) in from[a..b].iter().zip(&fluence[a..b]) {
                    let k = octahedral_bin(*d, n);
                    sum[k] += *e;
                    moment[k] += *d * e.element_sum();
                }
                let before = dirs.len();
                for (s, m) in sum.iter().zip(&moment) {
                    if s.element_sum() > 0.0 {
                        dirs.push(m.normalize_or_zero());
                        light.push(*s);
                    }
                }
                counts.push((dirs.len() - before) as u32);
            }
            (counts, dirs, light)
        })
        .collect();
    let mut new_starts = Vec::with_capacity(starts.len());
    new_starts.push(0u32);
    let (mut dirs, mut light) = (Vec::new(), Vec::new());
    for (counts, d, l) in jobs {
        for k in counts {
            let last = *new_starts.last().unwrap_or(&0);
            new_starts.push(last + k);
        }
        dirs.extend(d);
        light.extend(l);
    }
    (new_starts, dirs, light)
}
