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
//! ## Fibre placement (documented, deterministic)
//! Fibre f of a render strand follows the strand's polyline offset by a fixed vector in the
//! strand's normal plane. The normal frame starts from any unit vector perpendicular to the
//! first segment and is carried along the strand by projection (discrete parallel transport,
//! as `interp` carries curls), so a bundle keeps its shape along the strand. The F offsets are
//! a Vogel (golden-angle) spiral filling the disc of radius `bundle_radius_m` evenly, turned
//! by a per-strand angle from a hash of the strand index (and `placement_seed`, 0 unless a
//! measurement asks for another placement of the same bundles). With F = 1 the only fibre is the
//! strand itself (offset 0): the geometry is then exact, not a model.
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

use super::{MapLight, Projection};
use crate::fiber::{Fiber, LightAtPoint};
use glam::{Vec2, Vec3};
use rayon::prelude::*;

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
    pub fibre_share: &'a [f32],
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
    Fibres {
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
    fibre: u32,
    seg: u32,
}

/// Segments a ray ignores: of one strand (one fibre of it, or all), within a segment range.
#[derive(Clone, Copy)]
struct Exclude {
    strand: u32,
    fibre: Option<u32>,
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
    fibres_per_strand: usize,
    /// Light-frame points of every placed fibre: fibre f of strand s, point k at
    /// [(s·F + f)·P + k].
    fibre_points: Vec<Vec3>,
    /// Share of each strand's fibres present at each point (empty: all).
    fibre_share: Vec<f32>,
    segments: Vec<Segment>,
    /// Bin grid across the light.
    origin: Vec2,
    inv_bin: f32,
    dims: [usize; 2],
    bin_start: Vec<u32>,
    bin_items: Vec<u32>,
}

/// Golden angle, radians.
const GOLDEN_ANGLE: f32 = 2.399_963_2;

/// Point `i` of `count` of a Vogel spiral filling the unit disc evenly.
#[inline]
fn vogel(i: u32, count: u32) -> Vec2 {
    let rho = ((i as f32 + 0.5) / count as f32).sqrt();
    let (s, c) = (i as f32 * GOLDEN_ANGLE).sin_cos();
    Vec2::new(c, s) * rho
}

/// A per-strand angle in [0, 2π) from a hash of its index and the placement seed (SplitMix64
/// finaliser).
fn strand_angle(s: usize, seed: u64) -> f32 {
    let mut z = (s as u64)
        .wrapping_add(seed.wrapping_mul(0xD1B5_4A32_D192_ED03))
        .wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 40) as f32 / (1u64 << 24) as f32 * std::f32::consts::TAU
}

