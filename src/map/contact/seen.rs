//! Contact shadows given that the camera sees the point: the light averaged over the parts of
//! the piece the camera sees, with the real fibres deciding which parts those are.
//!
//! With the light near the camera, a fibre just in front of a point either hides it from the
//! camera or shadows it, rarely both apart: the two rays share it. The map's reading
//! (`LightMap::light_at_seen`) and the axis sweep of the parent module count such a fibre with
//! the probability that it is there given that the point is seen, min(1, s/s_c). That is the
//! right expectation over fibres placed at random, but not given the real fibres: the
//! rasterizer composites a fibre by its coverage whatever lies in front of it, so a fibre
//! sitting right behind another is drawn (at the other's transparency) *and* read as lit,
//! while in truth the parts of it that the camera sees are only those the front fibre leaves
//! clear, and those are lit or not by the fibres further out. Measured on a slab of parallel
//! fibres lit from the camera's side (ACCURACY.md §2): single scattering 1.11 (2 crossings) to
//! 1.19 (8) of the path tracer with the axis sweep; a 2-D simulation of the same slab
//! (`tools/reference/`) gives +4 to +7% for the axis sweep and within 3% for this one.
//!
//! What this computes, for a piece of fibre and the direction toward the eye: at `OFFSETS`
//! points across the fibre's visible width (offsets h·r perpendicular to the fibre and the
//! view), along each part of the piece, the intervals of u over which a fibre of the window
//! covers the ray toward the light (as the axis sweep does) and those over which a fibre
//! covers the ray toward the eye (the same computation in a frame whose depth runs along the
//! view ray). The result is ∫ seen·light du / ∫ seen du summed over the offsets: light only
//! where the camera sees the fibre. Hiders are taken over the window along the view ray, or
//! over as much of it as stays within one bin of the light ray across the light (the whole
//! window while the eye is within a bin/window of the light's direction, 11° for 2 mm bins and
//! a 10 mm window); fibres beyond that hide the point without being near its light ray: they
//! hide lit and unlit parts alike, so leaving them out changes the average by noise, not bias.
//! When no part of the piece is seen (a fibre entirely behind nearer ones in the window), the
//! axis sweep's expectation stands.

use super::{ContactScratch, ContactShadows, Cover, NearLight, OWN_AFTER, OWN_BEFORE, cover};
use glam::{Vec2, Vec3};

/// Offsets across the fibre's visible width, in radii (midpoints of equal quarters).
const OFFSETS: [f32; 4] = [-0.75, -0.25, 0.25, 0.75];

/// The seen piece's light and how much of it is seen (weight summed over parts and offsets).
#[derive(Clone, Copy, Debug)]
struct SeenSum {
    light: NearLight,
    seen: f32,
}

impl ContactShadows {
    /// [`Self::near_light`] given that the camera sees the point: `to_eye` is the unit
    /// direction toward the eye in the light frame (a directional light's map; the axis sweep
    /// serves point lights). Falls back to [`Self::near_light`] where no part of the piece is
    /// seen, or the eye is not on the light's side (nothing can both hide and shadow).
    pub fn near_light_seen(
        &self,
        vertex: usize,
        window_m: f32,
        shared_m: f32,
        to_eye: Vec3,
        scratch: &mut ContactScratch,
    ) -> NearLight {
        // The light travels along +x: the eye is on the light's side when to_eye.x < 0.
        let usable = to_eye.is_finite() && to_eye.x < 0.0 && self.central_ref_m.is_none();
        if usable && let Some(l) = self.seen_piece(vertex, window_m, to_eye, scratch) {
            return l;
        }
        self.near_light(vertex, window_m, shared_m, scratch)
    }

