//! Contact shadows: the exact shadow of the fibres just in front of a vertex, for hair whose
//! render strands are its real fibres (one fibre per strand).
//!
//! A map cell is an average over many fibres; a vertex on the lit side of the hair is lit or
//! not by the one or two fibres directly in front of it, which no cell resolves (ACCURACY.md
//! §1: with one fibre per strand the map alone reads the lit vertices 0.16–0.28 too dark binned
//! by truth, and the path tracer shows dense hair 10–20% brighter front-lit). When every render
//! strand *is* a fibre, the geometry in front of the vertex is known exactly, so over a window
//! of `window_m` toward the light the vertex's light is computed from the fibres themselves,
//! and only what lies beyond the window comes from the map (read at the window's far end,
//! [`super::LightMap::light_at_vertex_seen`]). The map's expected crossings inside the window
//! are replaced by the real ones: unbiased wherever the map is, and exact as the window grows.
//!
//! ## What a vertex receives
//! The vertex stands for the piece of fibre half a segment to each side (the exact reference's
//! `Footprint::Fibres`). Along each half, the light-frame point o(u), u ∈ [0, 1], moves on a
//! straight line. A fibre segment S of radius r shadows o(u) where (all linear in u, so their
//! intersection is one interval of u):
//! - the perpendicular distance across the light from o(u) to S's axis is below r, at a
//!   parameter t ∈ [0, 1) along S (joints are shared half-open, as in the exact reference);
//! - the crossing lies in front of o(u) and at most `window_m` in front of it.
//!
//! The half's light is then the exact average over u of ∏ ā_f over the segments covering u
//! (a sweep over the intervals' ends), its direct fraction the share of u that no segment
//! covers, its σ̄f² the share-weighted sum of β̄_f²: what infinitely many rays along the piece
//! would give, with no sampling noise. The vertex's own strand does not shadow it within two
//! segments (as the exact reference excludes them). Fibres end where the strand's fibre share
//! falls below one half, as the reference places them.
//!
//! ## Cost
//! Segments are cut into parts of at most a bin across and along the light and binned across
//! the light (a uniform grid, counting sort; index lists), each bin sorted by the parts'
//! nearest depth; a half of a piece is cut the same way, and each of its parts visits the bins
//! it touches and, in each, only the parts whose depth range meets the window (binary search,
//! then a scan). A part listed in several bins is taken in the first bin the query part and it
//! share. The number of fibres a query must take is inherent: every fibre crossing the
//! "curtain" the piece sweeps toward the light inside the window, about (piece length / fibre
//! width) × the expected crossings along one ray; hence the window's shortening with depth
//! (`LightMap::light_at_vertex_seen`). The result does not depend on the thread count.
//!
//! ## The camera
//! A vertex's colour is the average over its piece, but the camera sees only the parts of the
//! piece its view ray reaches; with the light near the camera those are the lit parts. Each
//! fibre in the window is therefore counted with the probability that it is there given that
//! the point is seen (`q` = min(1, s / s_c) for a fibre at distance s, s_c the length over
//! which the view and light rays share fibres; `LightMap::light_at_seen`).

use super::Projection;
use crate::fiber::Fiber;
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// What contact shadows are built from.
#[derive(Clone, Copy)]
pub struct ContactInput<'a> {
    /// Render-strand points (world, metres), strand after strand, root first; each render
    /// strand is one fibre.
    pub positions: &'a [Vec3],
    /// Points per render strand (≥ 1).
    pub points_per_strand: usize,
    /// Share of the strand's fibre present at each point, or empty for all: the fibre covers a
    /// segment where the mean share of its two ends is at least ½.
    pub fibre_share: &'a [f32],
    /// How far in front of a vertex the fibres are taken exactly, metres (> 0).
    pub window_m: f32,
    /// The fibre: radius and per-crossing forward scattering.
    pub fiber: &'a Fiber,
}

/// One fibre segment in the light frame.
#[derive(Clone, Copy, Debug)]
struct Segment {
    /// Projection of A across the light (y, z) and b − a, metres.
    a: Vec2,
    d: Vec2,
    /// 1/|d|.
    inv_len: f32,
    /// Depth of A along the light and its change to B, metres.
    x_a: f32,
    dx: f32,
    /// The fibre segment this is a part of (index into `ContactShadows::fibres`).
    parent: u32,
}

