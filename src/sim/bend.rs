//! Bending toward the rest shape: the per-step pull and damping constants, the transported
//! frame's minimal rotation, and the bending damping pass.
//!
//! What: `guide_step.rs` pulls each link toward its rest bend relative to its parent link,
//! expressed in a frame parallel-transported down the strand with [`rotation_arc`], then damps
//! the links' relative rotation with [`damp_bending`]. This file holds those pieces and the map
//! from the JSON parameters to per-step factors.
//!
//! # The bending of one link is a damped oscillator, the same at any step
//! Seen from its parent, a link's deviation `e` from its rest bend follows, per step of `dt`
//! (pull by `k` in `guide_step.rs`, then damping of the relative velocity by `κ` here):
//!
//! `e' = (1 − k)(e + u)`,  `u' = (1 − κ)(e' − e)`   (`u` = relative velocity × dt)
//!
//! a linear map with trace `(1 − k)(2 − κ)` and determinant `(1 − k)(1 − κ)`. The continuous
//! oscillator `ë + 2ζω ė + ω² e = 0` advanced exactly over `dt` has the eigenvalues
//! `exp((−ζ ± √(ζ² − 1)) ω dt)`, i.e. trace `T` and determinant `D = exp(−2ζω dt)`.
//! Matching both gives the per-step factors
//!
//! `k = 1 − T + D`,  `κ = 1 − D / (T − D)`
//!
//! so every step size advances the isolated link exactly as the same continuous oscillator
//! would: the bending frequency ω and damping ratio ζ are properties of the hair, not of the
//! step. For ζ = 1 (critical, the default) this is `k = (1 − e^{−ωdt})²`,
//! `1 − κ = e^{−ωdt} / (2 − e^{−ωdt})`; for small `ω dt`, `k → (ω dt)²` (a spring of
//! angular frequency ω) and `κ → 2ζω dt` (a damping rate 2ζω).
//!
//! The stiffness in the JSON, `s ∈ [0, 1]`, is the pull per step `k = s` at the reference
//! step 1/240 s: ω is chosen so that the critically damped oscillator's pull over 1/240 s is
//! `s`, `ω = −ln(1 − √s) / (1/240 s)` (s = 0.25: 166 rad/s; 0.6: 357 rad/s; 0 limp, 1 rigid),
//! and every other step gives the same oscillator. Why not keep `s` per step and scale it,
//! `k = 1 − (1 − s)^(dt/(1/240 s))`: that makes ω grow as 1/√dt, so the hair is twice as stiff
//! at 1/960 s as at 1/240 s, the largest step dependence measured (ACCURACY.md §4 runs the
//! steps).
//!
//! Why the bending needs damping at all: the pull acts on the child only, so link i is an
//! oscillator driven by link i−1 with no reaction back; with only air damping its resonance
//! gain is ω/c ≈ 100 per link, cascading over 13 links (measured without it: tips whirl at
//! 17 m/s under a still head). Damping the relative rotation bounds the gain near 1 and leaves
//! a rigid swing of the whole strand (equal angular velocities) untouched.

use glam::{Quat, Vec3, Vec3A};

use super::REFERENCE_STEP_S;

/// Angular frequency ω (rad/s) of the bending oscillator for a stiffness `s` in [0, 1]
/// (see the module doc); infinite for `s >= 1`.
pub fn bending_frequency_rad_s(stiffness: f32) -> f64 {
    let s = f64::from(stiffness).clamp(0.0, 1.0);
    if s >= 1.0 {
        return f64::INFINITY;
    }
    -(1.0 - s.sqrt()).ln() / f64::from(REFERENCE_STEP_S)
}