    fn seen_piece(
        &self,
        vertex: usize,
        window_m: f32,
        to_eye: Vec3,
        scratch: &mut ContactScratch,
    ) -> Option<NearLight> {
        let ppl = self.points_per_strand;
        let (strand, k) = (vertex / ppl, vertex % ppl);
        let pts = self.points.get(strand * ppl..(strand + 1) * ppl)?;
        let p = pts[k];
        if !p.is_finite() {
            return None;
        }
        let before = if k > 0 { p.lerp(pts[k - 1], 0.5) } else { p };
        let after = if k + 1 < ppl {
            p.lerp(pts[k + 1], 0.5)
        } else {
            p
        };
        // The view frame: depth grows away from the eye, as the light frame's grows away from
        // the light, so "in front" is the same test in both.
        let v = to_eye.normalize_or_zero();
        let (vy, vz) = (-v).any_orthonormal_pair();
        let view = [-v, vy, vz];
        let own = (strand as u32, k as i64);
        let window = window_m.clamp(0.0, self.window_m);
        let mut total = SeenSum {
            light: NearLight::ZERO,
            seen: 0.0,
        };
        for (a, b) in [(p, before), (p, after)] {
            let n = self.parts(Vec2::new(b.y - a.y, b.z - a.z).length(), b.x - a.x);
            let inv = 1.0 / n as f32;
            for i in 0..n {
                let (from, to) = (a.lerp(b, i as f32 * inv), a.lerp(b, (i + 1) as f32 * inv));
                // The fibre's width as the camera sees it: across the part and the view.
                let across = (to - from).cross(v).normalize_or_zero();
                if across == Vec3::ZERO {
                    return None;
                }
                let s = self.part_seen(from, to, across, view, own, window, scratch);
                total.light.add_weighted(0.5 * inv, &s.light);
                total.seen += 0.5 * inv * s.seen;
            }
        }
        if total.seen <= 1e-6 {
            return None;
        }
        let mut out = NearLight::ZERO;
        out.add_weighted(1.0 / total.seen, &total.light);
        out.direct_fraction = out.direct_fraction.clamp(0.0, 1.0);
        out.tf = out.tf.clamp(Vec3::ZERO, Vec3::ONE);
        Some(out)
    }

    /// One part (a straight piece within about a bin) from `a` to `b`, light frame: the sums
    /// over the offsets of ∫ seen·light du and of ∫ seen du, each offset weighing 1/OFFSETS.
    #[allow(clippy::too_many_arguments)]
    fn part_seen(
        &self,
        a: Vec3,
        b: Vec3,
        across: Vec3,
        view: [Vec3; 3],
        own: (u32, i64),
        window_m: f32,
        scratch: &mut ContactScratch,
    ) -> SeenSum {
        let r = self.radius_m;
        let to_view = |p: Vec3| Vec3::new(p.dot(view[0]), p.dot(view[1]), p.dot(view[2]));
        let (ayz, byz) = (Vec2::new(a.y, a.z), Vec2::new(b.y, b.z));
        // Hiders are taken along the view ray while it stays within a bin of the light ray
        // across the light (the whole window when the eye is near the light).
        let v = -view[0];
        let lateral = Vec2::new(v.y, v.z);
        let view_window = window_m.min(1.0 / (self.inv_bin * lateral.length()).max(1e-30));
        let shift = lateral * view_window;
        let (lo, hi) = (
            ayz.min(byz).min(ayz.min(byz) + shift),
            ayz.max(byz).max(ayz.max(byz) + shift),
        );
        let lists = &mut scratch.offset_covers;
        lists.resize_with(OFFSETS.len(), Vec::new);
        lists.iter_mut().for_each(Vec::clear);
        let (av, bv) = (to_view(a), to_view(b));
        // Offsets reach r to either side of the axis; segments are listed padded by r.
        if let Some(([x0, y0], [x1, y1])) = self.bin_rect_padded(lo, hi, r) {
            let x_lo = a.x.min(b.x) - window_m - r;
            let x_hi = a.x.max(b.x) + r;
            let ny = self.dims[1];
            for bx in x0..=x1 {
                for by in y0..=y1 {
                    let c = bx * ny + by;
                    let items =
                        &self.bin_items[self.bin_start[c] as usize..self.bin_start[c + 1] as usize];
                    let first = items.partition_point(|&i| {
                        self.segments[i as usize].x_min() < x_lo - self.max_dx
                    });
                    for &i in &items[first..] {
                        let s = &self.segments[i as usize];
                        if s.x_min() >= x_hi {
                            break;
                        }
                        // Within 2r of the axis covers some offset's ray: most parts do not.
                        let near_light = cover(s, a, b, 2.0 * r, window_m).is_some();
                        let sv = view_segment(s, &to_view);
                        let near_view = sv
                            .as_ref()
                            .is_some_and(|sv| cover(sv, av, bv, 2.0 * r, view_window).is_some());
                        if !(near_light || near_view) {
                            continue;
                        }
                        if let Some(([sx0, sy0], _)) = self.seg_rect(s)
                            && (bx, by) != (sx0.max(x0), sy0.max(y0))
                        {
                            continue;
                        }
                        let fibre = &self.fibres[s.parent as usize];
                        if fibre.strand == own.0
                            && (own.1 - OWN_BEFORE..=own.1 + OWN_AFTER)
                                .contains(&(fibre.seg as i64))
                        {
                            continue;
                        }
                        for (list, h) in lists.iter_mut().zip(OFFSETS) {
                            let off = across * (h * r);
                            if near_light
                                && let Some((u0, u1, _)) = cover(s, a + off, b + off, r, window_m)
                            {
                                list.push(Cover {
                                    u0,
                                    u1,
                                    a_f: Vec3::from(fibre.a_f),
                                    beta2: Vec3::from(fibre.beta2),
                                    q: 1.0,
                                });
                            }
                            let off_v = to_view(off);
                            if let Some(sv) = &sv
                                && near_view
                                && let Some((u0, u1, _)) =
                                    cover(sv, av + off_v, bv + off_v, r, view_window)
                            {
                                // q < 0 marks a fibre that hides the point from the camera.
                                list.push(Cover {
                                    u0,
                                    u1,
                                    a_f: Vec3::ONE,
                                    beta2: Vec3::ZERO,
                                    q: -1.0,
                                });
                            }
                        }
                    }
                }
            }
        }
        let w = 1.0 / OFFSETS.len() as f32;
        let mut sum = SeenSum {
            light: NearLight::ZERO,
            seen: 0.0,
        };
        for list in scratch.offset_covers.iter() {
            let s = sweep_seen(list, &mut scratch.events);
            sum.light.add_weighted(w, &s.light);
            sum.seen += w * s.seen;
        }
        sum
    }
}

