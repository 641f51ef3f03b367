//! Clustering captured strands into wisps: k-means on root position and strand shape, with a
//! grid over the centroids' roots so that no step is quadratic.
//!
//! Each strand is a point in 9-D: its root, and `SHAPE_WEIGHT` times the vectors from the root
//! to its middle and to its tip (all head-frame metres), so strands of a wisp start close
//! together *and* go the same way. Lloyd's iterations: assign each strand to the nearest
//! centroid, move each centroid to the mean of its strands.
//!
//! Plain assignment compares every strand with every centroid (O(N·k); with k growing with N
//! that is quadratic: 50,000 strands × 2,000 wisps = 10⁸ distances per iteration). Here the
//! centroids' roots are put in a uniform grid of cells about one wisp apart, and a strand looks
//! in shells of cells around its root, nearest first. The root part is a lower bound of the
//! full distance, so the search stops when the next shell cannot be closer, or one shell after
//! the first hit (then the answer may miss a centroid with a much closer shape whose root is
//! farther than two wisps: an approximation that only affects which wisp a strand joins, never
//! whether it is kept). Cost: O(N · candidates), candidates ≈ 27–125.
//!
//! Initial centroids: strands at evenly spaced ranks of the Morton order of their roots (spread
//! over the scalp, deterministic). Wisps left with fewer than 3 strands (a wisp needs 3 guides)
//! give their strands to the nearest wisp that has enough. Assignment runs on rayon with
//! per-strand independent results, so the clustering does not depend on the thread count.

use rayon::prelude::*;

/// Dimensions of a strand's feature: root (3), middle − root (3), tip − root (3).
pub const FEATURE_DIM: usize = 9;
pub type Feature = [f32; FEATURE_DIM];
/// Weight of the shape vectors against the root position.
pub const SHAPE_WEIGHT: f32 = 0.5;
/// Smallest wisp: its 3 guides are 3 of its strands.
pub const MIN_WISP_STRANDS: usize = 3;
/// Lloyd iterations at most (the loop stops earlier when no strand changes wisp).
pub const MAX_ITERATIONS: usize = 12;

fn dist2(a: &Feature, b: &Feature) -> f32 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Uniform grid over centroid roots, stored as sorted (cell key, centroid) pairs.
struct Grid {
    lo: [f32; 3],
    cell: f32,
    dims: [i64; 3],
    entries: Vec<(u64, u32)>,
}

impl Grid {
    fn key(&self, c: [i64; 3]) -> u64 {
        ((c[0] as u64) << 42) | ((c[1] as u64) << 21) | c[2] as u64
    }
    fn cell_of(&self, p: &Feature) -> [i64; 3] {
        let mut c = [0i64; 3];
        for a in 0..3 {
            c[a] = (((p[a] - self.lo[a]) / self.cell).floor() as i64).clamp(0, self.dims[a] - 1);
        }
        c
    }
    /// The live centroids of `centroids` in the cells of `frame`.
    fn new(frame: &GridFrame, centroids: &[Feature], live: &[bool]) -> Self {
        let mut g = Grid {
            lo: frame.lo,
            cell: frame.cell,
            dims: frame.dims,
            entries: Vec::with_capacity(centroids.len()),
        };
        for (i, c) in centroids.iter().enumerate() {
            if live[i] {
                let k = g.key(g.cell_of(c));
                g.entries.push((k, i as u32));
            }
        }
        g.entries.sort_unstable();
        g
    }
    /// Every live centroid, nearest first by index on ties: the search's fallback.
    fn scan(&self, f: &Feature, centroids: &[Feature]) -> u32 {
        let mut best = (f32::INFINITY, u32::MAX);
        for &(_, idx) in &self.entries {
            let d = dist2(f, &centroids[idx as usize]);
            if best.1 == u32::MAX || d < best.0 || (d == best.0 && idx < best.1) {
                best = (d, idx);
            }
        }
        best.1
    }

