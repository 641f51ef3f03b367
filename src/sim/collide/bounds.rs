//! Bounding spheres of the capsules, so that a particle far from a limb skips its exact test
//! (`CollisionScene::resolve`): a character has tens of capsules and a particle is near a few
//! at most. One distance to a bound's centre rules out a capsule, and one SIMD test rules out a
//! group of four. The bounds are widened for rounding, so a skipped capsule is one the exact
//! test would have found outside: the result is the same bits as testing every capsule.

use super::super::capsule::CapsuleCollider;
use super::COLLISION_MARGIN_M;
use glam::{Vec3A, Vec4};

/// The bounding spheres of up to four consecutive capsules, by coordinate (unused lanes can
/// touch nothing). Each squared reach is widened by 1e-5 relative over the capsule's own, so
/// that whenever the per-capsule test ([`BoundedCapsule::may_touch`]) says "may touch", this
/// one says so too, whatever the rounding of the two sums: it only decides which groups are
/// looked at capsule by capsule, and the answer is the same bits.
pub(super) struct BoundGroup {
    x: Vec4,
    y: Vec4,
    z: Vec4,
    reach2: Vec4,
}

impl BoundGroup {
    pub(super) fn of(capsules: &[BoundedCapsule]) -> Self {
        let (mut x, mut y, mut z, mut reach2) = ([0.0; 4], [0.0; 4], [0.0; 4], [-1.0; 4]);
        for (i, c) in capsules.iter().take(4).enumerate() {
            (x[i], y[i], z[i]) = (c.centre.x, c.centre.y, c.centre.z);
            reach2[i] = c.reach2 * (1.0 + 1e-5);
        }
        Self {
            x: Vec4::from_array(x),
            y: Vec4::from_array(y),
            z: Vec4::from_array(z),
            reach2: Vec4::from_array(reach2),
        }
    }

    /// Whether `p` may be inside any of the group's inflated capsules.
    #[inline]
    pub(super) fn may_touch_any(&self, p: Vec3A) -> bool {
        let dx = self.x - Vec4::splat(p.x);
        let dy = self.y - Vec4::splat(p.y);
        let dz = self.z - Vec4::splat(p.z);
        (dx * dx + dy * dy + dz * dz).cmplt(self.reach2).any()
    }
}

/// A capsule with a conservative bounding sphere of its inflated shape.
pub(super) struct BoundedCapsule<'a> {
    pub(super) capsule: &'a CapsuleCollider,
    pub(super) centre: Vec3A,
    /// Squared bound radius: (half the axis + radius + margin), widened by 1e-4 relative and
    /// 1 µm so rounding can never skip a capsule the exact test would catch.
    pub(super) reach2: f32,
}

impl<'a> BoundedCapsule<'a> {
    pub(super) fn new(capsule: &'a CapsuleCollider) -> Self {
        let (a, b) = (Vec3A::from(capsule.a), Vec3A::from(capsule.b));
        let reach = 0.5 * (b - a).length() + capsule.radius_m + COLLISION_MARGIN_M;
        let reach = reach * (1.0 + 1e-4) + 1e-6;
        Self {
            capsule,
            centre: 0.5 * (a + b),
            reach2: reach * reach,
        }
    }

    /// Whether `p` may be inside the inflated capsule (false: certainly outside).
    #[inline]
    pub(super) fn may_touch(&self, p: Vec3A) -> bool {
        (p - self.centre).length_squared() < self.reach2
    }
}
