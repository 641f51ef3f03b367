//! Reading the map: the trilinear filter of Bertails 2005 §3.3 and the cell density used by
//! self-collision (§4.1).

use super::{Cell, LightMap};
use crate::fiber::LightAtPoint;
use glam::Vec3;

/// Light leaving a far face: (direct fraction, T_f, σ̄f²) as plain arrays for blending.
#[derive(Clone, Copy)]
struct Face {
    direct: f32,
    tf: Vec3,
    sigma2: Vec3,
}

const OPEN: Face = Face {
    direct: 1.0,
    tf: Vec3::ONE,
    sigma2: Vec3::ZERO,
};

impl From<&Cell> for Face {
    #[inline]
    fn from(c: &Cell) -> Self {
        Face {
            direct: c.direct,
            tf: Vec3::from(c.tf),
            sigma2: Vec3::from(c.sigma2),
        }
    }
}

impl LightMap {
    /// Light reaching world point `p`, filtered trilinearly: along X between the far faces of
    /// cells i−1 and i (the light entering and leaving the point's cell), across X between
    /// column centres. Non-finite points and points before the hair read as unshadowed.
    pub fn light_at(&self, p: Vec3) -> LightAtPoint {
        let c = self.cell_coords(p);
        if !c.is_finite() || c.abs().max_element() >= 1.0e12 {
            return LightAtPoint::UNSHADOWED;
        }
        let i = c.x.floor();
        let lambda = c.x - i;
        let d = i as i64 - self.first_slice;
        let (yj, zk) = (c.y - 0.5, c.z - 0.5);
        let (j0, k0) = (yj.floor(), zk.floor());
        let (wy, wz) = (yj - j0, zk - k0);
        let (j0, k0) = (j0 as i64, k0 as i64);
        let mut acc = Face {
            direct: 0.0,
            tf: Vec3::ZERO,
            sigma2: Vec3::ZERO,
        };
        for (dj, wj) in [(0, 1.0 - wy), (1, wy)] {
            for (dk, wk) in [(0, 1.0 - wz), (1, wz)] {
                let w = wj * wk;
                if w == 0.0 {
                    continue;
                }
                let (before, after) = self.faces(self.column(j0 + dj, k0 + dk), d);
                let wb = w * (1.0 - lambda);
                let wa = w * lambda;
                acc.direct += wb * before.direct + wa * after.direct;
                acc.tf += wb * before.tf + wa * after.tf;
                acc.sigma2 += wb * before.sigma2 + wa * after.sigma2;
            }
        }
        LightAtPoint {
            direct_fraction: acc.direct.clamp(0.0, 1.0),
            tf: acc.tf.clamp(Vec3::ZERO, Vec3::ONE),
            sigma_f2: acc.sigma2.max(Vec3::ZERO),
            crossings_behind: LightAtPoint::DENSE,
        }
    }

    /// A smoother read for surfaces (skin, body): the mean of four lookups half a cell apart
    /// across the light, i.e. a 2-cell tent filter instead of the 1-cell one. Hair shadows on a
    /// smooth surface are seen over many pixels, where the 1-cell bilinear filter shows the
    /// grid as stair-steps along the shadow's edge; hair vertices keep the sharper filter.
    pub fn light_at_smooth(&self, p: Vec3) -> LightAtPoint {
        let h = 0.5 * self.geom.ds_m;
        let (dy, dz) = (self.frame.y * h, self.frame.z * h);
        let mut acc = LightAtPoint {
            direct_fraction: 0.0,
            tf: Vec3::ZERO,
            sigma_f2: Vec3::ZERO,
            crossings_behind: LightAtPoint::DENSE,
        };
        for o in [dy + dz, dy - dz, -dy + dz, -dy - dz] {
            let l = self.light_at(p + o);
            acc.direct_fraction += 0.25 * l.direct_fraction;
            acc.tf += 0.25 * l.tf;
            acc.sigma_f2 += 0.25 * l.sigma_f2;
        }
        acc
    }

    /// The light entering (far face of slice d−1) and leaving (far face of slice d) the cell at
    /// unwrapped distance `d` slices from the first slice, in column `col`.
    #[inline]
    fn faces(&self, col: usize, d: i64) -> (Face, Face) {
        if d < 0 {
            return (OPEN, OPEN);
        }
        let rel = d.rem_euclid(self.geom.n as i64) as u32;
        let Some(k) = self.last_at_or_before(col, rel) else {
            return (OPEN, OPEN);
        };
        let cell = &self.cells[k];
        let leaving = Face::from(cell);
        if cell.slice != rel {
            return (leaving, leaving);
        }
        // The cell itself is filled: the light entering it left the previous filled cell of
        // the column (if any, and not across the wrap).
        let entering = if rel > 0 && k > self.col_start[col] as usize {
            Face::from(&self.cells[k - 1])
        } else {
            OPEN
        };
        (entering, leaving)
    }

    /// Hair volume fraction of the cell holding world point `p` and that cell's centre (world),
    /// or `None` when the cell is empty (Bertails §4.1 self-collision).
    pub fn cell_density(&self, p: Vec3) -> Option<(f32, Vec3)> {
        let c = self.cell_coords(p);
        if !c.is_finite() || c.abs().max_element() >= 1.0e12 {
            return None;
        }
        let f = c.floor();
        let d = f.x as i64 - self.first_slice;
        if d < 0 {
            return None;
        }
        let rel = d.rem_euclid(self.geom.n as i64) as u32;
        let k = self.last_at_or_before(self.column(f.y as i64, f.z as i64), rel)?;
        let cell = Some(&self.cells[k]).filter(|c| c.slice == rel)?;
        let centre = self.frame.to_world((f + Vec3::splat(0.5)) * self.geom.ds_m);
        Some((cell.volume_fraction, centre))
    }
}