/// What a fibre segment's parts share: how a crossing scatters, and whose it is.
#[derive(Clone, Copy, Debug)]
struct FibreSegment {
    /// Per-crossing forward transmittance ā_f and spread β̄_f² (Zinke 2008 Eqs. 6, 19, 20)
    /// for the light's inclination to this segment.
    a_f: [f32; 3],
    beta2: [f32; 3],
    /// Render strand and segment index along it (own-strand exclusion).
    strand: u32,
    seg: u32,
}

impl Segment {
    #[inline]
    fn x_min(&self) -> f32 {
        self.x_a.min(self.x_a + self.dx)
    }
}

/// Segments of the vertex's own strand that do not shadow it: k − 2 ..= k + 1 (the two
/// segments on each side of point k), as the exact reference excludes.
const OWN_BEFORE: i64 = 2;
const OWN_AFTER: i64 = 1;

/// Most bins a side (a hostile extent gets coarser bins, never a huge grid).
const MAX_BINS: f32 = 4096.0;

/// Most parts a segment or a half-piece is cut into (longer ones get longer parts).
const MAX_PARTS: usize = 64;

/// The fibres near the hair, binned across the light, ready for per-vertex queries.
#[derive(Clone, Debug, Default)]
pub struct ContactShadows {
    window_m: f32,
    radius_m: f32,
    /// Lateral scale for a point light (`Projection::Central`): r shrinks as ref/x.
    central_ref_m: Option<f32>,
    points_per_strand: usize,
    /// Light-frame points of every render strand (NaN for strands with a non-finite point).
    points: Vec<Vec3>,
    /// The fibre segments, and their parts of at most a bin across and along the light.
    fibres: Vec<FibreSegment>,
    segments: Vec<Segment>,
    /// Largest depth extent of any segment, metres (bounds the window's binary search).
    max_dx: f32,
    origin: Vec2,
    inv_bin: f32,
    dims: [usize; 2],
    bin_start: Vec<u32>,
    /// Each bin's parts (indices), by nearest depth.
    bin_items: Vec<u32>,
}

/// The light a vertex receives from the fibres inside its window: exact averages over its
/// piece of fibre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearLight {
    /// Share of the piece no fibre in the window covers.
    pub direct_fraction: f32,
    /// Mean ∏ ā_f over the piece, RGB.
    pub tf: Vec3,
    /// Mean Σ β̄_f² over the piece, RGB (rad²).
    pub sigma_f2: Vec3,
    /// Mean number of crossings over the piece.
    pub crossings: f32,
}

impl NearLight {
    /// All zero: the start of a weighted sum.
    const ZERO: Self = Self {
        direct_fraction: 0.0,
        tf: Vec3::ZERO,
        sigma_f2: Vec3::ZERO,
        crossings: 0.0,
    };

    /// Adds `w` × `other` (averages over parts of a piece).
    #[inline]
    fn add_weighted(&mut self, w: f32, other: &Self) {
        self.direct_fraction += w * other.direct_fraction;
        self.tf += w * other.tf;
        self.sigma_f2 += w * other.sigma_f2;
        self.crossings += w * other.crossings;
    }

    /// Nothing in the window.
    pub const CLEAR: Self = Self {
        direct_fraction: 1.0,
        tf: Vec3::ONE,
        sigma_f2: Vec3::ZERO,
        crossings: 0.0,
    };
}

/// Reusable buffer of [`ContactShadows::near_light`] (one per worker).
#[derive(Clone, Debug, Default)]
pub struct ContactScratch {
    covers: Vec<Cover>,
    events: Vec<(f32, u32)>,
}

/// One segment's shadow on a half: the interval of u it covers and what it does there.
#[derive(Clone, Copy, Debug)]
struct Cover {
    u0: f32,
    u1: f32,
    a_f: Vec3,
    beta2: Vec3,
    /// Probability that the fibre is there given that the camera sees the point (1 − the
    /// share of it the view ray would have crossed too; 1 without a camera).
    q: f32,
}

/// What a query takes in front of the point: the window, and the length over which the ray
/// toward the camera shares the light ray's fibres.
#[derive(Clone, Copy, Debug)]
struct Reach {
    window_m: f32,
    shared_m: f32,
}

