//! Density-based self-collision (Bertails, Ménier & Cani 2005 §4.1).
//!
//! What: the hair's own volume is kept by pushing guide particles out of map cells whose hair
//! density is above a threshold, instead of testing strand against strand. Bertails: "hair
//! self-collisions are processed by applying repulsive forces from the center of each cell
//! having a too high density".
//!
//! How: the simulator asks a [`DensityField`] (in the engine, the light-oriented map built for
//! the previous frame; in tests, a small grid) for the volume fraction `d` of the cell holding
//! each free particle and that cell's centre `c`, and when `d > density_threshold` adds the
//! acceleration
//!
//! `a = repulsion_m_s2 · (d − density_threshold) · (p − c) / |p − c|`   (m/s²)
//!
//! The paper gives no formula; this reading is linear in the excess so that the force vanishes
//! continuously at the threshold (no chattering between "repelled" and "free" from one step to
//! the next), and it points away from the cell centre as the paper says. A particle exactly at
//! the centre gets no push (no preferred direction).
//!
//! Why a trait: the map module builds the field and must not depend on the simulator, and the
//! simulator must not know the map's layout. The simulator is generic over the field (no
//! dynamic dispatch in the per-particle loop) and calls it from several threads (`Sync`).

use glam::Vec3;

/// A field of hair volume fractions the simulator can query.
pub trait DensityField: Sync {
    /// Hair volume fraction (dimensionless, 0..1) of the map cell holding world point `p`, and
    /// that cell's centre (world metres); `None` when `p` is outside any filled cell.
    fn cell_density(&self, p: Vec3) -> Option<(f32, Vec3)>;
}

/// No density information: self-collision off.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoDensity;

impl DensityField for NoDensity {
    #[inline]
    fn cell_density(&self, _p: Vec3) -> Option<(f32, Vec3)> {
        None
    }
}

/// Bertails §4.1 repulsion: the acceleration (m/s²) on a particle at `p`, or `None` when its
/// cell is not over the threshold (or reports a non-finite value).
#[inline]
pub(crate) fn repulsion_m_s2<D: DensityField>(
    field: &D,
    p: Vec3,
    threshold: f32,
    strength_m_s2: f32,
) -> Option<Vec3> {
    let (d, centre) = field.cell_density(p)?;
    let excess = d - threshold;
    if !(excess > 0.0 && excess.is_finite() && centre.is_finite()) {
        return None;
    }
    Some((p - centre).normalize_or_zero() * (strength_m_s2 * excess))
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Uniform(f32);
    impl DensityField for Uniform {
        fn cell_density(&self, p: Vec3) -> Option<(f32, Vec3)> {
            Some((self.0, (p * 10.0).floor() / 10.0 + Vec3::splat(0.05)))
        }
    }

    #[test]
    fn repulsion_is_zero_at_threshold_and_points_away_from_the_centre() {
        let p = Vec3::new(0.07, 0.02, 0.05);
        assert!(repulsion_m_s2(&Uniform(0.25), p, 0.25, 20.0).is_none());
        assert!(repulsion_m_s2(&NoDensity, p, 0.25, 20.0).is_none());
        assert!(repulsion_m_s2(&Uniform(f32::NAN), p, 0.25, 20.0).is_none());
        let a = repulsion_m_s2(&Uniform(0.75), p, 0.25, 20.0).expect("over threshold");
        assert!((a.length() - 10.0).abs() < 1e-4);
        assert!(a.dot(p - Vec3::splat(0.05)) > 0.0);
    }
}
