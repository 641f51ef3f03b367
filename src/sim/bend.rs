//! Bending toward the rest shape: the per-step pull and damping constants, the transported
//! frame's minimal rotation, and the bending damping pass.
//!
//! What: `step.rs` pulls each link toward its rest bend relative to its parent link, expressed
//! in a frame parallel-transported down the strand with [`rotation_arc`], then damps the
//! links' relative rotation with [`damp_bending`]. This file holds those pieces and the map
//! from the JSON parameters to per-step factors.
//!
//! # The bending of one link is a damped oscillator, the same at any step
//! Seen from its parent, a link's deviation `e` from its rest bend follows, per step of `dt`
//! (pull by `k` in `step.rs`, then damping of the relative velocity by `κ` here):
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
//! The stiffness in the JSON, `s ∈ [0, 1]`, keeps its old meaning at the reference step
//! 1/240 s, where the pull was `k = s` per step: ω is chosen so that the critically damped
//! oscillator's pull over 1/240 s is `s`, `ω = −ln(1 − √s) / (1/240 s)` (s = 0.25: 166 rad/s;
//! 0.6: 357 rad/s; 0 limp, 1 rigid). At 1/240 s the factors are therefore what they were, and
//! other steps now give the same oscillator instead of a stiffer one at smaller steps (the old
//! `k = 1 − (1 − s)^(dt/(1/240 s))` made ω grow as 1/√dt: the hair was twice as stiff at
//! 1/960 s as at 1/240 s, which was the largest step dependence measured, see
//! `NOTES-sim-quality.md`).
//!
//! Why the bending needs damping at all: the pull acts on the child only, so link i is an
//! oscillator driven by link i−1 with no reaction back; with only air damping its resonance
//! gain is ω/c ≈ 100 per link, cascading over 13 links (measured before: tips whirled at
//! 17 m/s under a still head). Damping the relative rotation bounds the gain near 1 and leaves
//! a rigid swing of the whole strand (equal angular velocities) untouched.

use glam::{Quat, Vec3, Vec3A};

/// Reference step that `bending_stiffness` is defined at, seconds.
pub const BENDING_REFERENCE_STEP_S: f32 = 1.0 / 240.0;