impl ContactShadows {
    /// Bins the fibres of `input` in the light frame of `proj` (the map's), with bins of
    /// `bin_m` across the light.
    pub fn build(input: &ContactInput, proj: &Projection, bin_m: f32) -> Self {
        let ppl = input.points_per_strand.max(1);
        let strands = input.positions.len() / ppl;
        let r = input.fiber.params().radius_m;
        let points: Vec<Vec3> = input.positions[..strands * ppl]
            .par_chunks(ppl)
            .flat_map_iter(|pts| {
                let finite = pts.iter().all(|p| p.is_finite());
                pts.iter()
                    .map(move |p| if finite { proj.point(*p) } else { Vec3::NAN })
            })
            .collect();
        let share = input.fibre_share;
        let fiber = input.fiber;
        let pairs: Vec<(FibreSegment, Segment)> = (0..strands)
            .into_par_iter()
            .flat_map_iter(|s| {
                let pts = &points[s * ppl..(s + 1) * ppl];
                let at = move |i: usize| share.get(s * ppl + i).copied().unwrap_or(1.0);
                pts.windows(2).enumerate().filter_map(move |(k, w)| {
                    let (a, b) = (w[0], w[1]);
                    if !(a.is_finite() && b.is_finite()) || 0.5 * (at(k) + at(k + 1)) < 0.5 {
                        return None;
                    }
                    let d = Vec2::new(b.y - a.y, b.z - a.z);
                    let len = d.length();
                    // A fibre exactly along the light has a disc, not a strip, as its shadow;
                    // the exact reference skips it too.
                    if len * len <= 1e-18 {
                        return None;
                    }
                    let (wa, wb) = (proj.to_world(a), proj.to_world(b));
                    let u = (wb - wa).normalize_or_zero();
                    let sin_theta = u.dot(proj.toward_light(0.5 * (wa + wb)));
                    let f = fiber.forward_scatter(sin_theta);
                    let a_f = f.a_f.clamp(Vec3::ZERO, Vec3::ONE);
                    let fibre = FibreSegment {
                        a_f: a_f.into(),
                        beta2: f.beta_f2.max(Vec3::ZERO).into(),
                        strand: s as u32,
                        seg: k as u32,
                    };
                    let seg = Segment {
                        a: Vec2::new(a.y, a.z),
                        d,
                        inv_len: 1.0 / len,
                        x_a: a.x,
                        dx: b.x - a.x,
                        parent: 0,
                    };
                    Some((fibre, seg))
                })
            })
            .collect();
        let central_ref_m = match *proj {
            Projection::Parallel { .. } => None,
            Projection::Central { ref_depth_m, .. } => Some(ref_depth_m),
        };
        let mut c = Self {
            window_m: input.window_m.max(0.0),
            radius_m: r,
            central_ref_m,
            points_per_strand: ppl,
            points,
            ..Default::default()
        };
        let (fibres, segments): (Vec<FibreSegment>, Vec<Segment>) = pairs
            .into_par_iter()
            .enumerate()
            .map(|(i, (f, s))| {
                (
                    f,
                    Segment {
                        parent: i as u32,
                        ..s
                    },
                )
            })
            .unzip();
        c.fibres = fibres;
        c.bin(segments, bin_m);
        c
    }

    /// How many equal parts a straight piece is cut into so that each spans at most one bin
    /// across the light and one bin along it (at most [`MAX_PARTS`]).
    #[inline]
    fn parts(&self, lateral_m: f32, depth_m: f32) -> usize {
        let n = (lateral_m.max(depth_m.abs()) * self.inv_bin).ceil();
        if n.is_nan() {
            1
        } else {
            (n as usize).clamp(1, MAX_PARTS)
        }
    }

