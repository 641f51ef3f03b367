//! Queries of the exact reference: rays from a footprint toward the light, each one's
//! crossings with the binned fibres (module doc of `exact`: "A ray and its crossings",
//! "Footprint and exclusion").

use super::{ExactReference, Exclude, Footprint, Projection};
use crate::fiber::LightAtPoint;
use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::disc::vogel;

impl ExactReference<'_> {
    /// The light reaching render-strand point `vertex` (index into the positions it was built
    /// from), averaged over the footprint.
    pub fn light_at_vertex(&self, vertex: usize, fp: &Footprint) -> LightAtPoint {
        let ppl = self.points_per_strand;
        let (strand, k) = (vertex / ppl, vertex % ppl);
        if strand * self.fibers_per_strand * ppl >= self.fiber_points.len() {
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
                let base = strand * self.fibers_per_strand * ppl;
                let centre = if self.fibers_per_strand == 1 {
                    self.fiber_points[base + k]
                } else {
                    (0..self.fibers_per_strand)
                        .map(|f| self.fiber_points[base + f * ppl + k])
                        .sum::<Vec3>()
                        / self.fibers_per_strand as f32
                };
                let excl = exclude_segments as i64;
                // Segments k−excl .. k+excl−1 touch the points within `excl` segments of k.
                let own = Exclude {
                    strand: strand as u32,
                    fiber: None,
                    segs: (k as i64 - excl, k as i64 + excl - 1),
                };
                let rays = rays.max(1);
                for i in 0..rays {
                    let v = vogel(i, rays) * radius_m;
                    acc.add(self.trace(centre + Vec3::new(0.0, v.x, v.y), Some(own)));
                }
            }
            Footprint::Fibers { rays } => {
                self.for_each_fiber_origin(vertex, rays, false, |o, own| {
                    acc.add(self.trace(o, Some(own)));
                });
            }
            Footprint::FibersLitSide { rays } => {
                self.for_each_fiber_origin(vertex, rays, true, |o, own| {
                    acc.add(self.trace(o, Some(own)));
                });
            }
            Footprint::Ball { radius_m, rays } => {
                let centre = self.fiber_points[strand * self.fibers_per_strand * ppl + k];
                self.trace_ball(centre, radius_m, rays.max(1), &mut acc);
            }
        }
        acc.finish()
    }

    /// Rays from points spread evenly by length over the fibre pieces inside the ball of
    /// `radius` around light-frame point `centre`.
    fn trace_ball(&self, centre: Vec3, radius: f32, rays: u32, acc: &mut RayAverage) {
        let candidates = self.ball_candidates(centre, radius);
        let pieces = self.pieces_in_ball(&candidates, centre, radius);
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
                fiber: Some(s.fiber),
                segs: (s.seg as i64 - 2, s.seg as i64 + 2),
            };
            acc.add(self.trace(o, Some(own)));
        }
    }

    /// The segments that may cross the ball of `radius` around `centre`: those binned within
    /// the ball's lateral square (bins are at least as wide as r, so a segment crossing the
    /// ball is in one of them), each once, in index order.
    fn ball_candidates(&self, centre: Vec3, radius: f32) -> Vec<u32> {
        let yz = Vec2::new(centre.y, centre.z);
        let lo = ((yz - Vec2::splat(radius) - self.origin) * self.inv_bin)
            .floor()
            .max(Vec2::ZERO);
        let hi = ((yz + Vec2::splat(radius) - self.origin) * self.inv_bin).floor();
        if !(lo.is_finite() && hi.is_finite()) || hi.x < 0.0 || hi.y < 0.0 {
            return Vec::new();
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
        candidates
    }

    /// The parts of the `candidates` segments inside the ball of `radius` around `centre`:
    /// (segment, t0, t1), from |a + t·d − c|² = R², t = (−b ± √(b² − |d|²(|a − c|² − R²)))/|d|²
    /// clipped to [0, 1].
    fn pieces_in_ball(
        &self,
        candidates: &[u32],
        centre: Vec3,
        radius: f32,
    ) -> Vec<(usize, f32, f32)> {
        let mut pieces = Vec::new();
        for &idx in candidates {
            let s = &self.segments[idx as usize];
            let a = Vec3::new(s.x_a, s.a.x, s.a.y);
            let d = Vec3::new(s.dx, s.d.x, s.d.y);
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
        pieces
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
        if (strand + 1) * self.fibers_per_strand * ppl > self.fiber_points.len() {
            return (0.0, 0.0);
        }
        let (mut n, mut seen, mut both) = (0u32, 0u32, 0u32);
        self.for_each_fiber_origin(vertex, rays, false, |o, own| {
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
    /// excluded. Origins are in the map frame: on the fibre's axis, or with `lit_side` on its
    /// lit side ([`Projection::lit_side`]; at the point itself the tangent is the chord between
    /// its neighbours, as contact shadows take it, elsewhere the segment holding the origin).
    fn for_each_fiber_origin(
        &self,
        vertex: usize,
        rays: u32,
        lit_side: bool,
        mut visit: impl FnMut(Vec3, Exclude),
    ) {
        let ppl = self.points_per_strand;
        let (strand, k) = (vertex / ppl, vertex % ppl);
        let f_count = self.fibers_per_strand;
        let present = (0..f_count)
            .filter(|&f| self.fiber_present(vertex, f))
            .count();
        let per_fiber = (rays.max(1) as usize).div_ceil(present.max(1));
        for f in (0..f_count).filter(|&f| self.fiber_present(vertex, f)) {
            let base = (strand * f_count + f) * ppl;
            let pts = &self.fiber_points[base..base + ppl];
            let own = Exclude {
                strand: strand as u32,
                fiber: Some(f as u32),
                segs: (k as i64 - 2, k as i64 + 1),
            };
            for j in 0..per_fiber {
                let t = (j as f32 + 0.5) / per_fiber as f32 - 0.5;
                let (o, chord) = if t < 0.0 && k > 0 {
                    (pts[k].lerp(pts[k - 1], -t), (pts[k - 1], pts[k]))
                } else if t > 0.0 && k + 1 < ppl {
                    (pts[k].lerp(pts[k + 1], t), (pts[k], pts[k + 1]))
                } else {
                    (
                        pts[k],
                        (pts[k.saturating_sub(1)], pts[(k + 1).min(ppl - 1)]),
                    )
                };
                let o = if lit_side {
                    self.proj.lit_side(o, chord.0, chord.1, self.radius_m)
                } else {
                    o
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
                && e.fiber.is_none_or(|f| f == s.fiber)
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
