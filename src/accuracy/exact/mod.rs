//! The exact reference for the map: light shot along rays through explicit fibre cylinders.
//!
//! The map bins render-strand samples into cells and reads a filtered, column-averaged value;
//! this module measures what that value should be, with no grid and no statistical model of
//! the hair: every render strand becomes `F` real fibres (cylinders of the fibre's radius r
//! along polylines), and each queried point receives the average, over rays from a footprint
//! disc around it toward the light, of what those rays went through (Zinke 2008 §4: a ray's
//! forward transmittance is the product of ā_f(θ) over the fibres it crosses, its spread the sum
//! of β̄_f²(θ); "direct" rays cross none).
//!
//! ## Fibre placement
//! Each render strand becomes F fibres at documented, deterministic offsets (`placement.rs`);
//! with F = 1 the only fibre is the strand itself, so the geometry is exact, not a model.
//!
//! ## A ray and its crossings
//! A ray along the light L meets the cylinder around a straight segment AB exactly when the
//! distance between the ray's line and the segment's axis is below r. For a ray parallel to L
//! that distance is measured in the plane across the light: with a, b the projections of A, B
//! on that plane and o the ray's point, the ray crosses the fibre where the perpendicular
//! distance from o to the line ab is below r, at parameter t = (o − a)·(b − a)/|b − a|² along
//! the segment. Joints are shared half-open: a segment owns t ∈ [0, 1), so a ray through a joint
//! counts one crossing, not two. A segment whose projection is shorter than 1e-9 m (a fibre
//! exactly along the light) is skipped: its cross-section is a disc of area πr², not a strip.
//! The crossing lies before the point when the crossing depth x_A + t(x_B − x_A) (metres along
//! L) is smaller than the point's depth.
//!
//! ## Point lights
//! For a point light the fibres are placed in the map's central projection
//! ([`Projection::Central`]), where every ray toward the light is a line of constant (y, z):
//! the same binning and crossing test apply, with a fibre's radius scaled like everything
//! else at its depth (ref/x). This is exact for the rays' geometry up to the bending of a
//! straight segment by the projection (second order in the segment's length over its
//! distance to the light: 1e-5 for 8 mm segments 1 m away) and the obliquity of a ray off the
//! axis, which widens a fibre's shadow across it by at most 1/cos α (2% at 11°).
//!
//! ## Footprint and exclusion
//! Rays start at `rays` points of a Vogel spiral filling a disc of radius `footprint_radius_m`
//! across the light, centred on the queried point and at its depth: the value is the average
//! light over that disc, what a map column (also an average across the light) estimates. The
//! point's own render strand is excluded over `exclude_segments` segments on each side of the
//! point: a strand does not shadow itself where it is (at F = 1 every ray through the fibre
//! would otherwise start inside it), while the same strand higher up, curling back in front of
//! the point, still shadows it.
//!
//! ## Cost
//! Segments are binned across the light into a uniform 2D grid (each segment into every bin
//! its r-widened projection touches, counting sort, no hashing); a ray visits only its own bin.
//! Building is O(segments × bins per segment); a query is O(rays × segments in a bin). Both
//! run in parallel and the results do not depend on the thread count (each query is
//! independent and sums its rays in a fixed order).

use crate::fiber::Fiber;
use crate::map::lateral_bins::list_by_depth;
use crate::map::{MapLight, Projection};
use glam::{Vec2, Vec3};
use rayon::prelude::*;

mod placement;
mod rays;
mod segments;

use placement::place_fibers;
use segments::{BinGrid, fiber_segments};

/// What the exact reference is built from.
#[derive(Clone, Copy)]
pub struct ExactInput<'a> {
    /// Render-strand points (world, metres), strand after strand, root first.
    pub positions: &'a [Vec3],
    /// Points per render strand (≥ 2).
    pub points_per_strand: usize,
    /// Real fibres placed around each render strand (≥ 1; 1 = the strand itself).
    pub fibers_per_strand: u32,
    /// Radius of the disc across the strand within which its fibres are placed, metres
    /// (unused when `fibers_per_strand` is 1).
    pub bundle_radius_m: f32,
    /// Seed of each bundle's turn (0: the documented placement). Another seed turns the same
    /// pattern of fibres by other per-strand angles: the same hair, its fibres elsewhere in
    /// each bundle. Comparing two seeds measures how much of a point's light depends on where
    /// the fibres happen to lie, which no model of the render strands can know
    /// (`accuracy::placement_floor`).
    pub placement_seed: u64,
    /// Share of each strand's fibres present at each point (`StrandGeometry::fibre_share`), or
    /// empty for all. Fibre f of F covers a segment where the mean share of its two ends is at
    /// least (f + ½)/F, so the fibres end one by one as the share falls.
    pub fiber_share: &'a [f32],
    /// The light's geometry (a direction, or a point light and the point it aims at).
    pub light: MapLight,
    /// The fibre: radius and per-crossing forward scattering.
    pub fiber: &'a Fiber,
}