    /// Upper bound, in bytes, of what contact shadows hold once built from `points` render
    /// points whose segments are at most `segment_len_m` long, with bins of `bin_m`: per point
    /// its light-frame position and fibre record; per part (a segment cut into at most
    /// [`MAX_PARTS`] parts of a bin) the part, its bin rectangle while binning, and its
    /// listings (at most 3 × 3 bins: a part spans at most two bins a side, three with the
    /// radius' padding); two bin-offset tables of at most [`MAX_BINS`]² entries.
    pub fn estimated_bytes(points: u64, segment_len_m: f32, bin_m: f32) -> u64 {
        let parts_each = (segment_len_m / bin_m.max(1e-9)).ceil();
        let parts_each = if parts_each.is_finite() {
            (parts_each as u64).clamp(1, MAX_PARTS as u64)
        } else {
            MAX_PARTS as u64
        };
        let parts = points.saturating_mul(parts_each);
        let rect = size_of::<Option<([usize; 2], [usize; 2])>>() as u64;
        let per_part = size_of::<Segment>() as u64 + rect + 9 * size_of::<u32>() as u64;
        let per_point = (size_of::<Vec3>() + size_of::<FibreSegment>()) as u64;
        let bins = (MAX_BINS * MAX_BINS) as u64 * 2 * size_of::<u32>() as u64;
        points
            .saturating_mul(per_point)
            .saturating_add(parts.saturating_mul(per_part))
            .saturating_add(bins)
    }

    /// Metres in front of a vertex taken exactly.
    pub fn window_m(&self) -> f32 {
        self.window_m
    }

    /// The bin rectangle of a lateral box widened by the fibre radius.
    #[inline]
    fn bin_rect(&self, lo: Vec2, hi: Vec2) -> Option<([usize; 2], [usize; 2])> {
        self.bin_rect_padded(lo, hi, self.radius_m)
    }

    /// The bin rectangle of a lateral box widened by `pad`.
    #[inline]
    fn bin_rect_padded(&self, lo: Vec2, hi: Vec2, pad: f32) -> Option<([usize; 2], [usize; 2])> {
        let r = Vec2::splat(pad);
        let l = ((lo - r - self.origin) * self.inv_bin).floor();
        let h = ((hi + r - self.origin) * self.inv_bin).floor();
        if !(l.is_finite() && h.is_finite()) || h.x < 0.0 || h.y < 0.0 {
            return None;
        }
        let (dx, dy) = (self.dims[0] as f32, self.dims[1] as f32);
        if l.x >= dx || l.y >= dy {
            return None;
        }
        Some((
            [l.x.max(0.0) as usize, l.y.max(0.0) as usize],
            [h.x.min(dx - 1.0) as usize, h.y.min(dy - 1.0) as usize],
        ))
    }

    fn seg_rect(&self, s: &Segment) -> Option<([usize; 2], [usize; 2])> {
        let (a, b) = (s.a, s.a + s.d);
        self.bin_rect(a.min(b), a.max(b))
    }

