//! The link-preserving exit from a sphere: the point nearest a particle among those at one
//! link length from its predecessor and outside the sphere (`circle_exit`), and the capsule's
//! exit built on it (a capsule seen from one particle is the sphere about its segment's
//! nearest point).

use super::super::capsule::CapsuleCollider;
use super::COLLISION_MARGIN_M;
use glam::Vec3A;

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
/// The formula holds whether `prev` is outside, on or inside the sphere, and is used in all
/// three cases: a predecessor resting on the inflated surface is inside or outside by rounding
/// from one step to the next, and a radial push for a `prev` inside lands up to 64 µm away
/// from the circle point, so hair resting on a sphere would jump between the two every few
/// steps and never come to rest (measured: 2e-2 m/s on curly hair at the nape).
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