/// A part of a fibre segment in the view frame (`to_view` maps light-frame coordinates);
/// `None` for a part along the view (its shadow on the view ray is a disc, as the light
/// frame skips parts along the light).
#[inline]
fn view_segment(s: &super::Segment, to_view: &impl Fn(Vec3) -> Vec3) -> Option<super::Segment> {
    let a = to_view(Vec3::new(s.x_a, s.a.x, s.a.y));
    let b = to_view(Vec3::new(s.x_a + s.dx, s.a.x + s.d.x, s.a.y + s.d.y));
    let d = Vec2::new(b.y - a.y, b.z - a.z);
    let len2 = d.length_squared();
    if len2.is_nan() || len2 <= 1e-18 {
        return None;
    }
    Some(super::Segment {
        a: Vec2::new(a.y, a.z),
        d,
        inv_len: 1.0 / len2.sqrt(),
        x_a: a.x,
        dx: b.x - a.x,
        parent: s.parent,
    })
}

/// ∫ over u ∈ [0, 1] of the light through the shadowing covers where no hiding cover (q < 0)
/// is open, and the measure of those u: one pass over the intervals' ends, as
/// `super::sweep` does, with the spreads and crossing counts summed per interval.
fn sweep_seen(covers: &[Cover], events: &mut Vec<(f32, u32)>) -> SeenSum {
    events.clear();
    for (i, c) in covers.iter().enumerate() {
        events.push((c.u0, 2 * i as u32));
        events.push((c.u1, 2 * i as u32 + 1));
    }
    events.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut out = SeenSum {
        light: NearLight::ZERO,
        seen: 0.0,
    };
    // Open shadowing covers: log of their product per colour, how many, Σ β̄_f²; open hiders.
    let (mut log, mut zeros, mut count, mut beta2, mut hidden) =
        (Vec3::ZERO, [0i32; 3], 0i32, Vec3::ZERO, 0i32);
    let mut prev = 0.0f32;
    let mut credit = |w: f32, log: Vec3, zeros: [i32; 3], count: i32, beta2: Vec3| {
        let t = Vec3::new(
            if zeros[0] > 0 { 0.0 } else { log.x.exp() },
            if zeros[1] > 0 { 0.0 } else { log.y.exp() },
            if zeros[2] > 0 { 0.0 } else { log.z.exp() },
        );
        out.light.tf += w * t.min(Vec3::ONE);
        out.light.direct_fraction += if count == 0 { w } else { 0.0 };
        out.light.sigma_f2 += w * beta2;
        out.light.crossings += w * count as f32;
        out.seen += w;
    };
    for &(u, code) in events.iter() {
        let u = u.clamp(0.0, 1.0);
        if u > prev {
            if hidden == 0 {
                credit(u - prev, log, zeros, count, beta2);
            }
            prev = u;
        }
        let c = &covers[(code >> 1) as usize];
        let sign = if code & 1 == 0 { 1 } else { -1 };
        if c.q < 0.0 {
            hidden += sign;
            continue;
        }
        count += sign;
        beta2 += sign as f32 * c.beta2;
        for (k, a) in c.a_f.to_array().into_iter().enumerate() {
            if a > 0.0 {
                log[k] += sign as f32 * a.ln();
            } else {
                zeros[k] += sign;
            }
        }
        if count == 0 {
            (log, zeros, beta2) = (Vec3::ZERO, [0; 3], Vec3::ZERO);
        }
    }
    if prev < 1.0 && hidden == 0 {
        credit(1.0 - prev, log, zeros, count, beta2);
    }
    out
}
