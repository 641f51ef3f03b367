//! Reading the grid: what a point receives past the solids ([`OccluderGrid::visibility`]) and
//! where the first solid lies along the ray near a point ([`OccluderGrid::entry_depth`]).
//!
//! Where the four texels around the point all hit a solid, the entry depth d is interpolated
//! bilinearly and the point at depth x receives 1 − clamp((x − d)/texel, 0, 1): on a smooth
//! surface the interpolated depth follows the surface, so points on the lit side of a solid
//! never shadow themselves ("shadow acne") and points beyond it fade over a texel. Where some
//! texels miss (the silhouette of the shadow), each texel votes with its own comparison,
//! weighted bilinearly: the shadow's edge is antialiased over one texel.

use super::OccluderGrid;
use glam::{Vec2, Vec3};

impl OccluderGrid {
    /// The depth along the light (light-frame metres) at which a ray near light-frame point
    /// `m` first enters a solid: the shallowest of the 5 × 5 texels around `m`'s texel (+∞
    /// where none of them meets a solid). Nothing beyond it can shadow a lit point on the
    /// first surface that rays there meet; taking the neighbours' too keeps hair behind a
    /// solid's silhouette off the surface points at the silhouette, which read across it.
    #[inline]
    pub fn entry_depth(&self, m: Vec3) -> f32 {
        if self.depth.is_empty() || !m.is_finite() {
            return f32::INFINITY;
        }
        let t = (Vec2::new(m.y, m.z) - self.origin) / self.texel_m;
        let (ic, jc) = (t.x.floor() as i64, t.y.floor() as i64);
        let mut shallowest = f32::INFINITY;
        for i in ic - 2..=ic + 2 {
            for j in jc - 2..=jc + 2 {
                if i >= 0 && j >= 0 && (i as usize) < self.dims[0] && (j as usize) < self.dims[1] {
                    shallowest = shallowest.min(self.depth[i as usize * self.dims[1] + j as usize]);
                }
            }
        }
        shallowest
    }

    /// Fraction of the light reaching light-frame point `m` (metres) past the solids, in [0, 1].
    /// The shadow begins at the entry depth and is complete one texel further along the light,
    /// so a point on the lit surface of a solid (or just outside it, as hair roots are) is lit.
    #[inline]
    pub fn visibility(&self, m: Vec3) -> f32 {
        if self.depth.is_empty() || !m.is_finite() {
            return 1.0;
        }
        let t = (Vec2::new(m.y, m.z) - self.origin) / self.texel_m - 0.5;
        let f = t.floor();
        let (w, (i0, j0)) = (t - f, (f.x as i64, f.y as i64));
        let at = |i: i64, j: i64| -> f32 {
            if i < 0 || j < 0 || i as usize >= self.dims[0] || j as usize >= self.dims[1] {
                f32::INFINITY
            } else {
                self.depth[i as usize * self.dims[1] + j as usize]
            }
        };
        let d = [
            at(i0, j0),
            at(i0, j0 + 1),
            at(i0 + 1, j0),
            at(i0 + 1, j0 + 1),
        ];
        let wts = [
            (1.0 - w.x) * (1.0 - w.y),
            (1.0 - w.x) * w.y,
            w.x * (1.0 - w.y),
            w.x * w.y,
        ];
        let shadowed = |depth: f32| ((m.x - depth) / self.texel_m).clamp(0.0, 1.0);
        if d.iter().all(|v| v.is_finite()) {
            let depth = d.iter().zip(&wts).map(|(d, w)| d * w).sum::<f32>();
            1.0 - shadowed(depth)
        } else {
            1.0 - d
                .iter()
                .zip(&wts)
                .filter(|(d, _)| d.is_finite())
                .map(|(d, w)| w * shadowed(*d))
                .sum::<f32>()
        }
    }
}
