//! Collision shapes (the head ellipsoid, body spheres and capsules) and the projection that
//! moves a guide particle out of them while keeping its link length exact.
//!
//! What: [`Colliders`] is the scene at one instant (head transform, head semi-axes, spheres and
//! capsules in world metres). `CollisionScene` is the same scene prepared once per step
//! (inverse head transform, inflated radii, the capsules' bounds) for the per-particle test.
//!
//! How (inside the follow-the-leader sweep, see `guide_step.rs`): a particle is first placed at
//! exactly one link length L from its predecessor, which is already final and outside every
//! collider. If it lies inside a collider inflated by [`COLLISION_MARGIN_M`], it is moved to
//! the nearest point that is both at distance L from the predecessor and on the inflated
//! surface: for a sphere that point is exact and closed-form (the circle where the link sphere
//! meets the collider sphere, at the particle's azimuth, `exit.rs`); for the head the same
//! construction runs in scaled head coordinates, where the ellipsoid is the unit sphere, and the
//! result is put back at distance L in world space (the scaling distorts lengths by at most the
//! head's axis ratio, 1.29 for the presets, so the point lands within a small fraction of the
//! margin of the surface); a capsule is the sphere about its segment's point nearest the
//! particle (`capsule.rs`). This repeats, over all colliders, up to [`COLLISION_ROUNDS`] times
//! while any collider still holds the particle. The length projection is always last, so links
//! stay rigid to rounding; any residual penetration is of the inflated surface and the margin
//! absorbs it (the tests measure the true surface: 0 over 10 s of dance).
//!
//! Why not "push out along the normal, then restore the length": for hair lying nearly
//! tangent to a small sphere that alternation converges slowly; four rounds leave 1.03 mm
//! inside the 45 mm neck sphere in the dance test. Resolving collisions before the length pass
//! would let it pull particles back in; after it without re-projection would stretch links.
//!
//! Tunnelling: the answer is always on the predecessor's side of the collider (the link
//! sphere's cap facing it), so a particle can only end on the wrong side if its predecessor is
//! already inside. Predecessors are resolved first and the root segment is outside the head by
//! construction, so what remains is a collider moving so far in one step that it jumps past
//! a whole link, i.e. by more than the smallest collider dimension per step: 0.076 m / step_s
//! relative speed for the head and `radius / step_s` for a sphere: at 1/240 s, 18 m/s for the
//! head and 10.8 m/s for the dance's 0.045 m neck sphere; twice that at the default 1/480 s.
//! The dance's fastest scalp points move at about 0.8 m/s from the 8 rad/s yaw and 1.26 m/s
//! from the bob; 3× speed stays under 4 m/s.

mod bounds;
mod exit;

use bounds::{BoundGroup, BoundedCapsule};
use exit::circle_exit;
use glam::{Affine3A, Vec3, Vec3A};

use super::capsule::CapsuleCollider;

/// Extra clearance in metres that collisions push particles to, beyond the true surface: it
/// absorbs the residual penetration left by the final length projection. 1 mm is below the
/// visible scale of a wisp (≈ 9 mm radius) and above the residuals measured in the tests.
pub const COLLISION_MARGIN_M: f32 = 1.0e-3;

/// Maximum rounds of (push out of every collider, restore link length) per particle.
pub const COLLISION_ROUNDS: usize = 4;

/// A body collision sphere in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereCollider {
    /// Centre, world metres.
    pub center: Vec3,
    /// Radius in metres (> 0; a non-positive or non-finite radius is ignored).
    pub radius_m: f32,
}

/// Everything hair collides with at one instant.
#[derive(Clone, Debug, PartialEq)]
pub struct Colliders {
    /// Head frame → world, rigid (rotation + translation). The roots follow it.
    pub head: Affine3A,
    /// Semi-axes of the head ellipsoid in the head frame, metres (x ear to ear, y up, z face).
    pub head_radii_m: Vec3,
    /// Body spheres (neck, shoulders, ...), world.
    pub spheres: Vec<SphereCollider>,
    /// Body capsules (a character's limbs and torso), world; see `capsule.rs`.
    pub capsules: Vec<CapsuleCollider>,
    /// Head frame → world for each bone that carries roots (`GuideSet::carrier`: a groom kept
    /// as authored on its character); empty for hair on a head.
    pub carriers: Vec<Affine3A>,
}

impl Colliders {
    /// A head at `head` with no body spheres.
    pub fn head_only(head: Affine3A, head_radii_m: Vec3) -> Self {
        Self {
            head,
            head_radii_m,
            spheres: Vec::new(),
            capsules: Vec::new(),
            carriers: Vec::new(),
        }
    }