    /// The nearest live centroid found by the shell search (see the module doc). A shell with
    /// more cells than there are centroids costs more than comparing with all of them (a strand
    /// far from every wisp, in a grid stretched by an outlier, would search 257³ cells: minutes
    /// for 60 strands), so the search then scans the centroids instead.
    fn nearest(&self, f: &Feature, centroids: &[Feature]) -> u32 {
        let c = self.cell_of(f);
        let max_ring = self.dims.iter().copied().max().unwrap_or(1);
        let mut best = (f32::INFINITY, u32::MAX);
        let mut first_hit: Option<i64> = None;
        let mut visited = 0usize;
        for ring in 0..=max_ring {
            let shell = if ring == 0 {
                1
            } else {
                ((2 * ring + 1).pow(3) - (2 * ring - 1).pow(3)) as usize
            };
            visited += shell;
            if first_hit.is_none() && visited > 4 * self.entries.len() + 64 {
                return self.scan(f, centroids);
            }
            if let Some(h) = first_hit {
                let bound = (ring - 1).max(0) as f32 * self.cell;
                if ring > h + 1 || bound * bound >= best.0 {
                    break;
                }
            }
            for dx in -ring..=ring {
                for dy in -ring..=ring {
                    for dz in -ring..=ring {
                        if dx.abs().max(dy.abs()).max(dz.abs()) != ring {
                            continue;
                        }
                        let q = [c[0] + dx, c[1] + dy, c[2] + dz];
                        if (0..3).any(|a| q[a] < 0 || q[a] >= self.dims[a]) {
                            continue;
                        }
                        let k = self.key(q);
                        let start = self.entries.partition_point(|e| e.0 < k);
                        for &(ek, idx) in &self.entries[start..] {
                            if ek != k {
                                break;
                            }
                            let d = dist2(f, &centroids[idx as usize]);
                            // The first candidate is always taken: a distance that overflows
                            // to infinity (or NaN) must still give the strand a wisp.
                            if best.1 == u32::MAX || d < best.0 || (d == best.0 && idx < best.1) {
                                best = (d, idx);
                            }
                        }
                    }
                }
            }
            if first_hit.is_none() && best.1 != u32::MAX {
                first_hit = Some(ring);
            }
        }
        best.1
    }
}

/// Interleaves the low 10 bits of three integers (Morton code).
fn morton(x: u32, y: u32, z: u32) -> u32 {
    let spread = |mut v: u32| {
        v &= 0x3ff;
        v = (v | (v << 16)) & 0x0300_00ff;
        v = (v | (v << 8)) & 0x0300_f00f;
        v = (v | (v << 4)) & 0x030c_30c3;
        (v | (v << 2)) & 0x0924_9249
    };
    spread(x) | (spread(y) << 1) | (spread(z) << 2)
}

/// Clusters `features` into at most `k` wisps of at least [`MIN_WISP_STRANDS`] strands (when
/// there are that many strands). Returns the wisp of every strand, wisps numbered 0.. with
/// no gaps.
pub fn cluster(features: &[Feature], k: usize) -> Vec<u32> {
    let n = features.len();
    if n == 0 {
        return Vec::new();
    }
    let k = k.clamp(1, (n / MIN_WISP_STRANDS).max(1));
    let frame = GridFrame::new(features, k);
    let mut centroids = initial_centroids(features, &frame, k);
    let mut live = vec![true; k];
    let mut assign = lloyd(features, &frame, &mut centroids, &live);
    // Wisps too small for 3 guides give their strands to the nearest wisp large enough.
    let mut size = vec![0usize; k];
    for &a in &assign {
        size[a as usize] += 1;
    }
    for c in 0..k {
        live[c] = size[c] >= MIN_WISP_STRANDS;
    }
    if live.iter().any(|l| *l) {
        let grid = Grid::new(&frame, &centroids, &live);
        for (i, a) in assign.iter_mut().enumerate() {
            if !live[*a as usize] {
                *a = grid.nearest(&features[i], &centroids);
            }
        }
    }
    renumber(&assign, k)
}

/// The grid's placement over the strands' roots: lower corner, cell side and cells per axis.
struct GridFrame {
    lo: [f32; 3],
    /// Extent of the roots along each axis.
    ext: [f32; 3],
    cell: f32,
    dims: [i64; 3],
}

