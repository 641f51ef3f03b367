//! Reading the map: the trilinear filter of Bertails 2005 §3.3 and the cell density used by
//! self-collision (§4.1).

use super::{Cell, LightMap};
use crate::fiber::LightAtPoint;
use glam::Vec3;

/// What a ray has crossed up to some depth: expected crossings, losses Σ n(1 − ā_f) and
/// variance Σ n β̄_f² (the sweep's running sums, before any exponential).
#[derive(Clone, Copy)]
struct Sums {
    n: f32,
    loss: Vec3,
    var: Vec3,
}

const NOTHING: Sums = Sums {
    n: 0.0,
    loss: Vec3::ZERO,
    var: Vec3::ZERO,
};

impl From<&Cell> for Sums {
    #[inline]
    fn from(c: &Cell) -> Self {
        Sums {
            n: c.n_sum,
            loss: Vec3::from(c.loss),
            var: Vec3::from(c.sigma2),
        }
    }
}

impl LightMap {
    /// Light reaching world point `p`. Along X, each column gives exactly what has been
    /// crossed up to the point's depth: the sums entering the point's cell plus the share of
    /// the cell's own crossings that lie in front of the point (`Cell::share_before`), turned
    /// into direct fraction exp(−n) and T_f = exp(−loss) per column; across X, the four nearest
    /// columns are blended bilinearly between their centres. Non-finite points and points
    /// before the hair read as unshadowed. `crossings_behind` is each column's total crossings
    /// minus those in front of the point, blended the same way: the hair further along the
    /// light that can scatter light back to the point (Zinke's local back-scatter).
    ///
    /// Only the hair's own extent is read: a column outside it holds no hair (whatever the
    /// modulo indexing would alias there), and a point beyond the hair's last slice receives
    /// its column's whole sums. Inside a map whose span holds the hair (no overflow) this is
    /// exactly the unaliased answer, also for points far from the hair (a character's feet).
    pub fn light_at(&self, p: Vec3) -> LightAtPoint {
        let m = self.frame.to_map(p);
        let c = m * self.inv_ds;
        if !c.is_finite() || c.abs().max_element() >= 1.0e12 {
            return LightAtPoint::UNSHADOWED;
        }
        let visible = self.occluders.visibility(m);
        let i = c.x.floor();
        let mut lambda = c.x - i;
        let mut d = i as i64 - self.first_slice;
        let last = self.hair_hi[0] - self.first_slice;
        if d > last {
            (d, lambda) = (last, 1.0);
        }
        let (yj, zk) = (c.y - 0.5, c.z - 0.5);
        let (j0, k0) = (yj.floor(), zk.floor());
        let (wy, wz) = (yj - j0, zk - k0);
        let (j0, k0) = (j0 as i64, k0 as i64);
        let (mut direct, mut tf, mut var, mut behind) = (0.0f32, Vec3::ZERO, Vec3::ZERO, 0.0f32);
        for (dj, wj) in [(0, 1.0 - wy), (1, wy)] {
            for (dk, wk) in [(0, 1.0 - wz), (1, wz)] {
                let w = wj * wk;
                if w == 0.0 {
                    continue;
                }
                let (j, k) = (j0 + dj, k0 + dk);
                let in_hair = (self.hair_lo[1]..=self.hair_hi[1]).contains(&j)
                    && (self.hair_lo[2]..=self.hair_hi[2]).contains(&k);
                if !in_hair {
                    direct += w;
                    tf += Vec3::splat(w);
                    continue;
                }
                let col = self.column(j, k);
                let s = self.sums_at(col, d, lambda);
                direct += w * (-s.n).exp();
                tf += w * (-s.loss).exp();
                var += w * s.var;
                behind += w * (self.column_total(col) - s.n).max(0.0);
            }
        }
        LightAtPoint {
            direct_fraction: (direct * visible).clamp(0.0, 1.0),
            tf: (tf * visible).clamp(Vec3::ZERO, Vec3::ONE),
            sigma_f2: var.max(Vec3::ZERO),
            crossings_behind: behind,
        }
    }

    /// Expected crossings of a ray through the whole of column `col` (0 for an empty column):
    /// the running sum of its last filled cell, found through the column's slot table.
    #[inline]
    fn column_total(&self, col: usize) -> f32 {
        let end = self.slot_start[col + 1] as usize;
        if end == self.slot_start[col] as usize {
            return 0.0;
        }
        self.cells[self.slots[end - 1] as usize].n_sum
    }

    /// What column `col` has crossed up to depth `lambda` (cell units) inside the cell at
    /// unwrapped distance `d` slices from the first slice.
    #[inline]
    fn sums_at(&self, col: usize, d: i64, lambda: f32) -> Sums {
        if d < 0 {
            return NOTHING;
        }
        let rel = d.rem_euclid(self.geom.n as i64) as u32;
        let Some(k) = self.last_at_or_before(col, rel) else {
            return NOTHING;
        };
        let cell = &self.cells[k];
        let leaving = Sums::from(cell);
        if cell.slice != rel {
            return leaving;
        }
        // The cell itself is filled: the light entering it left the previous filled cell of
        // the column (if any, and not across the wrap).
        let entering = if rel > 0 && k > self.col_start[col] as usize {
            Sums::from(&self.cells[k - 1])
        } else {
            NOTHING
        };
        let share = cell.share_before(lambda);
        Sums {
            n: entering.n + (leaving.n - entering.n) * share,
            loss: entering.loss + (leaving.loss - entering.loss) * share,
            var: entering.var + (leaving.var - entering.var) * share,
        }
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