    /// A box (lowest and highest corners, world metres) around each solid: the head
    /// ellipsoid, each sphere and each capsule. Every point of positive
    /// [`Colliders::penetration_m`] lies in one.
    pub fn solid_bounds_m(&self) -> Vec<(Vec3, Vec3)> {
        // The ellipsoid's half extent along world axis i: |row i of M·diag(r)|.
        let m = glam::Mat3::from(self.head.matrix3);
        let r = self.head_radii_m;
        let half = Vec3::new(
            (m.row(0) * r).length(),
            (m.row(1) * r).length(),
            (m.row(2) * r).length(),
        );
        let centre = Vec3::from(self.head.translation);
        let mut boxes = vec![(centre - half, centre + half)];
        for sp in &self.spheres {
            boxes.push((
                sp.center - Vec3::splat(sp.radius_m),
                sp.center + Vec3::splat(sp.radius_m),
            ));
        }
        for c in &self.capsules {
            let r = Vec3::splat(c.radius_m);
            boxes.push((c.a.min(c.b) - r, c.a.max(c.b) + r));
        }
        boxes
    }

    /// Conservative penetration depth (metres, 0 outside) of world point `p` into the head
    /// ellipsoid or any sphere: for the ellipsoid, `(1 − |q/r|) · max(r)` bounds the distance
    /// to the surface from above (the distance along the ray from the centre is at least the
    /// distance to the surface, and at most `(1 − s) · max(r)`).
    pub fn penetration_m(&self, p: Vec3) -> f32 {
        let q = self.head.inverse().transform_point3(p);
        let r = self.head_radii_m;
        let s = (q / r).length();
        let mut depth = ((1.0 - s) * r.max_element()).max(0.0);
        for sp in &self.spheres {
            depth = depth.max(sp.radius_m - (p - sp.center).length());
        }
        for c in &self.capsules {
            depth = depth.max(c.penetration_m(Vec3A::from(p)));
        }
        depth.max(0.0)
    }
}

/// The colliders of one step, prepared for the inner loop.
pub(crate) struct CollisionScene<'a> {
    /// World → head frame.
    world_to_head: Affine3A,
    /// Head frame → world.
    head_to_world: Affine3A,
    /// True semi-axes (for measuring penetration).
    radii: Vec3A,
    /// Inflated semi-axes (radii + margin), what particles are pushed to.
    radii_out: Vec3A,
    /// 1 / radii_out (the common no-contact test multiplies instead of dividing).
    inv_radii_out: Vec3A,
    /// Largest true semi-axis (for the conservative penetration estimate).
    radius_max: f32,
    spheres: &'a [SphereCollider],
    /// The usable capsules (finite, positive radius) with a bounding sphere of each inflated
    /// capsule: most particles are far from most limbs, and one distance to the bound's
    /// centre skips a capsule that could not touch the particle (the skipped test would have
    /// answered "outside", so results are unchanged to the bit).
    capsules: Vec<BoundedCapsule<'a>>,
    /// The same bounds four capsules at a time, so that one SIMD test skips four capsules
    /// (a character has tens of them, and a particle is near a few at most).
    groups: Vec<BoundGroup>,
}

impl<'a> CollisionScene<'a> {
    pub(crate) fn new(c: &'a Colliders) -> Self {
        let capsules: Vec<BoundedCapsule> = c
            .capsules
            .iter()
            .filter(|c| c.usable())
            .map(BoundedCapsule::new)
            .collect();
        let radii = Vec3A::from(c.head_radii_m).max(Vec3A::splat(1e-6));
        Self {
            world_to_head: c.head.inverse(),
            head_to_world: c.head,
            radii,
            radii_out: radii + Vec3A::splat(COLLISION_MARGIN_M),
            inv_radii_out: (radii + Vec3A::splat(COLLISION_MARGIN_M)).recip(),
            radius_max: radii.max_element(),
            spheres: &c.spheres,
            groups: capsules.chunks(4).map(BoundGroup::of).collect(),
            capsules,
        }
    }

