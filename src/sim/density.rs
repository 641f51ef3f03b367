//! Self-collision (Bertails, Ménier & Cani 2005 §4.1) from the simulator's own density grid.
//!
//! What: the hair keeps its volume without strand-against-strand tests. Guide particles are
//! pushed down the gradient of the hair's excess density, and their motion relative to the
//! hair around them is damped (hair-hair friction). Bertails: "hair self-collisions are
//! processed by applying repulsive forces from the center of each cell having a too high
//! density".
//!
//! How, at the start of every step (so the field is consistent with the positions it acts on,
//! with no lag beyond the step itself):
//!
//! 1. **Splat.** Every guide particle stands for the hair volume `V` of its wisp share over
//!    one link: `V = (strands per wisp × fibres per strand × π r_fibre² / 3) × link length ×
//!    curl length factor`. It is spread over the nodes of a lattice of spacing `h` (the mean
//!    link length, so one sample per particle gives a density that is smooth along the strand;
//!    at least 1/60 of the hair's reach, so the reachable cube fits [`MAX_NODES`]) in the head
//!    frame with the quadratic B-spline `N` (27 nodes, C¹): node
//!    volume fraction `φ_n = Σ_i V_i N_n(x_i) / h³` and `φ_n v_n = Σ_i V_i N_n(x_i) v_i / h³`
//!    (the volume-weighted node velocity v_n).
//! 2. **Repulsion** (Bertails §4.1; the paper gives no formula). The excess
//!    `e_n = max(φ_n − φ₀, 0)` over the threshold φ₀ = `density_threshold` is interpolated with
//!    the same B-spline, `ẽ(x) = Σ_n e_n N_n(x)`, and each particle is accelerated down its
//!    gradient, `a = −K ∇ẽ(x)` with `K = repulsion_m2_s2`. This is exactly `−∂E/∂x_i / m_i`
//!    for the energy `E = Σ_n ½ κ h³ e_n²` (κ = K × hair mass density), so the forces are
//!    conservative, equal and opposite between particles sharing nodes, and **continuous in
//!    position** (N is C¹): hair can come to rest where they balance gravity and bending.
//! 3. **Friction** (viscous, after Petrovic, Henne & Anderson 2005, "Volumetric Methods for
//!    Simulation and Rendering of Hair", §3: hair-hair friction as a smoothing of the velocity
//!    field; not in `shared/papers`). Each particle's velocity relaxes toward the hair's
//!    local mean velocity `v̄(x) = Σ N_n φ_n v_n / Σ N_n φ_n`, at the rate `c = hair_friction_per_s ·
//!    min(φ(x)/φ₀, 1)`: `v ← v̄ + (v − v̄) e^{−c dt}` (exact for the rate over the step, so the
//!    same at any step). A strand alone (φ ≪ φ₀) is not slowed, a wisp moving as a whole
//!    keeps its motion (v = v̄), and strands pressed together stop sliding against each other.
//!
//! Why its own grid rather than the light map (what Bertails does, the map being there
//! already): the map's cell-constant volume fraction pushes particles away from cell centres
//! with a force that jumps at every cell face and lags a whole frame (8 steps) behind the
//! positions, so hair at rest never settles (measured: 4.6% of the pixels changing between
//! every two frames of a still head). The grid here is built from the guides inside the step,
//! does not depend on the light direction or on the render strands, and is cheap: about 6,400
//! particles × 27 nodes.
//!
//! Why the head frame: hair at rest on a moving head is at rest on the lattice, so the
//! lattice-dependence of the B-spline density (one particle's density seen at its own position
//! varies by up to 1.54× with where it sits in a cell: Σ N² per axis is 0.50 at a cell face and
//! 0.58 at a node) does not change as the head turns.
//!
//! Determinism and cost: the splat runs on one thread in particle order, so every node sum has
//! one order; the per-particle queries only read and run in parallel with the guides.
//! Measured with callgrind (smooth, 1/240 s, one thread): the splat is 2.6 M instructions per
//! step, a fifth of the step; self-collision as a whole adds 1.5× to the rest of the step (a
//! 1/30 s frame: 97 M instructions against 40 M without). The splat stays serial: by slabs of
//! z layers (each node summed in one fixed order) it costs 6% more instructions for no gain
//! measurable on 2 cores, and with the weights computed in a parallel first pass the
//! simulation is 5% faster on 2 threads but 6% slower on 1, the frame unchanged. Memory: the
//! lattice covers the hair's bounding box in the head frame (about 5,000 nodes for the
//! presets), at most [`MAX_NODES`] (the spacing guarantees the reachable cube fits; a box over
//! it skips self-collision for the step and is counted in `StepStats`).

use glam::{Affine3A, IVec3, Mat3A, Vec3, Vec3A, Vec4};

/// Largest lattice, nodes (16 bytes each: 32 MB).
pub const MAX_NODES: usize = 1 << 21;

