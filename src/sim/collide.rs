//! Collision shapes (the head ellipsoid and body spheres) and the projection that moves a guide
//! particle out of them while keeping its link length exact.
//!
//! What: [`Colliders`] is the scene at one instant (head transform, head semi-axes, spheres in
//! world metres). `CollisionScene` is the same scene prepared once per step (inverse head
//! transform, inflated radii) for the per-particle test.
//!
//! How (inside the follow-the-leader sweep, see `step.rs`): a particle is first placed at
//! exactly one link length L from its predecessor, which is already final and outside every
//! collider. If it lies inside a collider inflated by [`COLLISION_MARGIN_M`], it is moved to
//! the nearest point that is both at distance L from the predecessor and on the inflated
//! surface: for a sphere that point is exact and closed-form (the circle where the link sphere
//! meets the collider sphere, at the particle's azimuth, see `circle_exit`); for the head the
//! same construction runs in scaled head coordinates, where the ellipsoid is the unit sphere,
//! and the result is put back at distance L in world space (the scaling distorts lengths by at
//! most the head's axis ratio, 1.29 for the presets, so the point lands within a small fraction
//! of the margin of the surface). This repeats, over all colliders, up to [`COLLISION_ROUNDS`]
//! times while any collider still holds the particle. The length projection is always last, so
//! links stay rigid to rounding; any residual penetration is of the inflated surface and the
//! margin absorbs it (the tests measure the true surface: 0 over 10 s of dance).
//!
//! Why not "push out along the normal, then restore the length" (the first version): for hair
//! lying nearly tangent to a small sphere that alternation converges slowly; four rounds left
//! 1.03 mm inside the 45 mm neck sphere in the dance test. Resolving collisions before the
//! length pass would let it pull particles back in; after it without re-projection would
//! stretch links.
//!
//! Tunnelling: the answer is always on the predecessor's side of the collider (the link
//! sphere's cap facing it), so a particle can only end on the wrong side if its predecessor is
//! already inside. Predecessors are resolved first and the root segment is outside the head by
//! construction, so what remains is a collider moving so far in one step that it jumps past
//! a whole link, i.e. by more than the smallest collider dimension per step: 0.076 m / step_s
//! relative speed for the head and `radius / step_s` for a sphere: at 1/240 s, 18 m/s for the
//! head and 10.8 m/s for the dance's 0.045 m neck sphere; twice that at the default 1/480 s. The dance's fastest scalp points
//! move at about 0.8 m/s from the 8 rad/s yaw and 1.26 m/s from the bob; 3x speed stays under
//! 4 m/s.

use glam::{Affine3A, Vec3, Vec3A, Vec4};

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
}