    /// The bin grid over the segments' widened projections; each segment cut into parts of at
    /// most a bin across and along the light (so a part lies in at most 2 × 2 bins, padded by
    /// r, and a window's scan skips whole parts), each bin sorted by nearest depth.
    fn bin(&mut self, segments: Vec<Segment>, bin_m: f32) {
        let (mut lo, mut hi) = (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN));
        for s in &segments {
            lo = lo.min(s.a.min(s.a + s.d));
            hi = hi.max(s.a.max(s.a + s.d));
        }
        if segments.is_empty() {
            self.origin = Vec2::ZERO;
            self.inv_bin = 1.0;
            self.dims = [1, 1];
            self.bin_start = vec![0, 0];
            self.bin_items.clear();
            return;
        }
        let pad = Vec2::splat(self.radius_m + bin_m.max(1e-6));
        self.origin = lo - pad;
        let extent = hi + pad - self.origin;
        let bin = bin_m.max(1e-6).max(extent.max_element() / MAX_BINS);
        let dims = (extent / bin).ceil().max(Vec2::ONE);
        self.inv_bin = 1.0 / bin;
        self.dims = [dims.x as usize, dims.y as usize];
        // Parts tile their segment: each owns t ∈ [0, 1) of itself, as segments own theirs.
        self.segments = segments
            .par_iter()
            .flat_map_iter(|s| {
                let n = self.parts(s.d.length(), s.dx);
                let step = 1.0 / n as f32;
                (0..n).map(move |i| {
                    let t = i as f32 * step;
                    let d = s.d * step;
                    Segment {
                        a: s.a + s.d * t,
                        d,
                        inv_len: s.inv_len * n as f32,
                        x_a: s.x_a + s.dx * t,
                        dx: s.dx * step,
                        ..*s
                    }
                })
            })
            .collect();
        self.max_dx = self
            .segments
            .iter()
            .map(|s| s.dx.abs())
            .fold(0.0f32, f32::max);
        let ny = self.dims[1];
        let mut start = vec![0u32; self.dims[0] * ny + 1];
        let rects: Vec<_> = self.segments.par_iter().map(|s| self.seg_rect(s)).collect();
        for ([x0, y0], [x1, y1]) in rects.iter().flatten() {
            for bx in *x0..=*x1 {
                for by in *y0..=*y1 {
                    start[bx * ny + by + 1] += 1;
                }
            }
        }
        for i in 1..start.len() {
            start[i] += start[i - 1];
        }
        let mut cursor = start.clone();
        let mut items = vec![0u32; *start.last().unwrap_or(&0) as usize];
        for (i, rect) in rects.iter().enumerate() {
            if let Some(([x0, y0], [x1, y1])) = rect {
                for bx in *x0..=*x1 {
                    for by in *y0..=*y1 {
                        let c = &mut cursor[bx * ny + by];
                        items[*c as usize] = i as u32;
                        *c += 1;
                    }
                }
            }
        }
        let segs = &self.segments;
        let mut bins: Vec<&mut [u32]> = Vec::with_capacity(start.len() - 1);
        let mut rest: &mut [u32] = &mut items;
        for w in start.windows(2) {
            let (a, b) = std::mem::take(&mut rest).split_at_mut((w[1] - w[0]) as usize);
            bins.push(a);
            rest = b;
        }
        // Ties (equal nearest depth) by index: a total order, so the bins do not depend on
        // the thread count.
        bins.into_par_iter().for_each(|bin| {
            bin.sort_unstable_by(|a, b| {
                let (sa, sb) = (&segs[*a as usize], &segs[*b as usize]);
                sa.x_min().total_cmp(&sb.x_min()).then(a.cmp(b))
            })
        });
        self.bin_items = items;
        self.bin_start = start;
    }

    /// The light render-strand point `vertex` receives from the fibres within the window in
    /// front of it: the exact average over the piece of fibre it stands for. `scratch` is
    /// reused between calls (no allocation once warm).
    pub fn near_light(
        &self,
        vertex: usize,
        window_m: f32,
        shared_m: f32,
        scratch: &mut ContactScratch,
    ) -> NearLight {
        let ppl = self.points_per_strand;
        let (strand, k) = (vertex / ppl, vertex % ppl);
        let Some(pts) = self.points.get(strand * ppl..(strand + 1) * ppl) else {
            return NearLight::CLEAR;
        };
        let p = pts[k];
        if !p.is_finite() {
            return NearLight::CLEAR;
        }
        // The two halves of the piece (a point where the strand ends), half the weight each.
        let before = if k > 0 { p.lerp(pts[k - 1], 0.5) } else { p };
        let after = if k + 1 < ppl {
            p.lerp(pts[k + 1], 0.5)
        } else {
            p
        };
        let own = (strand as u32, k as i64);
        let reach = Reach {
            window_m: window_m.clamp(0.0, self.window_m),
            shared_m: if shared_m.is_finite() {
                shared_m.max(0.0)
            } else {
                0.0
            },
        };
        let mut sum = NearLight::ZERO;
        sum.add_weighted(0.5, &self.half(p, before, own, reach, scratch));
        sum.add_weighted(0.5, &self.half(p, after, own, reach, scratch));
        sum
    }

    /// The exact average light along the straight half from `a` to `b` (light frame): the mean
    /// of its parts of at most a bin across and along the light (`parts`), each visiting the
    /// few bins it touches.
    fn half(
        &self,
        a: Vec3,
        b: Vec3,
        own: (u32, i64),
        reach: Reach,
        scratch: &mut ContactScratch,
    ) -> NearLight {
        let n = self.parts(Vec2::new(b.y - a.y, b.z - a.z).length(), b.x - a.x);
        if n == 1 {
            return self.part(a, b, own, reach, scratch);
        }
        let mut sum = NearLight::ZERO;
        let inv = 1.0 / n as f32;
        for i in 0..n {
            let (from, to) = (a.lerp(b, i as f32 * inv), a.lerp(b, (i + 1) as f32 * inv));
            sum.add_weighted(inv, &self.part(from, to, own, reach, scratch));
        }
        sum
    }

    /// [`Self::half`] for one part (a straight piece within about a bin).
    fn part(
        &self,
        a: Vec3,
        b: Vec3,
        own: (u32, i64),
        reach: Reach,
        scratch: &mut ContactScratch,
    ) -> NearLight {
        let covers = &mut scratch.covers;
        covers.clear();
        let (ayz, byz) = (Vec2::new(a.y, a.z), Vec2::new(b.y, b.z));
        // A segment shadows o(u) only within r of its axis, so it is listed (padded by r) in
        // the bin holding o(u): the part's own bins suffice.
        let Some(([x0, y0], [x1, y1])) = self.bin_rect_padded(ayz.min(byz), ayz.max(byz), 0.0)
        else {
            return NearLight::CLEAR;
        };
        let x_lo = a.x.min(b.x) - reach.window_m;
        let x_hi = a.x.max(b.x);
        // A point light narrows fibres as it narrows everything at their depth.
        let r = match self.central_ref_m {
            None => self.radius_m,
            Some(ref_m) => self.radius_m * (ref_m / (0.5 * (a.x + b.x))).min(1.0),
        };
        let ny = self.dims[1];
        for bx in x0..=x1 {
            for by in y0..=y1 {
                let c = bx * ny + by;
                let items =
                    &self.bin_items[self.bin_start[c] as usize..self.bin_start[c + 1] as usize];
                // Segments whose nearest depth is below x_lo − max_dx lie wholly before the
                // window.
                let first = items
                    .partition_point(|&i| self.segments[i as usize].x_min() < x_lo - self.max_dx);
                for &i in &items[first..] {
                    let s = &self.segments[i as usize];
                    if s.x_min() >= x_hi {
                        break;
                    }
                    // Most parts scanned do not cover the query: test that first, and read the
                    // part's fibre record (elsewhere in memory) only for those that do.
                    let Some((u0, u1, dist)) = cover(s, a, b, r, reach.window_m) else {
                        continue;
                    };
                    // Taken once: in the first bin the half's and the segment's rectangles
                    // share.
                    if let Some(([sx0, sy0], _)) = self.seg_rect(s)
                        && (bx, by) != (sx0.max(x0), sy0.max(y0))
                    {
                        continue;
                    }
                    let fibre = &self.fibres[s.parent as usize];
                    if fibre.strand == own.0
                        && (own.1 - OWN_BEFORE..=own.1 + OWN_AFTER).contains(&(fibre.seg as i64))
                    {
                        continue;
                    }
                    // The view ray shares a fibre at distance s with the light ray over a
                    // share 1 − s/s_c of its width (`LightMap::light_at_seen`): given the point
                    // is seen, the fibre is there with probability min(1, s/s_c).
                    let q = if reach.shared_m > 0.0 {
                        (dist / reach.shared_m).min(1.0)
                    } else {
                        1.0
                    };
                    covers.push(Cover {
                        u0,
                        u1,
                        a_f: Vec3::from(fibre.a_f),
                        beta2: Vec3::from(fibre.beta2),
                        q,
                    });
                }
            }
        }
        sweep(covers, &mut scratch.events)
    }
}

