//! Capsule colliders (a character's limbs and torso, fitted per bone by `motion`).
//!
//! A capsule is the set of points within `radius_m` of a segment. Seen from one particle it is
//! the sphere of that radius centred on the segment point nearest the particle, so the
//! sphere's exact link-preserving exit (`circle_exit`) serves it unchanged: the particle, at
//! one link length from its predecessor (outside every collider), moves to the nearest point
//! at that distance on the sphere's inflated surface. Where that point is still inside the
//! capsule (a long capsule seen at a slant), the collision rounds of `CollisionScene::resolve`
//! repeat with the new nearest segment point. That exit is `CapsuleCollider::push_out`, next
//! to the sphere's in `collide/exit.rs`.

use glam::{Vec3, Vec3A};

/// A body capsule in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CapsuleCollider {
    /// Segment ends, world metres.
    pub a: Vec3,
    pub b: Vec3,
    /// Radius in metres (> 0; a non-positive or non-finite radius is ignored).
    pub radius_m: f32,
}

impl CapsuleCollider {
    /// The segment point nearest `p`.
    #[inline]
    pub(crate) fn nearest(&self, p: Vec3A) -> Vec3A {
        let (a, b) = (Vec3A::from(self.a), Vec3A::from(self.b));
        let ab = b - a;
        let len2 = ab.length_squared();
        if len2.is_nan() || len2 <= 0.0 {
            return a;
        }
        a + ab * ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    }

    pub(crate) fn usable(&self) -> bool {
        self.radius_m > 0.0 && self.radius_m.is_finite() && self.a.is_finite() && self.b.is_finite()
    }

    /// Depth of `p` inside the (true, not inflated) capsule in metres, 0 outside.
    #[inline]
    pub(crate) fn penetration_m(&self, p: Vec3A) -> f32 {
        if !self.usable() {
            return 0.0;
        }
        (self.radius_m - (p - self.nearest(p)).length()).max(0.0)
    }
}

#[cfg(test)]
mod tests;