impl Colliders {
    /// A head at `head` with no body spheres.
    pub fn head_only(head: Affine3A, head_radii_m: Vec3) -> Self {
        Self {
            head,
            head_radii_m,
            spheres: Vec::new(),
            capsules: Vec::new(),
        }
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

/// The bounding spheres of up to four consecutive capsules, by coordinate (unused lanes can
/// touch nothing). Each squared reach is widened by 1e-5 relative over the capsule's own, so
/// that whenever the per-capsule test ([`BoundedCapsule::may_touch`]) says "may touch", this
/// one says so too, whatever the rounding of the two sums: it only decides which groups are
/// looked at capsule by capsule, and the answer is the same bits.
struct BoundGroup {
    x: Vec4,
    y: Vec4,
    z: Vec4,
    reach2: Vec4,
}

impl BoundGroup {
    fn of(capsules: &[BoundedCapsule]) -> Self {
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
    fn may_touch_any(&self, p: Vec3A) -> bool {
        let dx = self.x - Vec4::splat(p.x);
        let dy = self.y - Vec4::splat(p.y);
        let dz = self.z - Vec4::splat(p.z);
        (dx * dx + dy * dy + dz * dz).cmplt(self.reach2).any()
    }
}

/// A capsule with a conservative bounding sphere of its inflated shape.
struct BoundedCapsule<'a> {
    capsule: &'a CapsuleCollider,
    centre: Vec3A,
    /// Squared bound radius: (half the axis + radius + margin), widened by 1e-4 relative and
    /// 1 µm so rounding can never skip a capsule the exact test would catch.
    reach2: f32,
}

impl<'a> BoundedCapsule<'a> {
    fn new(capsule: &'a CapsuleCollider) -> Self {
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
    fn may_touch(&self, p: Vec3A) -> bool {
        (p - self.centre).length_squared() < self.reach2
    }
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
    /// doc). `fallback_dir` (unit) replaces degenerate directions.
    #[inline]
    /// Also returns whether any collider was touched (when not, `p` is outside every inflated
    /// collider, hence outside the true ones, and its penetration is 0).
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
            let mut moved = false;
            // Head ellipsoid, in scaled head coordinates where it is the unit sphere.
            let qs = self.world_to_head.transform_point3a(p) * self.inv_radii_out;
            if qs.length_squared() < 1.0 {
                let prev_s = self.world_to_head.transform_point3a(prev) * self.inv_radii_out;
                let fallback_s =
                    self.world_to_head.transform_vector3a(fallback_dir) / self.radii_out;
                let link_s = (qs - prev_s).length();
                let out_s = circle_exit(prev_s, qs, link_s, Vec3A::ZERO, 1.0, fallback_s)
                    .unwrap_or_else(|| qs.normalize_or(fallback_s.normalize_or(Vec3A::Y)));
                let out = self.head_to_world.transform_point3a(out_s * self.radii_out);
                p = prev + (out - prev).normalize_or(fallback_dir) * link_m;
                moved = true;
            }
            for sp in self.spheres {
                let r = sp.radius_m;
                if !(r > 0.0 && r.is_finite()) {
                    continue;
                }
                let c = Vec3A::from(sp.center);
                let ro = r + COLLISION_MARGIN_M;
                if (p - c).length_squared() < ro * ro {
                    let out =
                        circle_exit(prev, p, link_m, c, ro, fallback_dir).unwrap_or_else(|| {
                            // The link cannot reach the surface (a kinematic root particle deep
                            // inside): push radially and accept what the length allows.
                            c + (p - c).normalize_or(fallback_dir) * ro
                        });
                    p = prev + (out - prev).normalize_or(fallback_dir) * link_m;
                    moved = true;
                }
            }
            for (group, four) in self.groups.iter().zip(self.capsules.chunks(4)) {
                if !group.may_touch_any(p) {
                    continue;
                }
                // In order and with the particle as it is now, as if there were no groups.
                for c in four {
                    if !c.may_touch(p) {
                        continue;
                    }
                    if let Some(q) = c.capsule.push_out_usable(prev, p, link_m, fallback_dir) {
                        p = q;
                        moved = true;
                    }
                }
            }
            if !moved {
                break;
            }
            touched = true;
        }
        (p, touched)
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

impl CapsuleCollider {
    /// `p` moved out of the capsule inflated by the collision margin, at `link_m` from `prev`,
    /// or `None` when it is already outside (see the module doc).
    #[cfg(test)]
    pub(crate) fn push_out(
        &self,
        prev: Vec3A,
        p: Vec3A,
        link_m: f32,
        fallback_dir: Vec3A,
    ) -> Option<Vec3A> {
        if !self.usable() {
            return None;
        }
        self.push_out_usable(prev, p, link_m, fallback_dir)
    }

    /// [`Self::push_out`] for a capsule known to be usable.
    #[inline]
    pub(crate) fn push_out_usable(
        &self,
        prev: Vec3A,
        p: Vec3A,
        link_m: f32,
        fallback_dir: Vec3A,
    ) -> Option<Vec3A> {
        let c = self.nearest(p);
        let ro = self.radius_m + COLLISION_MARGIN_M;
        if (p - c).length_squared() >= ro * ro {
            return None;
        }
        let out = circle_exit(prev, p, link_m, c, ro, fallback_dir)
            .unwrap_or_else(|| c + (p - c).normalize_or(fallback_dir) * ro);
        Some(prev + (out - prev).normalize_or(fallback_dir) * link_m)
    }
}

/// The point nearest `p` among those at distance `link` from `prev` and not inside the sphere
/// (`c`, `r`). Those points form a spherical cap of the link sphere, bounded by the circle
/// where the two spheres meet: with `D = |c − prev|` and axis `a = (c − prev)/D`, the circle's
/// centre is `prev + h a` with `h = (D² + L² − r²) / (2D)` and its radius `ρ = √(L² − h²)`.
/// A point of the link sphere beyond the cap (inside the collider) is nearest to the circle
/// point of the same azimuth about `a`. `None` when the two spheres do not meet (|h| > L: the
/// link sphere is wholly inside or wholly outside) or `prev` is the centre.
///
/// The formula holds whether `prev` is outside, on or inside the sphere. It used to refuse a
/// `prev` inside, but a predecessor resting on the inflated surface is inside or outside by
/// rounding from one step to the next, and the radial fallback it then took lands up to 64 µm
/// away from the circle point: hair resting on a sphere jumped between the two every few
/// steps and never came to rest (issue 11; measured 2e-2 m/s on curly hair at the nape).
#[inline]
pub(crate) fn circle_exit(
    prev: Vec3A,
    p: Vec3A,
    link: f32,
    c: Vec3A,
    r: f32,
    fallback: Vec3A,
) -> Option<Vec3A> {
    let to_c = c - prev;
    let d = to_c.length();
    // d is NaN or 0: no axis.
    if d.is_nan() || d <= 0.0 {
        return None;
    }
    let a = to_c / d;
    let h = (d * d + link * link - r * r) / (2.0 * d);
    if h.is_nan() || h.abs() > link {
        return None;
    }
    let rho = (link * link - h * h).max(0.0).sqrt();
    let rel = p - prev;
    let u = (rel - a * rel.dot(a))
        .try_normalize()
        .or_else(|| (fallback - a * fallback.dot(a)).try_normalize())
        .unwrap_or_else(|| a.any_orthonormal_vector());
    Some(prev + a * h + u * rho)
}

#[cfg(test)]
mod tests;
