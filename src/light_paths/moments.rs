//! A cell's weaker light kept as its angular moments up to the second (`response.rs`):
//! M₀ = Σ Φ, M₁ = Σ Φ ω and M₂ = Σ Φ ω ωᵀ over its direction bins (Φ a bin's share of ∫ L dω,
//! ω its mean direction), ten RGB numbers whatever the bins. Why: the gather of the moments is
//! a table lookup and a few dot products per point, where each bin costs one BCSDF
//! evaluation. The second order cannot hold light as peaked as forward scattering leaves it
//! (all of a back-lit cell's light as moments reads 0.65 of its bins; a 37° cap of light
//! through the second order, 1.5–1.7× too bright), so a cell keeps its strongest bins as they
//! are and only the rest, spread over the sphere, as moments (`bins.rs`).

use super::response::ResponseAt;
use glam::Vec3;
use std::f32::consts::PI;

/// One cell's moments (module doc), RGB each: M₀, M₁ by axis (x, y, z), M₂'s xx, yy, zz, xy,
/// xz, yz.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Moment {
    pub(crate) m0: Vec3,
    pub(crate) m1: [Vec3; 3],
    pub(crate) m2: [Vec3; 6],
}

impl Moment {
    /// Adds light `e` (RGB) arriving from unit `d`.
    #[inline]
    pub(crate) fn add(&mut self, d: Vec3, e: Vec3) {
        self.m0 += e;
        self.m1[0] += e * d.x;
        self.m1[1] += e * d.y;
        self.m1[2] += e * d.z;
        self.m2[0] += e * (d.x * d.x);
        self.m2[1] += e * (d.y * d.y);
        self.m2[2] += e * (d.z * d.z);
        self.m2[3] += e * (d.x * d.y);
        self.m2[4] += e * (d.x * d.z);
        self.m2[5] += e * (d.y * d.z);
    }

    /// M₁ · d (RGB).
    #[inline]
    fn first(&self, d: Vec3) -> Vec3 {
        self.m1[0] * d.x + self.m1[1] * d.y + self.m1[2] * d.z
    }

    /// aᵀ M₂ b (RGB).
    #[inline]
    fn second(&self, a: Vec3, b: Vec3) -> Vec3 {
        let m = &self.m2;
        m[0] * (a.x * b.x)
            + m[1] * (a.y * b.y)
            + m[2] * (a.z * b.z)
            + m[3] * (a.x * b.y + a.y * b.x)
            + m[4] * (a.x * b.z + a.z * b.x)
            + m[5] * (a.y * b.z + a.z * b.y)
    }

    /// ∫ S(ωi, ωo) cos θi L(ωi) dωi for the light these moments keep, projected on the
    /// spherical harmonics of order ≤ 2, with the fibre's integrals `r` at ωo's inclination in
    /// the frame (u, w, v) (`response.rs`).
    pub(crate) fn gather(&self, r: &ResponseAt, (u, w, v): (Vec3, Vec3, Vec3)) -> Vec3 {
        let third = self.m0 / 3.0;
        let order0 = self.m0 * r.a0;
        let order1 = 3.0 * (self.first(u) * r.a1_u + self.first(w) * r.a1_w);
        let order2 = 7.5
            * ((self.second(u, u) - third) * r.a2_uu
                + (self.second(w, w) - third) * r.a2_ww
                + (self.second(v, v) - third) * r.a2_vv
                + 2.0 * self.second(u, w) * r.a2_uw);
        (order0 + order1 + order2) / (4.0 * PI)
    }
}
