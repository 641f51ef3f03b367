//! Placing a captured groom on wisp's head: a scale, a turn about +Y and an offset that put
//! the groom's roots on the head ellipsoid.
//!
//! The head is wisp's own ellipsoid (semi-axes `r`, centred at the head frame's origin).
//! Unknowns: one uniform scale `s` (the file's units and head size are unknown) and an offset
//! `o`, so that each root `p` maps to `q = (s·p + o) / r` with `|q| = 1`, and the rest of the
//! hair stays outside the head (`|q| ≥ 1`: a one-sided residual for sample points along the
//! strands; without it, 13% of the shared ponytail's guide particles start inside the head, up
//! to 28 mm deep, and the collision pushes them out as the hair settles). They are found by
//! Levenberg-Marquardt with Huber weights (δ = 5 mm), so a few roots that do not sit on a
//! scalp (a ponytail's tie, a beard) do not pull the fit; 4 unknowns, O(N) per iteration. The
//! start: the roots' x-extent across the head width, their top at the top of the head, centred
//! in x and z.
//!
//! The groom is assumed Y-up (TressFX and most DCC exports). Which way it faces is either
//! given or guessed: hair mostly hangs behind the head, so when the mean of all points lies in
//! front of the roots' centre (+Z is the face in wisp), the groom is turned by 180°.
//!
//! After the fit every root's distance to the surface is measured along its ray from the head
//! centre (`|s·p + o| · |1 − 1/|q||`); the caller refuses grooms whose roots are far from it.

use glam::{DVec3, Quat, Vec3};

/// Huber threshold of the fit's robust weights, metres.
const HUBER_M: f64 = 0.005;

/// The placement of a groom in the head frame:
/// `p_head = scale · (R_y(yaw) · upright · p_file) + offset_m`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    pub scale: f32,
    /// Turn about +Y applied before scaling, radians.
    pub yaw_rad: f32,
    pub offset_m: Vec3,
    /// Turn applied first: the one that stood the groom's character upright (a groom kept as
    /// authored on a Z-up model, `Motion::file_turn`); identity otherwise.
    pub upright: Quat,
}

impl Placement {
    pub fn apply(&self, p: Vec3) -> Vec3 {
        self.scale * (Quat::from_rotation_y(self.yaw_rad) * (self.upright * p)) + self.offset_m
    }
}

/// The turn that puts the hair mass behind the head (0 or π), from roots and all points.
pub fn guess_yaw_rad(roots: &[Vec3], all_points_mean: Vec3) -> f32 {
    let n = roots.len().max(1) as f32;
    let root_mean = roots.iter().copied().sum::<Vec3>() / n;
    if all_points_mean.z > root_mean.z {
        std::f32::consts::PI
    } else {
        0.0
    }
}

/// Fits scale and offset so the turned `roots` lie on the ellipsoid with semi-axes `radii_m`
/// and the points `hair` (samples along the strands, away from the roots) lie outside it.
/// `None` when the roots give no extent (all in one point) or the fit diverges.
pub fn fit_to_head(
    roots: &[Vec3],
    hair: &[Vec3],
    yaw_rad: f32,
    radii_m: Vec3,
) -> Option<Placement> {
    let turn = Quat::from_rotation_y(yaw_rad);
    let r = radii_m.as_dvec3();
    let problem = HeadFit {
        roots: roots.iter().map(|p| (turn * *p).as_dvec3()).collect(),
        hair: hair.iter().map(|p| (turn * *p).as_dvec3()).collect(),
        r,
        mean_r: (r.x + r.y + r.z) / 3.0,
    };
    let (s, o) = problem.start()?;
    let (s, o) = problem.solve(s, o);
    let placement = Placement {
        scale: s as f32,
        yaw_rad,
        offset_m: o.as_vec3(),
        upright: glam::Quat::IDENTITY,
    };
    (s.is_finite() && s > 0.0 && o.is_finite()).then_some(placement)
}

/// The least-squares problem of [`fit_to_head`]: turned roots and hair samples (file units)
/// against the head ellipsoid of semi-axes `r` (metres); unknowns scale `s` and offset `o`.
struct HeadFit {
    roots: Vec<DVec3>,
    hair: Vec<DVec3>,
    r: DVec3,
    /// Mean semi-axis: turns a residual in units of the radius into metres.
    mean_r: f64,
}

/// Levenberg-Marquardt iterate: the unknowns, their cost and the damping.
struct Iterate {
    s: f64,
    o: DVec3,
    cost: f64,
    lambda: f64,
}

impl HeadFit {
    /// The start (module doc): the roots' x-extent across the head width, their top at the top
    /// of the head, centred in x and z. `None` when the roots have no finite extent.
    fn start(&self) -> Option<(f64, DVec3)> {
        let (pts, r) = (&self.roots, self.r);
        let (lo, hi) = pts.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let extent = (hi - lo).max_element();
        if pts.is_empty() || !(extent > 0.0 && extent.is_finite()) {
            return None;
        }
        let wide = (hi.x - lo.x).max(0.25 * extent);
        let s = 2.0 * r.x / wide;
        let o = DVec3::new(
            -s * 0.5 * (lo.x + hi.x),
            r.y - s * hi.y,
            -s * 0.5 * (lo.z + hi.z),
        );
        Some((s, o))
    }

