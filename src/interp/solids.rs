//! Render strands kept out of the head and body.
//!
//! The guides never enter a collider (`sim::collide`), but a render strand is a blend of its
//! wisp's three guides, and where those guides part around a collider (a wisp whose guides
//! fall on both sides of the neck, or on both sides of a parting) the blend cuts through it:
//! measured on the smooth preset over the dance, about 2% of render points lay more than 3 mm
//! inside the mannequin, up to 3 cm inside the head and 2 cm inside the neck. Each render
//! point (but the root) that lies inside a collider is therefore moved to the collider's
//! surface, radially: for the head ellipsoid along the ray from its centre in its unit-sphere
//! space (the point lands exactly on the surface), for a sphere or capsule away from its
//! centre or axis. A push stretches the segments next to a moved point (by up to the push,
//! centimetres), and a stretched segment would both add fibre to the map (its crossings grow
//! with its length) and raise the map's pieces per sample for every strand (the longest
//! segment sets them, and the memory budget counts them from the rest length: one pushed
//! strand took the map from 240 to 315 MB). So after the push, a follow-the-leader pass root
//! to tip brings every stretched segment back to its length before the push, and the two
//! alternate for up to [`ROUNDS`] rounds, lengths last, as the simulation's collision does
//! (a strand straight through a sphere's centre ends under 1 cm deep instead of 5 cm). Tangents
//! and lengths are computed after this.
//!
//! Cost: a strand's bounding box is tested against each collider's box first, so a collider
//! costs a point-by-point test only for the strands near it (the head's test is one transform
//! per point).

use crate::sim::Colliders;
use glam::{Affine3A, Vec3};

/// Rounds of push and length restoration per strand (the last restores lengths).
pub const ROUNDS: usize = 4;

/// The colliders of one frame, prepared for [`SolidsView::push_out`].
pub struct SolidsView<'a> {
    world_to_head: Affine3A,
    head_to_world: Affine3A,
    radii: Vec3,
    /// Bounding box of the head ellipsoid (its bounding sphere's box).
    head_box: (Vec3, Vec3),
    colliders: &'a Colliders,
}

impl<'a> SolidsView<'a> {
    pub fn new(colliders: &'a Colliders) -> Self {
        let radii = colliders.head_radii_m.max(Vec3::splat(1e-6));
        let centre = Vec3::from(colliders.head.translation);
        let reach = Vec3::splat(radii.max_element());
        Self {
            world_to_head: colliders.head.inverse(),
            head_to_world: colliders.head,
            radii,
            head_box: (centre - reach, centre + reach),
            colliders,
        }
    }

    /// Moves the points of one strand (all but the root) out of every collider, then keeps
    /// every segment no longer than it was (module doc); `scratch` (one value per point) holds
    /// those lengths.
    pub fn push_out(&self, pos: &mut [Vec3], scratch: &mut [f32]) {
        if pos.len() < 2 {
            return;
        }
        for i in 1..pos.len() {
            scratch[i] = pos[i].distance(pos[i - 1]);
        }
        for _ in 0..ROUNDS {
            if !self.push_radially(pos) {
                return;
            }
            // Follow the leader, root to tip: a segment the push stretched is brought back to
            // its length by moving its far end toward its near end.
            for i in 1..pos.len() {
                let d = pos[i] - pos[i - 1];
                let l = d.length();
                if l > scratch[i] && l > 0.0 {
                    pos[i] = pos[i - 1] + d * (scratch[i] / l);
                }
            }
        }
    }

    /// Moves points inside a collider to its surface, radially; whether any moved.
    fn push_radially(&self, pos: &mut [Vec3]) -> bool {
        let mut moved = false;
        let (lo, hi) = pos[1..].iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let overlaps = |a: (Vec3, Vec3)| a.0.cmple(hi).all() && a.1.cmpge(lo).all();
        for s in &self.colliders.spheres {
            let r = s.radius_m;
            if !(r > 0.0 && r.is_finite() && overlaps((s.center - r, s.center + r))) {
                continue;
            }
            for p in &mut pos[1..] {
                let d = *p - s.center;
                if d.length_squared() < r * r {
                    *p = s.center + d.normalize_or(Vec3::Y) * r;
                    moved = true;
                }
            }
        }
        for c in &self.colliders.capsules {
            let r = c.radius_m;
            if !(r > 0.0 && r.is_finite() && overlaps((c.a.min(c.b) - r, c.a.max(c.b) + r))) {
                continue;
            }
            let ab = c.b - c.a;
            let len2 = ab.length_squared();
            for p in &mut pos[1..] {
                let t = if len2 > 0.0 {
                    ((*p - c.a).dot(ab) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let axis = c.a + ab * t;
                let d = *p - axis;
                if d.length_squared() < r * r {
                    *p = axis + d.normalize_or(Vec3::Y) * r;
                    moved = true;
                }
            }
        }
        if overlaps(self.head_box) {
            for p in &mut pos[1..] {
                let q = self.world_to_head.transform_point3(*p) / self.radii;
                let s = q.length();
                if s < 1.0 && s > 1e-6 {
                    *p = self.head_to_world.transform_point3(q / s * self.radii);
                    moved = true;
                }
            }
        }
        moved
    }
}

#[cfg(test)]
mod tests;
