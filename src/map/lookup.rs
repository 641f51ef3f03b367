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
//! never aliases distant hair into a lookup. A seen point averages the sums over shifts
//! toward the light (the opposition effect, [`LightMap::light_at_seen`]), and with contact
//! shadows takes the fibres of a window in front of it exactly
//! ([`LightMap::light_at_vertex_seen`]).

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

/// T_f below which a point is dark enough that contact shadows are not computed.
const DARK: f32 = 1e-3;

/// Expected crossings (the map's) a contact window holds at most.
/// Measured on smooth × 12 strands of one fibre, 3000 vertices: T_f MAE 0.0066 at 16, 0.0067
/// at 8, 0.0070 at 4; shading smooth × 4 on 2 threads 6.9, 7.1 and 5.4 s.
const CONTACT_CROSSINGS: f32 = 4.0;

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

    /// The light reaching world point `p` *on a fibre the camera sees* from direction
    /// `to_eye` (from `p` toward the eye), for fibres of radius `fibre_radius_m`.
    ///
    /// When the light comes from near the camera, the ray toward the light and the ray toward
    /// the eye pass through the same fibres for a while: the two tubes of width 2r around them
    /// overlap over a length s_c = 2r / sin g (g: the angle between them), the overlap falling
    /// linearly from full at the point to none at s_c. Given that the view ray is clear (the
    /// fibre is seen), the light ray is clear where they overlap, so the light crosses only the
    /// fibres outside the shared part: P(lit | seen) = exp(−n̄) with n̄ the crossings in front
    /// of the point *averaged over shifts s ∈ [0, s_c] toward the light* (integrating the
    /// linear overlap by parts). This is the opposition effect ("hot spot") of fibre media:
    /// with the light exactly behind the camera every seen fibre is lit (g = 0: s_c = ∞), and it
    /// fades within a few degrees (r = 40 µm: s_c = 0.46 mm at 10°). The average is a
    /// two-point Gauss rule; beyond g where s_c is under a twentieth of a sub-slice, this is
    /// [`Self::light_at`] exactly (no extra lookups). `crossings_behind` is unconditional.
    pub fn light_at_seen(
        &self,
        p: Vec3,
        to_eye: Vec3,
        tangent: Vec3,
        fiber_radius_m: f32,
    ) -> LightAtPoint {
        self.light_at_seen_past(&NO_SOLIDS, p, to_eye, tangent, fiber_radius_m)
    }

    /// [`Self::light_at_seen`] past the opaque `solids` too.
    pub(crate) fn light_at_seen_past(
        &self,
        solids: &OccluderGrid,
        p: Vec3,
        to_eye: Vec3,
        tangent: Vec3,
        fiber_radius_m: f32,
    ) -> LightAtPoint {
        let s_c = self.shared_tube_m(p, to_eye, tangent, fiber_radius_m);
        let min_shift = 0.05 * self.geom.ds_m / crate::map::DEPTH_BINS as f32;
        if s_c <= min_shift {
            return self.light_past(solids, p);
        }
        // Gauss–Legendre nodes on [0, s_c]: s_c (1/2 ∓ 1/(2√3)), in cells.
        let h = 0.5 / 3f32.sqrt();
        let sc = s_c * self.inv_ds;
        self.light_with_taps(solids, p, &[(0.5, sc * (0.5 - h)), (0.5, sc * (0.5 + h))])
    }

    /// [`Self::light_at_seen`] for render-strand point `vertex` at `p`, with the fibres in the
    /// contact window in front of it taken exactly when the map has contact shadows
    /// ([`Self::build_contact`]; `super::contact`): the map is read at the window's far end
    /// (the light that reaches the window) and multiplied by what the real fibres inside the
    /// window let through. The opposition effect (the camera sees the point, and its view ray
    /// shares the light ray's fibres over a length s_c) applies on both sides: a fibre at a
    /// distance s in front counts with weight min(s, s_c)/s_c, inside the window as each real
    /// fibre's probability of being there (`ContactShadows::near_light`), beyond it as the far
    /// sums averaged with weight δ/s_c at the window's end and over shifts in [δ, s_c] (two
    /// Gauss nodes) with the rest. The exact fibres alone would not do it: the view ray crosses the
    /// same fibres near the point as the light ray, so with the light near the camera a seen
    /// point is lit more often than the exact light of an unseen one says (measured, with piece
    /// averages: dense blond, front light, single scattering 0.71 of the path tracer without
    /// this, 0.91 with the map alone).
    /// Points darker than 1e-3 on the map are not queried: they read [`Self::light_at_seen`].
    pub fn light_at_vertex_seen(
        &self,
        vertex: usize,
        p: Vec3,
        to_eye: Vec3,
        tangent: Vec3,
        fiber_radius_m: f32,
    ) -> LightAtPoint {
        self.light_at_vertex_seen_past(&NO_SOLIDS, vertex, p, to_eye, tangent, fiber_radius_m)
    }

    /// [`Self::light_at_vertex_seen`] past the opaque `solids` too.
    pub(crate) fn light_at_vertex_seen_past(
        &self,
        solids: &OccluderGrid,
        vertex: usize,
        p: Vec3,
        to_eye: Vec3,
        tangent: Vec3,
        fiber_radius_m: f32,
    ) -> LightAtPoint {
        let Some(contact) = &self.contact else {
            return self.light_at_seen_past(solids, p, to_eye, tangent, fiber_radius_m);
        };
        // Where the map says the point itself is dark, the exact window cannot make it
        // noticeably brighter (the map is calibrated there, ACCURACY.md §1): the map's value
        // stands, given the camera sees the point as everywhere else.
        let here = self.light_past(solids, p);
        if here.tf.max_element() <= DARK {
            return self.light_at_seen_past(solids, p, to_eye, tangent, fiber_radius_m);
        }
        // The window holds about CONTACT_CROSSINGS of the map's expected crossings in front of
        // the point (all of them up to the full window near the lit surface; a shorter window
        // deeper in, where hundreds of fibres would otherwise be taken one by one).
        let n_here = -here.direct_fraction.max(1e-30).ln();
        let delta = contact.window_m() * (CONTACT_CROSSINGS / n_here.max(CONTACT_CROSSINGS));
        let to_light = self.proj.toward_light(p);
        let far_p = p + to_light * delta;
        let s_c = self.shared_tube_m(p, to_eye, tangent, fiber_radius_m);
        let far = if s_c <= delta {
            self.light_past(solids, far_p)
        } else {
            let h = 0.5 / 3f32.sqrt();
            let rest = (s_c - delta) * self.inv_ds;
            let w = 0.5 * (s_c - delta) / s_c;
            self.light_with_taps(
                solids,
                far_p,
                &[
                    (delta / s_c, 0.0),
                    (w, rest * (0.5 - h)),
                    (w, rest * (0.5 + h)),
                ],
            )
        };
        if far.tf.max_element() <= DARK {
            return far;
        }
        let near = contact.near_light(vertex, delta, s_c);
        LightAtPoint {
            direct_fraction: (far.direct_fraction * near.direct_fraction).clamp(0.0, 1.0),
            tf: (far.tf * near.tf).clamp(Vec3::ZERO, Vec3::ONE),
            sigma_f2: far.sigma_f2 + near.sigma_f2,
            crossings_behind: (far.crossings_behind - near.crossings).max(0.0),
        }
    }

    /// The length s_c over which the ray toward the light and the ray toward the eye share
    /// the fibres they pass (module doc of [`Self::light_at_seen`]), metres; 0 when they
    /// share none.
    fn shared_tube_m(&self, p: Vec3, to_eye: Vec3, tangent: Vec3, fiber_radius_m: f32) -> f32 {
        let to_light = self.proj.toward_light(p);
        let v = to_eye.normalize_or_zero();
        let cos_g = v.dot(to_light);
        // Across the light: the direction in which the view ray leaves the light ray, and the
        // direction of the hair (the vertex's own, as locally the hair runs together).
        let sep = (v - to_light * cos_g).normalize_or_zero();
        let along = (tangent - to_light * tangent.dot(to_light)).normalize_or_zero();
        // A long fibre blocks both rays while their separation across it is under 2r: the
        // separation grows as s·sin g, and only its part across the fibre counts (|sin φ|),
        // floored at 0.1 for the spread of directions around the vertex's own.
        let sin_g = (1.0 - cos_g * cos_g).max(0.0).sqrt();
        let across = sep.cross(along).length().max(0.1);
        let limit = 2.0 * self.geom.n as f32 * self.geom.ds_m;
        // Opposite half-spaces (g ≥ 90°): the rays share only the point itself.
        let s_c = if cos_g > 0.0 {
            (2.0 * fiber_radius_m / (sin_g * across).max(1e-9)).min(limit)
        } else {
            0.0
        };
        if s_c.is_nan() { 0.0 } else { s_c }
    }

    /// The light at `p` with the sums along the light averaged over `taps` (weight, shift
    /// toward the light in cells); `crossings_behind` from the point itself.
    #[inline]
    fn light_with_taps(&self, solids: &OccluderGrid, p: Vec3, taps: &[(f32, f32)]) -> LightAtPoint {
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