/// What one particle reads from the grid.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct HairAround {
    /// Hair volume fraction at the particle (B-spline interpolated), dimensionless.
    pub volume_fraction: f32,
    /// Gradient of the excess volume fraction ∇ẽ, world, 1/m.
    pub excess_gradient_per_m: Vec3A,
    /// Mean velocity of the hair around the particle v̄, world, m/s.
    pub mean_velocity_m_s: Vec3A,
}

/// Quadratic B-spline weights and their derivatives (per grid unit) along one axis, for a
/// coordinate `u` in grid units: nodes `base, base + 1, base + 2` with `base = ⌊u − ½⌋`.
#[inline]
fn weights(u: f32) -> (i32, [f32; 3], [f32; 3]) {
    let base = (u - 0.5).floor();
    let f = u - base; // in [0.5, 1.5)
    let a = 1.5 - f;
    let b = f - 1.0;
    let c = f - 0.5;
    (
        base as i32,
        [0.5 * a * a, 0.75 - b * b, 0.5 * c * c],
        [-a, -2.0 * b, c],
    )
}

/// The simulator's hair density lattice (see the module doc).
pub(crate) struct DensityGrid {
    /// Node spacing h, metres.
    cell_m: f32,
    /// World → grid coordinates (head frame divided by h) of the current step.
    to_grid: Affine3A,
    /// Head rotation: grid axes → world axes.
    rotation: Mat3A,
    /// Lowest node of the current box, and the box size in nodes.
    lo: IVec3,
    dims: IVec3,
    /// Per node: (φ, φ v) — the volume fraction and the volume-fraction-weighted velocity
    /// (m/s), so that interpolating them gives φ(x) and the hair's mean velocity
    /// Σ N φ v / Σ N φ with one multiply-add per node and no branch.
    nodes: Vec<Vec4>,
    /// Per node: the excess max(φ − threshold, 0).
    excess: Vec<f32>,
    /// False when the last build found nothing to splat or a box over [`MAX_NODES`].
    active: bool,
}

impl DensityGrid {
    /// An empty grid of node spacing `cell_m` (metres, > 0) for hair that stays within
    /// `reach_m` of the head frame's origin: the node storage for that whole cube is reserved
    /// here (at most [`MAX_NODES`]), so no step allocates.
    pub(crate) fn new(cell_m: f32, reach_m: f32) -> Self {
        let per_axis = (2.0 * f64::from(reach_m) / f64::from(cell_m)).ceil() + 4.0;
        let reserve = if per_axis.is_finite() && per_axis > 0.0 {
            (per_axis.powi(3) as usize).min(MAX_NODES)
        } else {
            0
        };
        Self {
            cell_m,
            to_grid: Affine3A::IDENTITY,
            rotation: Mat3A::IDENTITY,
            lo: IVec3::ZERO,
            dims: IVec3::ZERO,
            nodes: Vec::with_capacity(reserve),
            excess: Vec::with_capacity(reserve),
            active: false,
        }
    }

    /// Node spacing, metres.
    pub(crate) fn cell_m(&self) -> f32 {
        self.cell_m
    }

    /// Whether the last build produced a usable field.
    pub(crate) fn is_active(&self) -> bool {
        self.active
    }

    /// Nodes of the current box (0 when inactive).
    pub(crate) fn node_count(&self) -> usize {
        if self.active { self.nodes.len() } else { 0 }
    }

    /// Index of the first of the 27 nodes around a particle whose B-spline bases are `base`,
    /// or `None` when they are not all inside the box.
    #[inline]
    fn first_node(&self, base: IVec3) -> Option<usize> {
        let o = base - self.lo;
        let inside = o.cmpge(IVec3::ZERO).all() && (o + IVec3::splat(2)).cmplt(self.dims).all();
        inside.then(|| ((o.z * self.dims.y + o.y) * self.dims.x + o.x) as usize)
    }

    /// Splats every particle (world positions and velocities, guide-major with `ppg` particles
    /// per guide; particle volume `volume_m3[guide]`) into the lattice of the head frame
    /// `head`, then takes the excess over `threshold`. Non-finite particles are skipped.
    /// Returns whether the field is usable.
    pub(crate) fn build(
        &mut self,
        head: Affine3A,
        positions: &[Vec3],
        velocities: &[Vec3],
        ppg: usize,
        volume_m3: &[f32],
        threshold: f32,
    ) -> bool {
        self.active = false;
        if ppg == 0 || !head.is_finite() {
            return false;
        }
        self.rotation = head.matrix3;
        self.to_grid = Affine3A::from_scale(Vec3::splat(1.0 / self.cell_m)) * head.inverse();
        if !self.fit_box(positions) {
            return false;
        }
        self.splat(positions, velocities, ppg, volume_m3);
        self.excess.clear();
        self.excess
            .extend(self.nodes.iter().map(|n| (n.x - threshold).max(0.0)));
        self.active = true;
        true
    }