    /// Residual `(|q| − 1)·mean_r` (metres, approximately) of point `p`, with
    /// `q = (s·p + o) / r`, and its gradient in (s, o).
    fn residual(&self, s: f64, o: DVec3, p: DVec3) -> (f64, [f64; 4]) {
        let (r, mean_r) = (self.r, self.mean_r);
        let q = (s * p + o) / r;
        let len = q.length().max(1e-12);
        let dq = q / len / r; // d|q| / d(world point)
        let e = (len - 1.0) * mean_r;
        (
            e,
            [
                dq.dot(p) * mean_r,
                dq.x * mean_r,
                dq.y * mean_r,
                dq.z * mean_r,
            ],
        )
    }

    /// Every residual with its gradient: roots two-sided; hair samples only when inside the
    /// head.
    fn terms(&self, s: f64, o: DVec3) -> impl Iterator<Item = (f64, [f64; 4])> + '_ {
        let roots = self.roots.iter().map(move |p| self.residual(s, o, *p));
        let hair = self.hair.iter().map(move |p| {
            let (e, j) = self.residual(s, o, *p);
            if e < 0.0 { (e, j) } else { (0.0, [0.0; 4]) }
        });
        roots.chain(hair)
    }

    /// The Huber cost: `e²/2` within [`HUBER_M`], `δ(|e| − δ/2)` beyond.
    fn cost(&self, s: f64, o: DVec3) -> f64 {
        self.terms(s, o)
            .map(|(e, _)| {
                let e = e.abs();
                if e <= HUBER_M {
                    0.5 * e * e
                } else {
                    HUBER_M * (e - 0.5 * HUBER_M)
                }
            })
            .sum()
    }

    /// The Huber-weighted normal equations `A·d = b` at (s, o): `A = Σ w J Jᵀ`, `b = −Σ w J e`,
    /// with `w = 1` within [`HUBER_M`] and `δ/|e|` beyond.
    fn normal_equations(&self, s: f64, o: DVec3) -> ([[f64; 4]; 4], [f64; 4]) {
        let mut a = [[0.0f64; 4]; 4];
        let mut b = [0.0f64; 4];
        for (e, j) in self.terms(s, o) {
            let w = if e.abs() <= HUBER_M {
                1.0
            } else {
                HUBER_M / e.abs()
            };
            for u in 0..4 {
                b[u] -= w * j[u] * e;
                for v in 0..4 {
                    a[u][v] += w * j[u] * j[v];
                }
            }
        }
        (a, b)
    }

    /// Levenberg-Marquardt from (s, o): at most 100 iterations, each stopping the fit when no
    /// damped step lowers the cost (or the step is below 1e-12).
    fn solve(&self, s: f64, o: DVec3) -> (f64, DVec3) {
        let mut it = Iterate {
            s,
            o,
            cost: self.cost(s, o),
            lambda: 1e-3,
        };
        for _ in 0..100 {
            let (a, b) = self.normal_equations(it.s, it.o);
            if !self.step(&mut it, a, b) {
                break;
            }
        }
        (it.s, it.o)
    }

    /// One iteration: damps the diagonal of `a` by `1 + λ` until the step lowers the cost with
    /// a positive scale (λ × 0.3 after it, × 10 for each refusal, at most 10 tries). True when
    /// a step was taken and was not negligible.
    fn step(&self, it: &mut Iterate, a: [[f64; 4]; 4], b: [f64; 4]) -> bool {
        for _ in 0..10 {
            let mut m = a;
            for (u, row) in m.iter_mut().enumerate() {
                row[u] *= 1.0 + it.lambda;
                row[u] += 1e-18;
            }
            let Some(d) = solve4(m, b) else { break };
            let (s2, o2) = (it.s + d[0], it.o + DVec3::new(d[1], d[2], d[3]));
            let c2 = self.cost(s2, o2);
            if c2.is_finite() && c2 < it.cost && s2 > 0.0 {
                let step = d.iter().map(|x| x.abs()).fold(0.0, f64::max);
                it.s = s2;
                it.o = o2;
                it.cost = c2;
                it.lambda = (it.lambda * 0.3).max(1e-9);
                return step > 1e-12;
            }
            it.lambda *= 10.0;
        }
        false
    }
}

/// Distance in metres from a head-frame point to the ellipsoid surface, measured along the ray
/// from the centre.
pub fn surface_distance_m(p: Vec3, radii_m: Vec3) -> f32 {
    let q = (p / radii_m).length();
    if q > 0.0 {
        p.length() * (1.0 - 1.0 / q).abs()
    } else {
        radii_m.min_element()
    }
}

/// Gaussian elimination with partial pivoting on a 4×4 system.
pub(super) fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> Option<[f64; 4]> {
    for c in 0..4 {
        let piv = (c..4).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[piv][c].abs() < 1e-300 {
            return None;
        }
        a.swap(c, piv);
        b.swap(c, piv);
        let (pivot_row, pivot_b) = (a[c], b[c]);
        for i in c + 1..4 {
            let f = a[i][c] / pivot_row[c];
            for (x, p) in a[i][c..].iter_mut().zip(&pivot_row[c..]) {
                *x -= f * p;
            }
            b[i] -= f * pivot_b;
        }
    }
    let mut x = [0.0; 4];
    for c in (0..4).rev() {
        let s: f64 = (c + 1..4).map(|k| a[c][k] * x[k]).sum();
        x[c] = (b[c] - s) / a[c][c];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
mod tests;
