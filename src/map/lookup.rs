//! Reading the map: the light reaching a point (Bertails 2005 §3.3, read exactly along the
//! light instead of filtered) and the cell density used by self-collision (§4.1).
//!
//! Along the light, a column gives the sums a ray has crossed up to the point's depth: those
//! entering the point's cell plus the share of the cell's own crossings in front of the point,
//!
//!   S(x) = S_in + (S_out − S_in)·share(λ),  λ = x/ds − ⌊x/ds⌋ (`Cell::share_before`),
//!
//! turned into the direct fraction exp(−n) and T_f = exp(−loss) per column. Across the light,
//! the four columns nearest to the point are blended bilinearly between their centres, the
//! weights of the fill's splat. Only the hair's own extent is read, so the modulo indexing
//! never aliases distant hair into a lookup. A point the camera sees averages the sums over
//! shifts toward the light (`seen.rs`).

use super::occluders::NO_SOLIDS;
use super::{Cell, LightMap, OccluderGrid, on_map};
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

/// What a column has crossed around one cell: the same sums at every depth (an empty cell),
/// or the sums entering and leaving a filled cell, its depth CDF telling how they grow inside.
enum Span<'a> {
    Whole(Sums),
    Inside {
        entering: Sums,
        leaving: Sums,
        cell: &'a Cell,
    },
}

impl Span<'_> {
    /// The sums at depth `lambda` (cell units from the light-side face) inside the cell.
    #[inline]
    fn at(&self, lambda: f32) -> Sums {
        match *self {
            Span::Whole(s) => s,
            Span::Inside {
                entering,
                leaving,
                cell,
            } => {
                let share = cell.share_before(lambda);
                Sums {
                    n: entering.n + (leaving.n - entering.n) * share,
                    loss: entering.loss + (leaving.loss - entering.loss) * share,
                    var: entering.var + (leaving.var - entering.var) * share,
                }
            }
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
        self.light_past(&NO_SOLIDS, p)
    }

    /// [`Self::light_at`] past the opaque `solids` too (their grid in this map's frame).
    pub(crate) fn light_past(&self, solids: &OccluderGrid, p: Vec3) -> LightAtPoint {
        self.light_with_taps(solids, p, &[(1.0, 0.0)])
    }

    /// The light at `p` with the sums along the light averaged over `taps` (weight, shift
    /// toward the light in cells); `crossings_behind` from the point itself.
    #[inline]
    pub(super) fn light_with_taps(
        &self,
        solids: &OccluderGrid,
        p: Vec3,
        taps: &[(f32, f32)],
    ) -> LightAtPoint {
        let m = self.proj.point(p);
        let c = m * self.inv_cell;
        if !on_map(c) {
            return LightAtPoint::UNSHADOWED;
        }
        let visible = solids.visibility(m);
        let (yj, zk) = (c.y - 0.5, c.z - 0.5);
        let (j0, k0) = (yj.floor(), zk.floor());
        let (wy, wz) = (yj - j0, zk - k0);
        let (j0, k0) = (j0 as i64, k0 as i64);
        // Beyond the hair's last slice a point receives its column's whole sums (what the
        // modulo indexing holds further on is other slices' hair).
        let last = self.hair_hi[0].saturating_sub(self.first_slice);
        let depth = |x: f32| {
            let i = x.floor();
            let d = i as i64 - self.first_slice;
            if d > last { (last, 1.0) } else { (d, x - i) }
        };
        let here = depth(c.x);
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
                // The point's cell is found once; taps inside it (the common case: shifts
                // are a fraction of a cell) only re-read its depth CDF.
                let span = self.span_at(col, here.0);
                let s = span.at(here.1);
                let (n, loss) = if taps.len() == 1 && taps[0].1 == 0.0 {
                    (s.n, s.loss)
                } else {
                    taps.iter()
                        .fold((0.0, Vec3::ZERO), |(n, loss), (tw, shift)| {
                            let (d, lambda) = depth(c.x - shift);
                            let t = if d == here.0 {
                                span.at(lambda)
                            } else {
                                self.span_at(col, d).at(lambda)
                            };
                            (n + tw * t.n, loss + *tw * t.loss)
                        })
                };
                direct += w * (-n).exp();
                tf += w * (-loss).exp();
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
    /// the running sum of its last filled cell.
    #[inline]
    fn column_total(&self, col: usize) -> f32 {
        self.index[col].total_n
    }

    /// What column `col` has crossed around the cell at unwrapped distance `d` slices from
    /// the first slice: read at a depth inside that cell with [`Span::at`].
    #[inline]
    fn span_at(&self, col: usize, d: i64) -> Span<'_> {
        if d < 0 {
            return Span::Whole(NOTHING);
        }
        let rel = d.rem_euclid(self.geom.n as i64) as u32;
        let Some(k) = self.last_at_or_before(col, rel) else {
            return Span::Whole(NOTHING);
        };
        let cell = &self.cells[k];
        let leaving = Sums::from(cell);
        if cell.slice != rel {
            return Span::Whole(leaving);
        }
        // The cell itself is filled: the light entering it left the previous filled cell of
        // the column (if any, and not across the wrap).
        let entering = if rel > 0 && k > self.index[col].start as usize {
            Sums::from(&self.cells[k - 1])
        } else {
            NOTHING
        };
        Span::Inside {
            entering,
            leaving,
            cell,
        }
    }

    /// Hair volume fraction of the cell holding world point `p` and that cell's centre (world),
    /// or `None` when the cell is empty (Bertails §4.1 self-collision).
    pub fn cell_density(&self, p: Vec3) -> Option<(f32, Vec3)> {
        let c = self.cell_coords(p);
        if !on_map(c) {
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
        let centre = self.proj.to_world((f + Vec3::splat(0.5)) / self.inv_cell);
        Some((cell.volume_fraction, centre))
    }
}
