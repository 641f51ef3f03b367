//! Reading the contact shadows: for one vertex, the fibres of its window that cross the ray
//! from its point toward the light (`crossing`), multiplied in depth order; module doc of
//! `contact`, "What a vertex receives".

use super::{ContactShadows, NearLight, OWN_AFTER, OWN_BEFORE, Segment};
use glam::{Vec2, Vec3};

impl ContactShadows {
    /// The light render-strand point `vertex` receives from the fibres within `window_m` in
    /// front of it (at most the window it was built with), on the fibre's lit side
    /// ([`super::Projection::lit_side`], the chord between the point's neighbours as its
    /// tangent). `shared_m` is the length over which the view ray shares fibres with the light
    /// ray (0: no camera), for the probability that a fibre is there given that the point is
    /// seen.
    pub fn near_light(&self, vertex: usize, window_m: f32, shared_m: f32) -> NearLight {
        let ppl = self.points_per_strand;
        let (strand, k) = (vertex / ppl, vertex % ppl);
        let Some(p) = self.points.get(strand * ppl + k).copied() else {
            return NearLight::CLEAR;
        };
        if !p.is_finite() {
            return NearLight::CLEAR;
        }
        let base = strand * ppl;
        let prev = self.points[base + k.saturating_sub(1)];
        let next = self.points[base + (k + 1).min(ppl - 1)];
        let p = self.proj.lit_side(p, prev, next, self.radius_m);
        let window_m = window_m.clamp(0.0, self.window_m);
        let shared_m = if shared_m.is_finite() {
            shared_m.max(0.0)
        } else {
            0.0
        };
        let pyz = Vec2::new(p.y, p.z);
        // A segment shadows the point only within r of its axis, so it is listed (padded by r)
        // in the one bin holding the point.
        let Some(([bx, by], _)) = self.bin_rect_padded(pyz, pyz, 0.0) else {
            return NearLight::CLEAR;
        };
        let c = bx * self.dims[1] + by;
        let items = &self.bin_items[self.bin_start[c] as usize..self.bin_start[c + 1] as usize];
        let (x_lo, x_hi) = (p.x - window_m, p.x);
        let central_ref_m = self.proj.central_ref_depth_m();
        // Parts whose nearest depth is below x_lo − max_dx lie wholly before the window.
        let first =
            items.partition_point(|&i| self.segments[i as usize].x_min() < x_lo - self.max_dx);
        let mut light = NearLight::CLEAR;
        let mut direct = 1.0f32;
        for &i in &items[first..] {
            let s = &self.segments[i as usize];
            if s.x_min() >= x_hi {
                break;
            }
            let Some(dist) = crossing(s, p, self.radius_m, central_ref_m, window_m) else {
                continue;
            };
            let fiber = &self.fibers[s.parent as usize];
            if fiber.strand == strand as u32
                && (k as i64 - OWN_BEFORE..=k as i64 + OWN_AFTER).contains(&(fiber.seg as i64))
            {
                continue;
            }
            // The view ray shares a fibre at distance s with the light ray over a share
            // 1 − s/s_c of its width (`LightMap::light_at_seen`): given the point is seen,
            // the fibre is there with probability min(1, s/s_c).
            let q = if shared_m > 0.0 {
                (dist / shared_m).clamp(0.0, 1.0)
            } else {
                1.0
            };
            // Present with probability q, independently: it lets 1 − q(1 − ā_f) through on
            // average and leaves the direct ray unblocked with probability 1 − q.
            light.tf *= Vec3::ONE - q * (Vec3::ONE - Vec3::from(fiber.a_f));
            direct *= 1.0 - q;
            light.sigma_f2 += q * Vec3::from(fiber.beta2);
            light.crossings += q;
        }
        light.direct_fraction = direct.clamp(0.0, 1.0);
        light.tf = light.tf.clamp(Vec3::ZERO, Vec3::ONE);
        light
    }
}

/// Whether segment `s` (radius `r`) crosses the ray from `p` toward the light within
/// `window_m` in front of it: its distance in front, metres, or `None`. The crossing is at
/// t ∈ [0, 1) along S (joints are shared half-open, as in the exact reference), within r of
/// the point across the light, strictly in front of it and at most the window ahead. A point
/// light's projection (`central_ref_m`) narrows the fibre as everything at the crossing's depth
/// x, by ref/x, as the exact reference does (never widened: the bins are padded by r, and no
/// hair lies nearer the light than ref).
#[inline]
fn crossing(
    s: &Segment,
    p: Vec3,
    r: f32,
    central_ref_m: Option<f32>,
    window_m: f32,
) -> Option<f32> {
    let rel = Vec2::new(p.y, p.z) - s.a;
    let t = rel.dot(s.d) * (s.inv_len * s.inv_len);
    let h = rel.perp_dot(s.d * s.inv_len);
    let x = s.x_a + s.dx * t;
    let r = match central_ref_m {
        None => r,
        Some(ref_m) => r * (ref_m / x).min(1.0),
    };
    // Depth of the crossing minus depth of the point.
    let e = x - p.x;
    let hit = (0.0..1.0).contains(&t) && h.abs() < r && e < 0.0 && -e <= window_m;
    hit.then_some(-e)
}