/// The interval of u ∈ [0, 1] over which segment `s` shadows o(u) = a + u(b − a) within a
/// window of `window_m` in front: one interval, as every condition is linear in u (module
/// doc), and the crossing's distance in front of the point at the interval's middle, metres.
/// `None` when empty.
#[inline]
fn cover(s: &Segment, a: Vec3, b: Vec3, r: f32, window_m: f32) -> Option<(f32, f32, f32)> {
    let rel0 = Vec2::new(a.y, a.z) - s.a;
    let du = Vec2::new(b.y - a.y, b.z - a.z);
    let dir = s.d * s.inv_len;
    // Parameter along S: t(u) = t0 + u·tu; signed distance across S: h(u) = h0 + u·hu.
    let inv_len2 = s.inv_len * s.inv_len;
    let (t0, tu) = (rel0.dot(s.d) * inv_len2, du.dot(s.d) * inv_len2);
    let (h0, hu) = (rel0.perp_dot(dir), du.perp_dot(dir));
    // Depth of the crossing minus depth of the point: e(u) = e0 + u·eu.
    let e0 = s.x_a + s.dx * t0 - a.x;
    let eu = s.dx * tu - (b.x - a.x);
    let mut iv = (0.0f32, 1.0f32);
    // Each condition α + β·u < 0 (strict) or ≤ 0.
    let conds = [
        (h0 - r, hu, true),           // h < r
        (-h0 - r, -hu, true),         // h > −r
        (-t0, -tu, false),            // t ≥ 0
        (t0 - 1.0, tu, true),         // t < 1
        (e0, eu, true),               // crossing in front of the point
        (-e0 - window_m, -eu, false), // ... by at most the window
    ];
    for (alpha, beta, strict) in conds {
        if beta == 0.0 {
            let fails = if strict { alpha >= 0.0 } else { alpha > 0.0 };
            if fails || alpha.is_nan() {
                return None;
            }
        } else {
            let u = -alpha / beta;
            if beta > 0.0 {
                iv.1 = iv.1.min(u);
            } else {
                iv.0 = iv.0.max(u);
            }
        }
    }
    // A half of zero length (the strand's end) is a point: it is covered or not.
    if du == Vec2::ZERO && b.x == a.x {
        return Some((0.0, 1.0, -e0));
    }
    let mid = 0.5 * (iv.0 + iv.1);
    (iv.1 > iv.0).then_some((iv.0, iv.1, -(e0 + mid * eu)))
}

