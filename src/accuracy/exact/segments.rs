//! The placed fibres as straight segments in the light frame, and the bin grid across the
//! light that lists them (module doc of `exact`: "A ray and its crossings", "Cost").
//!
//! A segment AB keeps what a ray's crossing test needs: a and b − a across the light (with
//! 1/|b − a|², so the crossing parameter is t = (o − a)·(b − a)/|b − a|²), the depth x_A and its
//! change, and sin θ of the light on the fibre for its ā_f(θ) and β̄_f²(θ).

use super::{ExactInput, Segment};
use crate::map::Projection;
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// The segments of the `fibers` placed fibres (their light-frame points `fiber_points`, fibre
/// after fibre): where fibre f of F is present (the strand's fibre share, mean of the
/// segment's ends, at least (f + ½)/F) and not along the light, in fibre and segment order.
pub(super) fn fiber_segments(
    input: &ExactInput,
    proj: &Projection,
    fiber_points: &[Vec3],
    fibers: usize,
) -> Vec<Segment> {
    let ppl = input.points_per_strand.max(1);
    let f_count = input.fibers_per_strand.max(1) as usize;
    (0..fibers)
        .into_par_iter()
        .flat_map_iter(|fi| {
            let pts = &fiber_points[fi * ppl..(fi + 1) * ppl];
            let finite = pts.iter().all(|p| p.is_finite());
            let (strand, f) = (fi / f_count, fi % f_count);
            let threshold = (f as f32 + 0.5) / f_count as f32;
            let share = input.fiber_share;
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
                .filter_map(move |(k, w)| segment(proj, w[0], w[1], (fi, f_count, k)))
        })
        .collect()
}

/// The segment from light-frame point `a` to `b` of fibre `fi` (of `f_count` a strand),
/// segment `k` along it, or `None` when it lies along the light (a projection shorter than
/// 1e-9 m).
fn segment(
    proj: &Projection,
    a: Vec3,
    b: Vec3,
    (fi, f_count, k): (usize, usize, usize),
) -> Option<Segment> {
    let d = Vec2::new(b.y - a.y, b.z - a.z);
    let len2 = d.length_squared();
    // θ from the fibre's real direction and the real ray toward the light.
    let (u, to_light) = match *proj {
        Projection::Parallel { frame } => (frame.to_world(b - a).normalize_or_zero(), -frame.x),
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
        fiber: (fi % f_count) as u32,
        seg: k as u32,
    })
}

/// The bin grid across the light over the segments' r-widened projections.
pub(super) struct BinGrid {
    pub(super) origin: Vec2,
    pub(super) inv_bin: f32,
    pub(super) dims: [usize; 2],
}

impl BinGrid {
    /// Bins of `bin_m` (at least 1 µm) over `segments` widened by `r` and a bin, capped at
    /// 4096 bins a side: the reference is a measuring tool, so a hostile extent gets coarser
    /// bins rather than a huge grid. One bin when there are no segments.
    pub(super) fn over(segments: &[Segment], r: f32, bin_m: f32) -> Self {
        const MAX_BINS: f32 = 4096.0;
        let (mut lo, mut hi) = (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN));
        for s in segments {
            lo = lo.min(s.a.min(s.a + s.d));
            hi = hi.max(s.a.max(s.a + s.d));
        }
        if segments.is_empty() {
            return BinGrid {
                origin: Vec2::ZERO,
                inv_bin: 1.0,
                dims: [1, 1],
            };
        }
        let pad = Vec2::splat(r + bin_m.max(1e-6));
        let origin = lo - pad;
        let extent = hi + pad - origin;
        let bin = bin_m.max(1e-6).max(extent.max_element() / MAX_BINS);
        let dims = (extent / bin).ceil().max(Vec2::ONE);
        BinGrid {
            origin,
            inv_bin: 1.0 / bin,
            dims: [dims.x as usize, dims.y as usize],
        }
    }

    /// The bins (rows x0..=x1, columns y0..=y1) that segment `s` widened by `r` touches.
    pub(super) fn bins_of(&self, s: &Segment, r: f32) -> ((usize, usize), (usize, usize)) {
        let (a, b) = (s.a, s.a + s.d);
        let l = ((a.min(b) - Vec2::splat(r) - self.origin) * self.inv_bin).floor();
        let h = ((a.max(b) + Vec2::splat(r) - self.origin) * self.inv_bin).floor();
        (
            (l.x.max(0.0) as usize, (h.x as usize).min(self.dims[0] - 1)),
            (l.y.max(0.0) as usize, (h.y as usize).min(self.dims[1] - 1)),
        )
    }
}