    /// Moves `p`, which is at exactly `link_m` from `prev` (outside every collider), out of the
    /// colliders inflated by the margin while keeping it at `link_m` from `prev` (see the module
    /// doc). `fallback_dir` (unit) replaces degenerate directions. Also returns whether any
    /// collider was touched (when not, `p` is outside every inflated collider, hence outside
    /// the true ones, and its penetration is 0).
    #[inline]
    pub(crate) fn resolve(
        &self,
        prev: Vec3A,
        p: Vec3A,
        link_m: f32,
        fallback_dir: Vec3A,
    ) -> (Vec3A, bool) {
        let mut p = p;
        let mut touched = false;
        for _ in 0..COLLISION_ROUNDS {
            // Head, then spheres, then capsules, each seeing the particle as the last left it.
            let head = self.out_of_head(prev, &mut p, link_m, fallback_dir);
            let spheres = self.out_of_spheres(prev, &mut p, link_m, fallback_dir);
            let capsules = self.out_of_capsules(prev, &mut p, link_m, fallback_dir);
            if !(head || spheres || capsules) {
                break;
            }
            touched = true;
        }
        (p, touched)
    }

    /// One round's push out of the head ellipsoid, in scaled head coordinates where it is the
    /// unit sphere (module doc). Whether `p` moved.
    #[inline]
    fn out_of_head(&self, prev: Vec3A, p: &mut Vec3A, link_m: f32, fallback_dir: Vec3A) -> bool {
        let qs = self.world_to_head.transform_point3a(*p) * self.inv_radii_out;
        if qs.length_squared() >= 1.0 {
            return false;
        }
        let prev_s = self.world_to_head.transform_point3a(prev) * self.inv_radii_out;
        let fallback_s = self.world_to_head.transform_vector3a(fallback_dir) / self.radii_out;
        let link_s = (qs - prev_s).length();
        let out_s = circle_exit(prev_s, qs, link_s, Vec3A::ZERO, 1.0, fallback_s)
            .unwrap_or_else(|| qs.normalize_or(fallback_s.normalize_or(Vec3A::Y)));
        let out = self.head_to_world.transform_point3a(out_s * self.radii_out);
        *p = prev + (out - prev).normalize_or(fallback_dir) * link_m;
        true
    }

    /// One round's push out of each usable sphere in turn. Whether `p` moved.
    #[inline]
    fn out_of_spheres(&self, prev: Vec3A, p: &mut Vec3A, link_m: f32, fallback_dir: Vec3A) -> bool {
        let mut moved = false;
        for sp in self.spheres {
            let r = sp.radius_m;
            if !(r > 0.0 && r.is_finite()) {
                continue;
            }
            let c = Vec3A::from(sp.center);
            let ro = r + COLLISION_MARGIN_M;
            if (*p - c).length_squared() < ro * ro {
                let out = circle_exit(prev, *p, link_m, c, ro, fallback_dir).unwrap_or_else(|| {
                    // The link cannot reach the surface (a kinematic root particle deep
                    // inside): push radially and accept what the length allows.
                    c + (*p - c).normalize_or(fallback_dir) * ro
                });
                *p = prev + (out - prev).normalize_or(fallback_dir) * link_m;
                moved = true;
            }
        }
        moved
    }

    /// One round's push out of each capsule in turn, skipping those whose bounds rule the
    /// particle out (`bounds.rs`). Whether `p` moved.
    #[inline]
    fn out_of_capsules(
        &self,
        prev: Vec3A,
        p: &mut Vec3A,
        link_m: f32,
        fallback_dir: Vec3A,
    ) -> bool {
        let mut moved = false;
        for (group, four) in self.groups.iter().zip(self.capsules.chunks(4)) {
            if !group.may_touch_any(*p) {
                continue;
            }
            // In order and with the particle as it is now, as if there were no groups.
            for c in four {
                if !c.may_touch(*p) {
                    continue;
                }
                if let Some(q) = c.capsule.push_out_usable(prev, *p, link_m, fallback_dir) {
                    *p = q;
                    moved = true;
                }
            }
        }
        moved
    }

    /// Penetration depth in metres of `p` into the true (not inflated) colliders: conservative
    /// for the ellipsoid (see [`Colliders::penetration_m`]), exact for spheres; 0 outside.
    #[inline]
    pub(crate) fn penetration_m(&self, p: Vec3A) -> f32 {
        let s2 = (self.world_to_head.transform_point3a(p) / self.radii).length_squared();
        let mut depth = if s2 < 1.0 {
            (1.0 - s2.sqrt()) * self.radius_max
        } else {
            0.0
        };
        for sp in self.spheres {
            let r = sp.radius_m;
            let d2 = (p - Vec3A::from(sp.center)).length_squared();
            if r > 0.0 && r.is_finite() && d2 < r * r {
                depth = depth.max(r - d2.sqrt());
            }
        }
        for c in &self.capsules {
            if c.may_touch(p) {
                depth = depth.max(c.capsule.penetration_m(p));
            }
        }
        depth
    }
}

#[cfg(test)]
mod tests;