/// Where the rays of a query start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Footprint {
    /// A disc across the light, centred on the point and at its depth.
    Disc {
        /// Radius of the disc, metres.
        radius_m: f32,
        /// Rays per point.
        rays: u32,
        /// Segments of the point's own strand excluded on each side of the point.
        exclude_segments: u32,
    },
    /// On the fibres the vertex stands for: every placed fibre of its render strand, along
    /// the piece of strand the vertex represents (half a segment on each side). Each ray
    /// ignores its own fibre near its start; the other fibres of the bundle shadow it as any
    /// fibre does. This is the light the hair drawn for this vertex actually receives.
    Fibers {
        /// Rays per vertex (spread evenly over the fibres and along the piece).
        rays: u32,
    },
    /// As [`Footprint::Fibres`], each origin moved onto its fibre's lit side: by the fibre's
    /// radius toward the light, across the fibre ([`Projection::lit_side`]). The path tracer
    /// lights the fibre's surface; a ray from the axis also meets fibres lying against the
    /// lit side, which the surface there sees past. With one ray per fibre this is the ray
    /// contact shadows take (`map::contact`).
    FibersLitSide {
        /// Rays per vertex (spread evenly over the fibres and along the piece).
        rays: u32,
    },
    /// On all the hair within a ball around the vertex: rays start at points spread evenly
    /// by length over every placed fibre (of any strand) inside the ball. This is the mean
    /// light received by the hair near the vertex, at the resolution `radius_m`; unlike a disc
    /// across the light it never samples empty space beside a hair surface.
    Ball {
        /// Radius of the ball, metres.
        radius_m: f32,
        /// Rays per vertex.
        rays: u32,
    },
}

/// One fibre segment in the light frame.
#[derive(Clone, Copy, Debug)]
struct Segment {
    /// Projection of A across the light (y, z), metres.
    a: Vec2,
    /// b − a across the light.
    d: Vec2,
    /// 1/|d|².
    inv_len2: f32,
    /// Depth of A along the light and its change to B, metres.
    x_a: f32,
    dx: f32,
    /// sin θ = ωi·u of the light on this fibre (ωi toward the light).
    sin_theta: f32,
    /// Render strand, fibre within it, and segment index along the fibre (for exclusions).
    strand: u32,
    fiber: u32,
    seg: u32,
}

/// Segments a ray ignores: of one strand (one fibre of it, or all), within a segment range.
#[derive(Clone, Copy)]
struct Exclude {
    strand: u32,
    fiber: Option<u32>,
    segs: (i64, i64),
}

/// The fibres of a hair state, binned across the light, ready for queries.
pub struct ExactReference<'a> {
    /// World -> map coordinates: the light frame, and for a point light the central
    /// projection that makes its rays parallel (see "Point lights" in the module doc).
    proj: Projection,
    fiber: &'a Fiber,
    radius_m: f32,
    points_per_strand: usize,
    fibers_per_strand: usize,
    /// Light-frame points of every placed fibre: fibre f of strand s, point k at
    /// [(s·F + f)·P + k].
    fiber_points: Vec<Vec3>,
    /// Share of each strand's fibres present at each point (empty: all).
    fiber_share: Vec<f32>,
    segments: Vec<Segment>,
    /// Bin grid across the light.
    origin: Vec2,
    inv_bin: f32,
    dims: [usize; 2],
    bin_start: Vec<u32>,
    bin_items: Vec<u32>,
}

impl<'a> ExactReference<'a> {
    /// Places the fibres and bins them. `bin_m` is the bin size across the light (smaller bins
    /// mean fewer segments per ray and more bins per segment; about the strand spacing works
    /// well). Non-finite points make their strand's fibres vanish.
    pub fn build(input: &ExactInput<'a>, bin_m: f32) -> Self {
        // A point light's projection puts its reference plane at the nearest hair, so no fibre
        // is magnified across the light (the bins' padding by r then holds).
        let proj = input.light.projection(input.positions);
        let ppl = input.points_per_strand.max(1);
        let strands = input.positions.len() / ppl;
        let f_count = input.fibers_per_strand.max(1) as usize;
        let r = input.fiber.params().radius_m;
        let fiber_points: Vec<Vec3> = (0..strands)
            .into_par_iter()
            .flat_map_iter(|s| {
                place_fibers(&input.positions[s * ppl..(s + 1) * ppl], s, input, &proj)
            })
            .collect();
        let segments = fiber_segments(input, &proj, &fiber_points, strands * f_count);
        let grid = BinGrid::over(&segments, r, bin_m);
        // Each bin sorted by the segments' nearest depth to the light, so a ray stops at the
        // first segment that lies wholly behind its start.
        let (bin_start, bin_items) = list_by_depth(
            grid.dims,
            segments.len(),
            |i| {
                let ((x0, x1), (y0, y1)) = grid.bins_of(&segments[i], r);
                Some(([x0, y0], [x1, y1]))
            },
            |i| {
                let s = &segments[i as usize];
                s.x_a.min(s.x_a + s.dx)
            },
        );
        Self {
            proj,
            fiber: input.fiber,
            radius_m: r,
            points_per_strand: ppl,
            fibers_per_strand: f_count,
            fiber_points,
            fiber_share: input.fiber_share.to_vec(),
            segments,
            origin: grid.origin,
            inv_bin: grid.inv_bin,
            dims: grid.dims,
            bin_start,
            bin_items,
        }
    }

    /// Fibre segments placed (all strands, all fibres).
    pub fn segment_count(&self) -> usize {
        self.segments.len()
    }

    /// Whether fibre `f` of the strand reaches point `vertex` (fibres end one by one where the
    /// strand's fibre share falls: fibre f ends below (f + ½)/F).
    #[inline]
    fn fiber_present(&self, vertex: usize, f: usize) -> bool {
        let threshold = (f as f32 + 0.5) / self.fibers_per_strand as f32;
        self.fiber_share
            .get(vertex)
            .is_none_or(|sh| *sh >= threshold)
    }
}