    /// Sets the box to the nodes the finite `positions` reach (their B-spline supports) and
    /// zeroes it. False when there is no finite position, one lies absurdly far (10⁶ cells),
    /// or the box would exceed [`MAX_NODES`].
    fn fit_box(&mut self, positions: &[Vec3]) -> bool {
        let (mut lo, mut hi) = (Vec3A::splat(f32::MAX), Vec3A::splat(f32::MIN));
        for p in positions {
            let g = self.to_grid.transform_point3a(Vec3A::from(*p));
            if g.is_finite() {
                lo = lo.min(g);
                hi = hi.max(g);
            }
        }
        if lo.x > hi.x || lo.abs().max_element() > 1e6 || hi.abs().max_element() > 1e6 {
            return false;
        }
        let lo_node = (lo - Vec3A::splat(0.5)).floor().as_ivec3();
        let hi_node = (hi - Vec3A::splat(0.5)).floor().as_ivec3() + IVec3::splat(2);
        let dims = hi_node - lo_node + IVec3::ONE;
        let count = dims.x as usize * dims.y as usize * dims.z as usize;
        if count > MAX_NODES {
            return false;
        }
        self.lo = lo_node;
        self.dims = dims;
        self.nodes.clear();
        self.nodes.resize(count, Vec4::ZERO);
        true
    }

    /// Adds every finite particle's (φ, φ v) to its 27 nodes, in particle order (module doc,
    /// step 1): already divided by h³, node = Σ N (V/h³)(1, v).
    fn splat(&mut self, positions: &[Vec3], velocities: &[Vec3], ppg: usize, volume_m3: &[f32]) {
        let dims = self.dims;
        let (row_y, row_z) = (dims.x as usize, dims.x as usize * dims.y as usize);
        let inv_cell_volume = 1.0 / (self.cell_m * self.cell_m * self.cell_m);
        for (guide, (ps, vs)) in positions
            .chunks(ppg)
            .zip(velocities.chunks(ppg))
            .enumerate()
        {
            let phi = volume_m3.get(guide).copied().unwrap_or(0.0) * inv_cell_volume;
            if phi.is_nan() || phi <= 0.0 {
                continue;
            }
            for (p, v) in ps.iter().zip(vs) {
                let g = self.to_grid.transform_point3a(Vec3A::from(*p));
                if !(g.is_finite() && v.is_finite()) {
                    continue;
                }
                let (bx, wx, _) = weights(g.x);
                let (by, wy, _) = weights(g.y);
                let (bz, wz, _) = weights(g.z);
                let Some(first) = self.first_node(IVec3::new(bx, by, bz)) else {
                    continue;
                };
                let carried = Vec4::new(phi, phi * v.x, phi * v.y, phi * v.z);
                for (c, wzc) in wz.iter().enumerate() {
                    for (b, wyb) in wy.iter().enumerate() {
                        let start = first + b * row_y + c * row_z;
                        let row = &mut self.nodes[start..start + 3];
                        let cw = carried * (wyb * wzc);
                        for (node, wxa) in row.iter_mut().zip(&wx) {
                            *node += cw * *wxa;
                        }
                    }
                }
            }
        }
    }

    /// The hair around world point `x` (see [`HairAround`]). All zero outside the box or when
    /// the grid is inactive.
    #[inline]
    pub(crate) fn around(&self, x: Vec3A) -> HairAround {
        let mut out = HairAround::default();
        if !self.active {
            return out;
        }
        let g = self.to_grid.transform_point3a(x);
        if !g.is_finite() {
            return out;
        }
        let (bx, wx, dx) = weights(g.x);
        let (by, wy, dy) = weights(g.y);
        let (bz, wz, dz) = weights(g.z);
        let Some(first) = self.first_node(IVec3::new(bx, by, bz)) else {
            return out;
        };
        let (row_y, row_z) = (self.dims.x as usize, (self.dims.x * self.dims.y) as usize);
        // Contract each row of three nodes along x first (the weights are separable), then
        // weight the nine rows by their y and z weights.
        let (wx3, dx3) = (Vec3A::from(wx), Vec3A::from(dx));
        let mut acc = Vec4::ZERO;
        let (mut gx, mut gy, mut gz) = (0.0f32, 0.0f32, 0.0f32);
        for c in 0..3 {
            for b in 0..3 {
                let start = first + b * row_y + c * row_z;
                let nodes = &self.nodes[start..start + 3];
                let e = &self.excess[start..start + 3];
                let e3 = Vec3A::new(e[0], e[1], e[2]);
                let row = nodes[0] * wx[0] + nodes[1] * wx[1] + nodes[2] * wx[2];
                let wyz = wy[b] * wz[c];
                acc += row * wyz;
                let (e_w, e_d) = (e3.dot(wx3), e3.dot(dx3));
                gx += e_d * wyz;
                gy += e_w * (dy[b] * wz[c]);
                gz += e_w * (wy[b] * dz[c]);
            }
        }
        let grad = Vec3A::new(gx, gy, gz);
        out.volume_fraction = acc.x;
        // ∇ in world metres: grid units are head-frame metres / h, and the head frame is
        // rotated by `rotation`.
        out.excess_gradient_per_m = self.rotation * grad * (1.0 / self.cell_m);
        out.mean_velocity_m_s = if acc.x > 0.0 {
            Vec3A::new(acc.y, acc.z, acc.w) / acc.x
        } else {
            Vec3A::ZERO
        };
        out
    }
}

#[cfg(test)]
mod tests;