/// The average over u ∈ [0, 1] of the light through the covers over u, the share of u no
/// present cover blocks and the spreads, exact for the given intervals. A cover is present with
/// probability q (1 without a camera), independently: it lets through 1 − q(1 − ā_f) on average
/// and leaves the direct ray unblocked with probability 1 − q. One pass over the intervals' ends
/// in increasing order carries the sums of the logarithms of the open covers (and, per factor,
/// how many of them are exactly 0); where none is open the sums restart from 0, so rounding does
/// not accumulate across the gaps.
fn sweep(covers: &[Cover], events: &mut Vec<(f32, u32)>) -> NearLight {
    if covers.is_empty() {
        return NearLight::CLEAR;
    }
    let mut var = Vec3::ZERO;
    let mut crossings = 0.0;
    events.clear();
    for (i, c) in covers.iter().enumerate() {
        var += (c.u1 - c.u0) * c.q * c.beta2;
        crossings += (c.u1 - c.u0) * c.q;
        events.push((c.u0, 2 * i as u32));
        events.push((c.u1, 2 * i as u32 + 1));
    }
    events.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let (mut tf, mut direct, mut prev) = (Vec3::ZERO, 0.0f32, 0.0f32);
    // Logarithms and zero counts of the open covers' factors: three colours, then direct.
    let (mut log, mut zeros, mut open) = ([0.0f32; 4], [0i32; 4], 0i32);
    let value = |log: &[f32; 4], zeros: &[i32; 4], k: usize| {
        if zeros[k] > 0 {
            0.0
        } else {
            log[k].exp().min(1.0)
        }
    };
    for &(u, code) in events.iter() {
        let w = u - prev;
        if w > 0.0 {
            if open == 0 {
                tf += Vec3::splat(w);
                direct += w;
            } else {
                let t = Vec3::new(
                    value(&log, &zeros, 0),
                    value(&log, &zeros, 1),
                    value(&log, &zeros, 2),
                );
                tf += w * t;
                direct += w * value(&log, &zeros, 3);
            }
            prev = u;
        }
        let c = &covers[(code >> 1) as usize];
        let sign = if code & 1 == 0 { 1 } else { -1 };
        open += sign;
        if open == 0 {
            log = [0.0; 4];
            zeros = [0; 4];
            continue;
        }
        let q = c.q.clamp(0.0, 1.0);
        let factors = [
            1.0 - q * (1.0 - c.a_f.x),
            1.0 - q * (1.0 - c.a_f.y),
            1.0 - q * (1.0 - c.a_f.z),
            1.0 - q,
        ];
        for (k, f) in factors.into_iter().enumerate() {
            if f > 0.0 {
                log[k] += sign as f32 * f.ln();
            } else {
                zeros[k] += sign;
            }
        }
    }
    let w = 1.0 - prev;
    if w > 0.0 {
        tf += Vec3::splat(w);
        direct += w;
    }
    NearLight {
        direct_fraction: direct.clamp(0.0, 1.0),
        tf: tf.clamp(Vec3::ZERO, Vec3::ONE),
        sigma_f2: var,
        crossings,
    }
}
