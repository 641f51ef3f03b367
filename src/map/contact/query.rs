//! Reading the contact shadows: for one vertex, the covers its window's fibres cast on its
//! piece of fibre (`cover`) and the exact average of the light through them (`sweep`); module
//! doc of `contact`, "What a vertex receives".

use super::{
    ContactScratch, ContactShadows, Cover, NearLight, OWN_AFTER, OWN_BEFORE, Reach, Segment,
};
use glam::{Vec2, Vec3};

impl ContactShadows {
    /// The light render-strand point `vertex` receives from the fibres within the window in
    /// front of it, at its own point on the fibre's axis. `scratch` is
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
        let own = (strand as u32, k as i64);
        let reach = Reach {
            window_m: window_m.clamp(0.0, self.window_m),
            shared_m: if shared_m.is_finite() {
                shared_m.max(0.0)
            } else {
                0.0
            },
        };
        // The vertex's own point (module doc, "What a vertex receives"): a piece of zero length.
        self.part(p, p, own, reach, scratch)
    }

    /// The exact average light along the straight piece from `a` to `b` (light frame; within
    /// about a bin), visiting the bins it touches; a point when `a == b`.
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