impl GridFrame {
    /// Cells about one wisp apart over the roots' bounding box: the roots cover roughly half
    /// its surface, so a cell of `sqrt(area / k)` holds about one wisp's roots; at least 1/256
    /// of the box's longest side, and at most 2²⁰ cells per axis.
    fn new(features: &[Feature], k: usize) -> Self {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for f in features {
            for a in 0..3 {
                lo[a] = lo[a].min(f[a]);
                hi[a] = hi[a].max(f[a]);
            }
        }
        let ext = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
        let max_ext = ext.iter().copied().fold(0.0, f32::max);
        let area = ext[0] * ext[1] + ext[1] * ext[2] + ext[0] * ext[2];
        let mut cell = (area / k as f32).sqrt();
        if cell.is_nan() || cell <= max_ext / 256.0 {
            cell = max_ext / 256.0;
        }
        if !(cell > 0.0 && cell.is_finite()) {
            cell = 1.0;
        }
        let dims = ext.map(|e| ((e / cell).floor() as i64 + 1).clamp(1, 1 << 20));
        Self {
            lo,
            ext,
            cell,
            dims,
        }
    }
}

/// `k` initial centroids: the strands at evenly spaced ranks of their roots' Morton order
/// (10 bits per axis over the roots' box).
fn initial_centroids(features: &[Feature], frame: &GridFrame, k: usize) -> Vec<Feature> {
    let (lo, ext, n) = (frame.lo, frame.ext, features.len());
    let q = |v: f32, a: usize| {
        if ext[a] > 0.0 {
            ((v - lo[a]) / ext[a] * 1023.0) as u32
        } else {
            0
        }
    };
    let mut order: Vec<(u32, u32)> = features
        .iter()
        .enumerate()
        .map(|(i, f)| (morton(q(f[0], 0), q(f[1], 1), q(f[2], 2)), i as u32))
        .collect();
    order.sort_unstable();
    (0..k)
        .map(|c| features[order[(2 * c + 1) * n / (2 * k)].1 as usize])
        .collect()
}

/// Lloyd's iterations from `centroids` (at most [`MAX_ITERATIONS`], until no strand changes
/// wisp): each strand to its nearest live centroid, each centroid to its strands' mean.
/// Returns each strand's centroid.
fn lloyd(
    features: &[Feature],
    frame: &GridFrame,
    centroids: &mut [Feature],
    live: &[bool],
) -> Vec<u32> {
    let n = features.len();
    let mut assign = vec![u32::MAX; n];
    let mut next = vec![0u32; n];
    for _ in 0..MAX_ITERATIONS {
        let grid = Grid::new(frame, centroids, live);
        features
            .par_iter()
            .map(|f| grid.nearest(f, centroids))
            .collect_into_vec(&mut next);
        let changed = next != assign;
        std::mem::swap(&mut assign, &mut next);
        update_centroids(features, &assign, centroids, live);
        if !changed {
            break;
        }
    }
    assign
}

/// The wisps of `assign` (centroids 0..k) numbered without gaps, in centroid order.
fn renumber(assign: &[u32], k: usize) -> Vec<u32> {
    let mut id = vec![u32::MAX; k];
    let mut used = vec![false; k];
    for &a in assign {
        used[a as usize] = true;
    }
    let mut next_id = 0u32;
    for c in 0..k {
        if used[c] {
            id[c] = next_id;
            next_id += 1;
        }
    }
    assign.iter().map(|&a| id[a as usize]).collect()
}

/// Moves each live centroid with strands to their mean (summed in f64).
fn update_centroids(
    features: &[Feature],
    assign: &[u32],
    centroids: &mut [Feature],
    live: &[bool],
) {
    let k = centroids.len();
    let mut sum = vec![[0.0f64; FEATURE_DIM]; k];
    let mut count = vec![0u32; k];
    for (f, &a) in features.iter().zip(assign) {
        let a = a as usize;
        count[a] += 1;
        for d in 0..FEATURE_DIM {
            sum[a][d] += f[d] as f64;
        }
    }
    for c in 0..k {
        if count[c] > 0 && live[c] {
            for d in 0..FEATURE_DIM {
                centroids[c][d] = (sum[c][d] / count[c] as f64) as f32;
            }
        }
    }
}