/// Per-step pull `k` and relative-velocity damping `κ`, both in [0, 1], of the bending
/// oscillator of frequency `omega_rad_s` and damping ratio `zeta` advanced over `dt_s`
/// (see the module doc for the derivation).
pub(crate) fn step_factors(omega_rad_s: f64, zeta: f64, dt_s: f64) -> (f32, f32) {
    let x = omega_rad_s * dt_s;
    if !x.is_finite() {
        return (1.0, 1.0);
    }
    if x.is_nan() || x <= 0.0 {
        return (0.0, 0.0);
    }
    let zeta = zeta.max(0.0);
    // Trace of the exact step map: the sum of its two eigenvalues, written so that no
    // exponential overflows (both terms decay for ζ >= 1).
    let trace = if zeta < 1.0 {
        2.0 * (-zeta * x).exp() * (x * (1.0 - zeta * zeta).sqrt()).cos()
    } else {
        let r = (zeta * zeta - 1.0).sqrt();
        (-(zeta - r) * x).exp() + (-(zeta + r) * x).exp()
    };
    let det = (-2.0 * zeta * x).exp();
    let k = (1.0 - trace + det).clamp(0.0, 1.0);
    // T − D <= 0 (an under-damped oscillator not resolved by the step): no pull survives
    // a step, so the relative velocity is removed entirely. κ < 0 (anti-damping, at ζ near 0)
    // is clamped to 0: the step is then slightly more damped than the oscillator.
    let kappa = if trace - det > 0.0 {
        (1.0 - det / (trace - det)).clamp(0.0, 1.0)
    } else {
        1.0
    };
    (k as f32, kappa as f32)
}

/// The minimal rotation taking unit `a` to unit `b`: the quaternion (a × b, 1 + a·b),
/// normalised, which is (sin(θ/2) axis, cos(θ/2)) by the half-angle identities. Near
/// `b = −a` (1 + a·b → 0, no unique axis) it turns by π about any axis perpendicular to `a`.
/// Cheaper than `Quat::from_rotation_arc` (one square root, no branches in the common case),
/// which took 18% of a step in the profile.
#[inline]
pub(crate) fn rotation_arc(a: Vec3A, b: Vec3A) -> Quat {
    let w = 1.0 + a.dot(b);
    if w > 1e-6 {
        let axis = a.cross(b);
        Quat::from_xyzw(axis.x, axis.y, axis.z, w).normalize()
    } else {
        let axis = a.any_orthonormal_vector();
        Quat::from_xyzw(axis.x, axis.y, axis.z, 0.0)
    }
}

/// The weights of the exact one-sided damping over one step (see [`damp_bending`]): the
/// Poisson probabilities `P_m = e^{−x} x^m / m!` for `x = −ln(1 − kappa)` (the step's damping
/// `c dt`), for m = 0.. until they fall below 1e-9 past their peak (the rest of the mass goes
/// to the link just beyond, see [`damp_bending`]), at most `max_len` of them. `kappa >= 1`
/// gives no weights (every link takes its farthest ancestor's rotation); `kappa <= 0` gives
/// `[1]` (no damping).
pub(crate) fn damping_weights(kappa: f32, max_len: usize) -> Vec<f32> {
    let kappa = f64::from(kappa);
    if kappa.is_nan() || kappa <= 0.0 {
        return vec![1.0];
    }
    if kappa >= 1.0 {
        return Vec::new();
    }
    let x = -(1.0 - kappa).ln();
    let mut w = Vec::new();
    let mut p = (-x).exp();
    let mut m = 0usize;
    while w.len() < max_len.max(1) {
        w.push(p as f32);
        m += 1;
        p *= x / m as f64;
        if m as f64 > x && p < 1e-9 {
            break;
        }
    }
    w
}

