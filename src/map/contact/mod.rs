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
//! The light at the vertex's point on the fibre's lit side, along one ray toward the light:
//! the axis point moved by the fibre's radius toward the light, across the fibre
//! (`Projection::lit_side`, with the chord between the point's neighbours as the tangent). The
//! path tracer lights the fibre's surface; a ray from the axis also meets the fibres lying
//! against the lit side (render strands touch and interpenetrate), which the surface sees past.
//! At the axis, converged strands (91 points) read dense side-lit single scattering 0.84–0.89
//! and back-lit 0.84–0.92 of the path tracer; on the lit side 0.89–0.93 and 0.94–1.02
//! (ACCURACY.md §2, "Converged strands").
//!
//! The raster draws each segment with its two vertices' colours interpolated linearly, so the
//! light it shows at a point between them is the interpolation of the vertices' values: point
//! values are what that reconstruction needs. An average over the vertex's piece (half a
//! segment to each side) would filter the light along the fibre twice, and where fibres weave
//! over and under each other every few millimetres the camera sees mostly the lit parts, which
//! the double average dims: dense hair side-lit reads single scattering 0.84 of the path tracer
//! with piece averages, 0.92 with point values (ACCURACY.md §2, "Contact light at the vertex").
//!
//! A fibre segment S of radius r shadows the point o when:
//! - the perpendicular distance across the light from o to S's axis is below r, at a
//!   parameter t ∈ [0, 1) along S (joints are shared half-open, as in the exact reference);
//! - the crossing lies in front of o and at most `window_m` in front of it.
//!
//! The light is then ∏ ā_f over the covering segments, its direct fraction 1 when none covers
//! (0 otherwise), its σ̄f² the sum of their β̄_f²: what the exact reference's ray from the
//! vertex's lit side gives (`Footprint::FibresLitSide` with one ray per fibre). The vertex's
//! own strand does not shadow it within two segments (as the exact reference excludes them).
//! Fibres end where the strand's fibre share falls below one half, as the reference places
//! them.
//!
//! ## Cost
//! Segments are cut into parts of at most a bin across and along the light and binned across
//! the light (a uniform grid, counting sort; index lists), each bin sorted by the parts'
//! nearest depth; a query visits the bin holding its point and, there, only the parts whose
//! depth range meets the window (binary search, then a scan). The number of fibres a query
//! must take is inherent: every fibre crossing the ray inside the window; hence the window's
//! shortening with depth (`LightMap::light_at_vertex_seen`). The result does not depend on the
//! thread count.
//!
//! ## The camera
//! The camera sees the vertex only where its view ray reaches it; with the light near the
//! camera, the view and light rays cross the same fibres near the point. Each
//! fibre in the window is therefore counted with the probability that it is there given that
//! the point is seen (`q` = min(1, s / s_c) for a fibre at distance s, s_c the length over
//! which the view and light rays share fibres; `LightMap::light_at_seen`).

use super::Projection;
use crate::fiber::Fiber;
use glam::{Vec2, Vec3};

mod bins;
mod query;
mod segments;

use segments::{fiber_segments, light_frame_points};

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
    pub fiber_share: &'a [f32],
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
struct FiberSegment {
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

/// Most parts a segment is cut into (longer ones get longer parts).
const MAX_PARTS: usize = 64;

/// The fibres near the hair, binned across the light, ready for per-vertex queries.
#[derive(Clone, Debug)]
pub struct ContactShadows {
    window_m: f32,
    radius_m: f32,
    /// The map's projection: a query's point moves to the fibre's lit side, and a point
    /// light narrows fibres by ref/x (`Projection::central_ref_depth_m`).
    proj: Projection,
    points_per_strand: usize,
    /// Light-frame points of every render strand (NaN for strands with a non-finite point).
    points: Vec<Vec3>,
    /// The fibre segments, and their parts of at most a bin across and along the light.
    fibers: Vec<FiberSegment>,
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

/// The light a vertex receives from the fibres inside its window, at its point (exact without
/// a camera: the direct fraction is then 0 or 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearLight {
    /// 1 when no fibre in the window covers the point (with a camera, the probability).
    pub direct_fraction: f32,
    /// ∏ ā_f of the covering fibres, RGB.
    pub tf: Vec3,
    /// Σ β̄_f² of the covering fibres, RGB (rad²).
    pub sigma_f2: Vec3,
    /// Number of covering fibres (with a camera, the expected number).
    pub crossings: f32,
}

impl NearLight {
    /// Nothing in the window.
    pub const CLEAR: Self = Self {
        direct_fraction: 1.0,
        tf: Vec3::ONE,
        sigma_f2: Vec3::ZERO,
        crossings: 0.0,
    };
}

impl ContactShadows {
    /// Bins the fibres of `input` in the light frame of `proj` (the map's), with bins of
    /// `bin_m` across the light.
    pub fn build(input: &ContactInput, proj: &Projection, bin_m: f32) -> Self {
        let ppl = input.points_per_strand.max(1);
        let points = light_frame_points(input, proj);
        let (fibers, segments) = fiber_segments(input, proj, &points);
        let mut c = Self {
            window_m: input.window_m.max(0.0),
            radius_m: input.fiber.params().radius_m,
            proj: *proj,
            points_per_strand: ppl,
            points,
            fibers,
            segments: Vec::new(),
            max_dx: 0.0,
            origin: Vec2::ZERO,
            inv_bin: 0.0,
            dims: [0, 0],
            bin_start: Vec::new(),
            bin_items: Vec::new(),
        };
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
        let per_point = (size_of::<Vec3>() + size_of::<FiberSegment>()) as u64;
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
}