/// The points of the F fibres of one render strand (light frame), fibre after fibre; NaN
/// points when the strand has a non-finite point.
fn place_fibres(pts: &[Vec3], s: usize, input: &ExactInput, proj: &Projection) -> Vec<Vec3> {
    let f_count = input.fibers_per_strand.max(1) as usize;
    let ppl = pts.len();
    if pts.iter().any(|p| !p.is_finite()) {
        return vec![Vec3::NAN; ppl * f_count];
    }
    let (sn, cs) = strand_angle(s, input.placement_seed).sin_cos();
    let offsets = (0..f_count as u32).map(|f| {
        if f_count == 1 {
            Vec2::ZERO
        } else {
            let v = vogel(f, f_count as u32);
            Vec2::new(cs * v.x - sn * v.y, sn * v.x + cs * v.y) * input.bundle_radius_m
        }
    });
    // Normal frame per point, carried along the strand by projection.
    let tangent =
        |k: usize| (pts[(k + 1).min(ppl - 1)] - pts[k.saturating_sub(1)]).normalize_or(Vec3::Y);
    let mut n1 = tangent(0).any_orthonormal_vector();
    let frames: Vec<(Vec3, Vec3)> = (0..ppl)
        .map(|k| {
            let t = tangent(k);
            n1 = (n1 - t * n1.dot(t)).normalize_or(t.any_orthonormal_vector());
            (n1, t.cross(n1))
        })
        .collect();
    offsets
        .flat_map(|off| {
            frames
                .iter()
                .zip(pts)
                .map(move |((n1, n2), p)| proj.point(*p + *n1 * off.x + *n2 * off.y))
        })
        .collect()
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
        let fibre_points: Vec<Vec3> = (0..strands)
            .into_par_iter()
            .flat_map_iter(|s| {
                place_fibres(&input.positions[s * ppl..(s + 1) * ppl], s, input, &proj)
            })
            .collect();
        let segments: Vec<Segment> = (0..strands * f_count)
            .into_par_iter()
            .flat_map_iter(|fi| {
                let pts = &fibre_points[fi * ppl..(fi + 1) * ppl];
                let finite = pts.iter().all(|p| p.is_finite());
                let (strand, f) = (fi / f_count, fi % f_count);
                let threshold = (f as f32 + 0.5) / f_count as f32;
                let share = input.fibre_share;
                // Segment k holds the fibres whose threshold is under the mean share of its two
                // ends: the expected count is then F × that mean, as the map fills (each point
                // carries its share over half of each adjacent segment).
                let present = move |k: usize| {
                    let at = |i: usize| share.get(strand * ppl + i).copied().unwrap_or(1.0);
                    0.5 * (at(k) + at(k + 1)) >= threshold
                };
                pts.windows(2)
                    .enumerate()
                    .filter(move |(k, _)| finite && present(*k))
                    .filter_map(move |(k, w)| {
                        let (a, b) = (w[0], w[1]);
                        let d = Vec2::new(b.y - a.y, b.z - a.z);
                        let len2 = d.length_squared();
                        // θ from the fibre's real direction and the real ray toward the light.
                        let (u, to_light) = match proj {
                            Projection::Parallel { frame } => {
                                (frame.to_world(b - a).normalize_or_zero(), -frame.x)
                            }
                            Projection::Central { .. } => {
                                let (wa, wb) = (proj.to_world(a), proj.to_world(b));
                                (
                                    (wb - wa).normalize_or_zero(),
                                    proj.toward_light(0.5 * (wa + wb)),
                                )
                            }
                        };
                        (len2 > 1e-18).then(|| Segment {
                            a: Vec2::new(a.y, a.z),
                            d,
                            inv_len2: 1.0 / len2,
                            x_a: a.x,
                            dx: b.x - a.x,
                            sin_theta: u.dot(to_light).clamp(-1.0, 1.0),
                            strand: (fi / f_count) as u32,
                            fibre: (fi % f_count) as u32,
                            seg: k as u32,
                        })
                    })
            })
            .collect();

        // Bin grid over the segments' widened projections. A hostile extent would make the
        // grid huge: the reference is a measuring tool, so it caps its grid at 4096 bins a side
        // (larger scenes get coarser bins).
        const MAX_BINS: f32 = 4096.0;
        let (mut lo, mut hi) = (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN));
        for s in &segments {
            lo = lo.min(s.a.min(s.a + s.d));
            hi = hi.max(s.a.max(s.a + s.d));
        }
        let (origin, inv_bin, dims) = if segments.is_empty() {
            (Vec2::ZERO, 1.0, [1usize, 1usize])
        } else {
            let pad = Vec2::splat(r + bin_m.max(1e-6));
            let origin = lo - pad;
            let extent = hi + pad - origin;
            let bin = bin_m.max(1e-6).max(extent.max_element() / MAX_BINS);
            let dims = (extent / bin).ceil().max(Vec2::ONE);
            (origin, 1.0 / bin, [dims.x as usize, dims.y as usize])
        };
        let bin_range = |s: &Segment| {
            let (a, b) = (s.a, s.a + s.d);
            let l = ((a.min(b) - Vec2::splat(r) - origin) * inv_bin).floor();
            let h = ((a.max(b) + Vec2::splat(r) - origin) * inv_bin).floor();
            (
                (l.x.max(0.0) as usize, (h.x as usize).min(dims[0] - 1)),
                (l.y.max(0.0) as usize, (h.y as usize).min(dims[1] - 1)),
            )
        };
        let mut bin_start = vec![0u32; dims[0] * dims[1] + 1];
        for s in &segments {
            let ((x0, x1), (y0, y1)) = bin_range(s);
            for bx in x0..=x1 {
                for by in y0..=y1 {
                    bin_start[bx * dims[1] + by + 1] += 1;
                }
            }
        }
        for i in 1..bin_start.len() {
            bin_start[i] += bin_start[i - 1];
        }
        let mut cursor = bin_start.clone();
        let mut bin_items = vec![0u32; *bin_start.last().unwrap_or(&0) as usize];
        for (i, s) in segments.iter().enumerate() {
            let ((x0, x1), (y0, y1)) = bin_range(s);
            for bx in x0..=x1 {
                for by in y0..=y1 {
                    let c = &mut cursor[bx * dims[1] + by];
                    bin_items[*c as usize] = i as u32;
                    *c += 1;
                }
            }
        }
        // Each bin sorted by the segments' nearest depth to the light, so a ray stops at the
        // first segment that lies wholly behind its start.
        let x_min = |i: u32| {
            let s = &segments[i as usize];
            s.x_a.min(s.x_a + s.dx)
        };
        let mut slices = Vec::with_capacity(bin_start.len().saturating_sub(1));
        let mut rest: &mut [u32] = &mut bin_items;
        for w in bin_start.windows(2) {
            let (a, b) = std::mem::take(&mut rest).split_at_mut((w[1] - w[0]) as usize);
            slices.push(a);
            rest = b;
        }
        slices.into_par_iter().for_each(|bin| {
            bin.sort_unstable_by(|a, b| x_min(*a).total_cmp(&x_min(*b)).then(a.cmp(b)))
        });
        Self {
            proj,
            fiber: input.fiber,
            radius_m: r,
            points_per_strand: ppl,
            fibres_per_strand: f_count,
            fibre_points,
            fibre_share: input.fibre_share.to_vec(),
            segments,
            origin,
            inv_bin,
            dims,
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
    fn fibre_present(&self, vertex: usize, f: usize) -> bool {
        let threshold = (f as f32 + 0.5) / self.fibres_per_strand as f32;
        self.fibre_share
            .get(vertex)
            .is_none_or(|sh| *sh >= threshold)
    }

    /// The light reaching render-strand point `vertex` (index into the positions it was built
    /// from), averaged over the footprint.
    pub fn light_at_vertex(&self, vertex: usize, fp: &Footprint) -> LightAtPoint {
        let ppl = self.points_per_strand;
        let (strand, k) = (vertex / ppl, vertex % ppl);
        if strand * self.fibres_per_strand * ppl >= self.fibre_points.len() {
            return LightAtPoint::UNSHADOWED;
        }
        let mut acc = RayAverage::default();
        match *fp {
            Footprint::Disc {
                radius_m,
                rays,
                exclude_segments,
            } => {
                // The strand's axis point (fibre 0 at F = 1; the bundle centre otherwise).
                let base = strand * self.fibres_per_strand * ppl;
                let centre = if self.fibres_per_strand == 1 {
                    self.fibre_points[base + k]
                } else {
                    (0..self.fibres_per_strand)
                        .map(|f| self.fibre_points[base + f * ppl + k])
                        .sum::<Vec3>()
                        / self.fibres_per_strand as f32
                };
                let excl = exclude_segments as i64;
                // Segments k−excl .. k+excl−1 touch the points within `excl` segments of k.
                let own = Exclude {
                    strand: strand as u32,
                    fibre: None,
                    segs: (k as i64 - excl, k as i64 + excl - 1),
                };
                let rays = rays.max(1);
                for i in 0..rays {
                    let v = vogel(i, rays) * radius_m;
                    acc.add(self.trace(centre + Vec3::new(0.0, v.x, v.y), Some(own)));
                }
            }
            Footprint::Fibres { rays } => {
                self.for_each_fibre_origin(vertex, rays, |o, own| {
                    acc.add(self.trace(o, Some(own)));
                });
            }
            Footprint::Ball { radius_m, rays } => {
                let centre = self.fibre_points[strand * self.fibres_per_strand * ppl + k];
                self.trace_ball(centre, radius_m, rays.max(1), &mut acc);
            }
        }
        acc.finish()
    }

    /// Rays from points spread evenly by length over the fibre pieces inside the ball of
    /// `radius` around light-frame point `centre`.
    fn trace_ball(&self, centre: Vec3, radius: f32, rays: u32, acc: &mut RayAverage) {
        // Candidate segments: those binned within the ball's lateral square (bins are at least
        // as wide as r, so a segment crossing the ball is in one of them), deduplicated by
        // keeping a segment only in the first bin of the square it was listed in.
        let lo = ((Vec2::new(centre.y, centre.z) - Vec2::splat(radius) - self.origin)
            * self.inv_bin)
            .floor()
            .max(Vec2::ZERO);
        let hi = ((Vec2::new(centre.y, centre.z) + Vec2::splat(radius) - self.origin)
            * self.inv_bin)
            .floor();
        if !(lo.is_finite() && hi.is_finite()) || hi.x < 0.0 || hi.y < 0.0 {
            return;
        }
        let (x0, y0) = (lo.x as usize, lo.y as usize);
        let (x1, y1) = (
            (hi.x as usize).min(self.dims[0] - 1),
            (hi.y as usize).min(self.dims[1] - 1),
        );
        let mut candidates: Vec<u32> = Vec::new();
        for bx in x0..=x1 {
            for by in y0..=y1 {
                let c = bx * self.dims[1] + by;
                candidates.extend_from_slice(
                    &self.bin_items[self.bin_start[c] as usize..self.bin_start[c + 1] as usize],
                );
            }
        }
        candidates.sort_unstable();
        candidates.dedup();
        let mut pieces: Vec<(usize, f32, f32)> = Vec::new(); // (segment, t0, t1) inside the ball
        {
            {
                for &idx in &candidates {
                    let s = &self.segments[idx as usize];
                    let a = Vec3::new(s.x_a, s.a.x, s.a.y);
                    let d = Vec3::new(s.dx, s.d.x, s.d.y);
                    // |a + t d − c|² = R²: t = (−b ± √(b² − |d|²(|a − c|² − R²)))/|d|².
                    let ac = a - centre;
                    let dd = d.length_squared();
                    let b = ac.dot(d);
                    let disc = b * b - dd * (ac.length_squared() - radius * radius);
                    if disc <= 0.0 || dd <= 0.0 {
                        continue;
                    }
                    let sq = disc.sqrt();
                    let (t0, t1) = (((-b - sq) / dd).max(0.0), ((-b + sq) / dd).min(1.0));
                    if t1 > t0 {
                        pieces.push((idx as usize, t0, t1));
                    }
                }
            }
        }
        let lengths: Vec<f32> = pieces
            .iter()
            .map(|&(i, t0, t1)| {
                let s = &self.segments[i];
                (t1 - t0) * Vec3::new(s.dx, s.d.x, s.d.y).length()
            })
            .collect();
        let total: f32 = lengths.iter().sum();
        if total.is_nan() || total <= 0.0 {
            return;
        }
        // Stratified by arc length over the concatenated pieces.
        let (mut piece, mut before) = (0usize, 0.0f32);
        for i in 0..rays {
            let at = (i as f32 + 0.5) / rays as f32 * total;
            while piece + 1 < pieces.len() && before + lengths[piece] < at {
                before += lengths[piece];
                piece += 1;
            }
            let (idx, t0, t1) = pieces[piece];
            let s = &self.segments[idx];
            let t = t0 + (t1 - t0) * ((at - before) / lengths[piece].max(1e-30)).clamp(0.0, 1.0);
            let o = Vec3::new(s.x_a + t * s.dx, s.a.x + t * s.d.x, s.a.y + t * s.d.y);
            let own = Exclude {
                strand: s.strand,
                fibre: Some(s.fibre),
                segs: (s.seg as i64 - 2, s.seg as i64 + 2),
            };
            acc.add(self.trace(o, Some(own)));
        }
    }

    /// For the fibres render-strand point `vertex` stands for (as [`Footprint::Fibres`]): the
    /// share of ray origins the camera sees, and the share both seen and lit by direct light.
    /// `view` must hold the same fibres with its "light" travelling from the camera into the
    /// scene (built from the same input with `light_dir` = the view direction): a ray from an
    /// origin toward its light is then the ray toward the eye. Their ratio is the direct
    /// fraction *given* that the fibre is seen, which a picture shows; it measures the
    /// opposition effect the map models in `LightMap::light_at_seen`.
    pub fn seen_and_lit(&self, view: &ExactReference, vertex: usize, rays: u32) -> (f32, f32) {
        let ppl = self.points_per_strand;
        let strand = vertex / ppl;
        if (strand + 1) * self.fibres_per_strand * ppl > self.fibre_points.len() {
            return (0.0, 0.0);
        }
        let (mut n, mut seen, mut both) = (0u32, 0u32, 0u32);
        self.for_each_fibre_origin(vertex, rays, |o, own| {
            let o_view = view.proj.point(self.proj.to_world(o));
            let is_seen = view.trace(o_view, Some(own)).0 == 0;
            let is_lit = self.trace(o, Some(own)).0 == 0;
            n += 1;
            seen += is_seen as u32;
            both += (is_seen && is_lit) as u32;
        });
        let inv = 1.0 / n.max(1) as f32;
        (seen as f32 * inv, both as f32 * inv)
    }

    /// The ray origins of [`Footprint::Fibres`] for render-strand point `vertex`: `rays` spread
    /// over the fibres present there, stratified along the piece of fibre the point stands for
    /// (parameter in (−½, ½) segments around it), each with the fibre's own nearby segments
    /// excluded. Origins are in the map frame.
    fn for_each_fibre_origin(
        &self,
        vertex: usize,
        rays: u32,
        mut visit: impl FnMut(Vec3, Exclude),
    ) {
        let ppl = self.points_per_strand;
        let (strand, k) = (vertex / ppl, vertex % ppl);
        let f_count = self.fibres_per_strand;
        let present = (0..f_count)
            .filter(|&f| self.fibre_present(vertex, f))
            .count();
        let per_fibre = (rays.max(1) as usize).div_ceil(present.max(1));
        for f in (0..f_count).filter(|&f| self.fibre_present(vertex, f)) {
            let base = (strand * f_count + f) * ppl;
            let pts = &self.fibre_points[base..base + ppl];
            let own = Exclude {
                strand: strand as u32,
                fibre: Some(f as u32),
                segs: (k as i64 - 2, k as i64 + 1),
            };
            for j in 0..per_fibre {
                let t = (j as f32 + 0.5) / per_fibre as f32 - 0.5;
                let o = if t < 0.0 && k > 0 {
                    pts[k].lerp(pts[k - 1], -t)
                } else if t >= 0.0 && k + 1 < ppl {
                    pts[k].lerp(pts[k + 1], t)
                } else {
                    pts[k]
                };
                visit(o, own);
            }
        }
    }

    /// The light reaching world point `p` over a disc across the light of `radius_m` with
    /// `rays` rays, excluding nothing.
    pub fn light_at_point(&self, p: Vec3, radius_m: f32, rays: u32) -> LightAtPoint {
        let m = self.proj.point(p);
        let rays = rays.max(1);
        let mut acc = RayAverage::default();
        for i in 0..rays {
            let v = vogel(i, rays) * radius_m;
            acc.add(self.trace(m + Vec3::new(0.0, v.x, v.y), None));
        }
        acc.finish()
    }

    /// [`Self::light_at_vertex`] for many vertices, in parallel (order of `vertices`).
    pub fn light_at_vertices(&self, vertices: &[usize], fp: &Footprint) -> Vec<LightAtPoint> {
        vertices
            .par_iter()
            .with_min_len(16)
            .map(|&v| self.light_at_vertex(v, fp))
            .collect()
    }

    /// One ray from light-frame point `o` toward the light: (crossings, ∏ ā_f, Σ β̄_f²).
    fn trace(&self, o: Vec3, own: Option<Exclude>) -> (u32, Vec3, Vec3) {
        let (mut t_ray, mut v_ray, mut hits) = (Vec3::ONE, Vec3::ZERO, 0u32);
        let oyz = Vec2::new(o.y, o.z);
        let b = ((oyz - self.origin) * self.inv_bin).floor();
        // `!(a >= b)` also rejects NaN.
        if !(b.x >= 0.0 && b.y >= 0.0 && o.x.is_finite()) {
            return (0, t_ray, v_ray);
        }
        let (bx, by) = (b.x as usize, b.y as usize);
        if bx >= self.dims[0] || by >= self.dims[1] {
            return (0, t_ray, v_ray);
        }
        let r2 = self.radius_m * self.radius_m;
        let c = bx * self.dims[1] + by;
        let items = &self.bin_items[self.bin_start[c] as usize..self.bin_start[c + 1] as usize];
        for &idx in items {
            let s = &self.segments[idx as usize];
            if s.x_a.min(s.x_a + s.dx) >= o.x {
                break; // this and every later segment of the bin lie wholly behind the start
            }
            let rel = oyz - s.a;
            let t = rel.dot(s.d) * s.inv_len2;
            if !(0.0..1.0).contains(&t) {
                continue;
            }
            let perp = rel - s.d * t;
            let x = s.x_a + t * s.dx;
            // A point light's projection narrows a fibre across the light as it shrinks
            // everything at that depth (`Projection::Central`).
            let r2 = match self.proj {
                Projection::Parallel { .. } => r2,
                Projection::Central { ref_depth_m, .. } => r2 * (ref_depth_m / x).powi(2),
            };
            if perp.length_squared() >= r2 || x >= o.x {
                continue;
            }
            if let Some(e) = own
                && s.strand == e.strand
                && e.fibre.is_none_or(|f| f == s.fibre)
                && (e.segs.0..=e.segs.1).contains(&(s.seg as i64))
            {
                continue;
            }
            let f = self.fiber.forward_scatter(s.sin_theta);
            t_ray *= f.a_f.clamp(Vec3::ZERO, Vec3::ONE);
            v_ray += f.beta_f2;
            hits += 1;
        }
        (hits, t_ray, v_ray)
    }
}