/// Damps the links' angular velocities relative to their parents, exactly over the step,
/// keeping the radial (along-link) relative velocities. With `rᵢ = pᵢ − pᵢ₋₁` and
/// `wᵢ = vᵢ − vᵢ₋₁`, link i turns at `Ωᵢ = rᵢ × wᵢ / |rᵢ|²`. The damping
/// `dΩᵢ/dt = −c (Ωᵢ − Ωᵢ₋₁)` (each link toward its parent, link 1 the kinematic root segment,
/// held over the step) is a chain of first-order lags whose exact solution after `x = c dt` is
/// `Ω'ᵢ = Σₘ Pₘ Ωᵢ₋ₘ` with the Poisson weights `Pₘ = e^{−x} xᵐ / m!` of [`damping_weights`],
/// the mass they leave going to the last link reached (for link i, the root segment). Velocities
/// are rebuilt root to tip, `vᵢ = v'ᵢ₋₁ + (wᵢ·r̂ᵢ) r̂ᵢ + Ω'ᵢ × rᵢ`, so a strand swinging or
/// turning rigidly is untouched (all Ωᵢ equal, weights summing to 1) and only bending motion
/// loses energy.
///
/// Why exact rather than one damping factor per link applied root to tip,
/// `Ω'ᵢ = Ωᵢ − κ (Ωᵢ − Ω'ᵢ₋₁)`: that sweep hands each link its parent's already damped
/// rotation within the same step, weights `(1 − κ) κᵐ` instead of `Pₘ`, so a rotation travels
/// down the chain at a speed set by the step, not by c. Measured on the dance: it makes the
/// coarse-step hair lag the converged motion by about 6 steps, half of the error at 1/240 s
/// (tip error 19.5 mm RMS with it, 10.0 mm with the exact weights).
pub(crate) fn damp_bending(pos: &[Vec3], vel: &mut [Vec3], weights: &[f32]) {
    let n = pos.len().min(vel.len());
    if n < 3 {
        return;
    }
    // The undamped Ω of the last RING links (the weights reach at most RING − 1 links back;
    // `damping_weights` stops far earlier for any κ below 1 in f32).
    const RING: usize = 64;
    let mut ring = [Vec3A::ZERO; RING];
    let (omega_root, _) = link_motion(pos[0], pos[1], vel[0], vel[1]);
    ring[1] = omega_root;
    let reach = weights.len().min(RING - 1);
    let mut v_parent_old = vel[1];
    let mut v_parent_new = Vec3A::from(vel[1]);
    for i in 2..n {
        let (omega, radial) = link_motion(pos[i - 1], pos[i], v_parent_old, vel[i]);
        v_parent_old = vel[i];
        ring[i % RING] = omega;
        let damped = if weights.is_empty() {
            // κ = 1: every link takes the root segment's rotation.
            omega_root
        } else {
            // Links i, i − 1, … with weights P₀, P₁, …; the mass left goes to the last link
            // reached (the root segment unless the weights end first).
            let window = (i - 1).min(reach);
            let mut acc = Vec3A::ZERO;
            let mut mass = 0.0f32;
            for (m, p) in weights[..window].iter().enumerate() {
                acc += ring[(i - m) % RING] * *p;
                mass += *p;
            }
            acc + ring[(i - window) % RING] * (1.0 - mass).max(0.0)
        };
        let r = Vec3A::from(pos[i]) - Vec3A::from(pos[i - 1]);
        let v_new = v_parent_new + radial + damped.cross(r);
        vel[i] = Vec3::from(v_new);
        v_parent_new = v_new;
    }
}

/// Angular velocity `r × w / |r|²` of the link from `a` to `b` (velocities `va`, `vb`) and the
/// radial part of the relative velocity `w = vb − va`; a degenerate link has no rotation and
/// keeps all of `w` as radial.
#[inline]
fn link_motion(a: Vec3, b: Vec3, va: Vec3, vb: Vec3) -> (Vec3A, Vec3A) {
    let r = Vec3A::from(b) - Vec3A::from(a);
    let w = Vec3A::from(vb) - Vec3A::from(va);
    let l2 = r.length_squared();
    if l2 > 0.0 && l2.is_finite() {
        (r.cross(w) / l2, r * (w.dot(r) / l2))
    } else {
        (Vec3A::ZERO, w)
    }
}

#[cfg(test)]
mod tests;