/// Angular frequency ω (rad/s) of the bending oscillator for a stiffness `s` in [0, 1]
/// (see the module doc); infinite for `s >= 1`.
pub fn bending_frequency_rad_s(stiffness: f32) -> f64 {
    let s = f64::from(stiffness).clamp(0.0, 1.0);
    if s >= 1.0 {
        return f64::INFINITY;
    }
    -(1.0 - s.sqrt()).ln() / f64::from(BENDING_REFERENCE_STEP_S)
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

/// Damps each link's angular velocity relative to its parent link's by the factor `kappa` per
/// step, keeping the radial (along-link) relative velocity: with `rᵢ = pᵢ − pᵢ₋₁` and
/// `wᵢ = vᵢ − vᵢ₋₁`, the link's angular velocity is `Ωᵢ = rᵢ × wᵢ / |rᵢ|²`; it becomes
/// `Ωᵢ − kappa (Ωᵢ − Ωᵢ₋₁)` and the velocity is rebuilt as
/// `vᵢ = v'ᵢ₋₁ + (wᵢ·r̂ᵢ) r̂ᵢ + Ω'ᵢ × rᵢ` from the already damped parent, so a strand swinging or
/// turning rigidly is untouched (all Ωᵢ equal) and only bending motion loses energy.
pub(crate) fn damp_bending(pos: &[Vec3], vel: &mut [Vec3], kappa: f32) {
    let r0 = Vec3A::from(pos[1]) - Vec3A::from(pos[0]);
    let l0 = r0.length_squared();
    let mut omega_parent = if l0 > 0.0 {
        r0.cross(Vec3A::from(vel[1]) - Vec3A::from(vel[0])) / l0
    } else {
        Vec3A::ZERO
    };
    let mut v_parent_new = Vec3A::from(vel[1]);
    let mut v_parent_old = v_parent_new;
    for i in 2..pos.len() {
        let r = Vec3A::from(pos[i]) - Vec3A::from(pos[i - 1]);
        let l2 = r.length_squared();
        let v = Vec3A::from(vel[i]);
        let w = v - v_parent_old;
        v_parent_old = v;
        if l2.is_nan() || l2 <= 0.0 {
            v_parent_new = v;
            continue;
        }
        let radial = r * (w.dot(r) / l2);
        let omega = r.cross(w) / l2;
        let omega_new = omega - (omega - omega_parent) * kappa;
        let v_new = v_parent_new + radial + omega_new.cross(r);
        vel[i] = Vec3::from(v_new);
        v_parent_new = v_new;
        omega_parent = omega_new;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_arc_maps_a_to_b_including_opposite_vectors() {
        let pairs = [
            (Vec3A::X, Vec3A::Y),
            (Vec3A::new(0.6, 0.8, 0.0), Vec3A::new(0.0, 0.6, 0.8)),
            (Vec3A::Z, Vec3A::Z),
            (Vec3A::Y, Vec3A::NEG_Y),
        ];
        for (a, b) in pairs {
            let q = rotation_arc(a, b);
            assert!((q.length() - 1.0).abs() < 1e-6);
            assert!((q * a - b).length() < 1e-5, "{a} -> {b}: got {}", q * a);
        }
    }

    /// A three-link chain along +Y from the origin.
    fn chain() -> Vec<Vec3> {
        (0..4)
            .map(|i| Vec3::new(0.0, i as f32 * 0.02, 0.0))
            .collect()
    }

    #[test]
    fn bending_damping_keeps_rigid_rotation_and_damps_relative_rotation() {
        let pos = chain();
        // Rigid rotation about Z at 3 rad/s through the origin: v = ω × p.
        let omega = Vec3::new(0.0, 0.0, 3.0);
        let mut vel: Vec<Vec3> = pos.iter().map(|p| omega.cross(*p)).collect();
        let rigid = vel.clone();
        damp_bending(&pos, &mut vel, 0.6);
        for (v, r) in vel.iter().zip(&rigid) {
            assert!((*v - *r).length() < 1e-6);
        }
        // Only the last link bends (its tip moves sideways relative to a still chain).
        let mut vel = vec![Vec3::ZERO; 4];
        vel[3] = Vec3::new(1.0, 0.0, 0.0);
        damp_bending(&pos, &mut vel, 0.6);
        assert!((vel[3].x - 0.4).abs() < 1e-6, "{}", vel[3]);
        // Stretching velocity along the link is not bending and is kept.
        let mut vel = vec![Vec3::ZERO; 4];
        vel[3] = Vec3::new(0.0, 1.0, 0.0);
        damp_bending(&pos, &mut vel, 0.6);
        assert!((vel[3] - Vec3::Y).length() < 1e-6);
    }

    #[test]
    fn the_stiffness_keeps_its_meaning_at_the_reference_step() {
        // At 1/240 s and ζ = 1, the pull is the stiffness itself (the old definition).
        for s in [0.05f32, 0.25, 0.6, 0.9] {
            let w = bending_frequency_rad_s(s);
            let (k, _) = step_factors(w, 1.0, f64::from(BENDING_REFERENCE_STEP_S));
            assert!((k - s).abs() < 1e-6, "{s}: {k}");
        }
        assert_eq!(bending_frequency_rad_s(0.0), 0.0);
        assert_eq!(step_factors(0.0, 1.0, 0.01), (0.0, 0.0));
        assert_eq!(
            step_factors(bending_frequency_rad_s(1.0), 1.0, 0.001),
            (1.0, 1.0)
        );
        // ω for the smooth preset: −ln(1 − 0.5) · 240 = 166.4 rad/s.
        // (1/240 s is rounded to f32, hence the tolerance.)
        assert!((bending_frequency_rad_s(0.25) - 240.0 * 2f64.ln()).abs() < 1e-4);
    }

    /// Seconds until the isolated link's deviation stays below `tol` for good, at step `dt`.
    fn settle_time_s(w: f64, zeta: f64, dt: f64, tol: f64) -> f64 {
        let (k, kappa) = step_factors(w, zeta, dt);
        let (k, kappa) = (f64::from(k), f64::from(kappa));
        let (mut e, mut u) = (1.0f64, 0.0f64);
        let mut last_above = 0usize;
        for n in 1..100_000 {
            let e_new = (1.0 - k) * (e + u);
            u = (1.0 - kappa) * (e_new - e);
            e = e_new;
            if e.abs() > tol {
                last_above = n;
            }
        }
        last_above as f64 * dt
    }

    #[test]
    fn the_link_settles_in_the_same_time_at_any_step() {
        // The continuous critically damped link, e(t) = (1 + ωt) e^{−ωt} from e = 1 at rest,
        // is below 1e-4 after t with (1 + ωt) e^{−ωt} = 1e-4: ωt = 11.76 (solved below), i.e.
        // 70.7 ms at ω = 166.4 rad/s. The discrete map has the same eigenvalues at every step
        // (it starts from a slightly different velocity, since u = 0 means "at rest" over the
        // previous step), so it settles at the same time to within about two steps (measured:
        // 50, 67, 70 and 70 ms at 1/60, 1/240, 1/960 and 1/3840 s). The old per-step scaling,
        // k = 1 − (1 − s)^(dt·240) and κ = 1 − exp(−2√k), took 100, 46, 36 and 21 ms.
        let w = bending_frequency_rad_s(0.25);
        let mut wt = 10.0f64;
        for _ in 0..50 {
            let f = (1.0 + wt) * (-wt).exp() - 1e-4;
            let df = -wt * (-wt).exp();
            wt -= f / df;
        }
        let exact_s = wt / w;
        assert!((exact_s - 0.0707).abs() < 5e-4, "{exact_s}");
        for dt in [1.0 / 60.0, 1.0 / 240.0, 1.0 / 960.0, 1.0 / 3840.0] {
            let t = settle_time_s(w, 1.0, dt, 1e-4);
            assert!(
                (t - exact_s).abs() <= 2.0 * dt,
                "dt {dt}: {t} s vs {exact_s} s"
            );
        }
        // Under- and over-damped links (ζ = 0.5, 2): the same time at 1/240 and 1/3840 s.
        for zeta in [0.5f64, 2.0] {
            let a = settle_time_s(w, zeta, 1.0 / 240.0, 1e-4);
            let b = settle_time_s(w, zeta, 1.0 / 3840.0, 1e-4);
            assert!((a - b).abs() <= 2.0 / 240.0, "ζ {zeta}: {a} vs {b}");
        }
    }

    #[test]
    fn factors_stay_in_range_for_extreme_inputs() {
        for w in [0.0, 1e-3, 10.0, 166.0, 1e4, 1e9, f64::INFINITY] {
            for zeta in [0.0, 0.3, 1.0, 3.0, 10.0] {
                for dt in [1e-5, 1.0 / 240.0, 0.05] {
                    let (k, kappa) = step_factors(w, zeta, dt);
                    assert!((0.0..=1.0).contains(&k), "{w} {zeta} {dt}: k {k}");
                    assert!((0.0..=1.0).contains(&kappa), "{w} {zeta} {dt}: κ {kappa}");
                }
            }
        }
    }
}