/// Running average over rays.
#[derive(Default)]
struct RayAverage {
    rays: u32,
    direct: u32,
    tf: Vec3,
    var: Vec3,
}

impl RayAverage {
    fn add(&mut self, (hits, tf, var): (u32, Vec3, Vec3)) {
        self.rays += 1;
        self.direct += (hits == 0) as u32;
        self.tf += tf;
        self.var += var;
    }

    fn finish(&self) -> LightAtPoint {
        if self.rays == 0 {
            return LightAtPoint::UNSHADOWED;
        }
        let inv = 1.0 / self.rays as f32;
        LightAtPoint {
            direct_fraction: self.direct as f32 * inv,
            tf: self.tf * inv,
            sigma_f2: self.var * inv,
            crossings_behind: LightAtPoint::DENSE,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Vogel spiral fills the unit disc evenly: the share of points within radius ρ is ρ².
    #[test]
    fn vogel_spiral_is_area_uniform() {
        let n = 4096;
        for rho in [0.25f32, 0.5, 0.9] {
            let inside = (0..n).filter(|&i| vogel(i, n).length() < rho).count();
            let share = inside as f32 / n as f32;
            assert!(
                (share - rho * rho).abs() < 2.0 / n as f32 + 1e-3,
                "{rho}: {share}"
            );
        }
    }
}
