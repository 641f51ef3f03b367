//! Bending toward the rest shape: the per-step pull and damping constants, the transported
//! frame's minimal rotation, and the bending damping pass.
//!
//! What: `step.rs` pulls each link toward its rest bend relative to its parent link, expressed
//! in a frame parallel-transported down the strand with [`rotation_arc`], then damps the
//! links' relative rotation with [`damp_bending`]. This file holds those pieces and the maps
//! from the JSON parameters to per-step factors.
//!
//! Why per-step factors derived here: the parameters must mean the same at any `step_s`.
//! - Pull: `k = 1 − (1 − bending_stiffness)^(dt / (1/240 s))`, so `bending_stiffness` is the
//!   fraction of the deviation removed per 1/240 s whatever the step.
//! - The pulled link is an oscillator: from the per-step map `e ← (1 − k)(e + v dt)`,
//!   `v dt ← e' − e`, the eigenvalues solve `λ² − 2(1 − k)λ + (1 − k) = 0`, i.e. for small k
//!   `λ ≈ 1 ± i√k`: angular frequency `ω = √k / dt` (120 rad/s at k = 0.25, dt = 1/240 s).
//! - Damping: a rate `c = 2ζω` (critical for ζ = 1) is the per-step factor
//!   `κ = 1 − exp(−c dt) = 1 − exp(−2ζ√k)`, independent of dt for a given k.

use glam::{Quat, Vec3, Vec3A};

/// Reference step that `bending_stiffness` is defined at, seconds.
pub const BENDING_REFERENCE_STEP_S: f32 = 1.0 / 240.0;

/// Fraction `k` of the deviation from the rest bend removed per step of `dt` seconds, for
/// `stiffness` in [0, 1] defined per [`BENDING_REFERENCE_STEP_S`].
pub(crate) fn pull_per_step(stiffness: f32, dt: f32) -> f32 {
    1.0 - (1.0 - stiffness).powf(dt / BENDING_REFERENCE_STEP_S)
}

/// Fraction `κ` of the relative angular velocity of adjacent links removed per step, for a
/// damping ratio `zeta` and the per-step pull `k` (see the module doc).
pub(crate) fn damping_per_step(zeta: f32, k: f32) -> f32 {
    1.0 - (-2.0 * zeta * k.sqrt()).exp()
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
    fn per_step_factors_do_not_depend_on_the_step() {
        // Two steps of 1/480 s remove the same fraction as one of 1/240 s.
        let k240 = pull_per_step(0.25, 1.0 / 240.0);
        let k480 = pull_per_step(0.25, 1.0 / 480.0);
        assert!((k240 - 0.25).abs() < 1e-6);
        assert!(((1.0 - k480) * (1.0 - k480) - (1.0 - k240)).abs() < 1e-6);
        assert_eq!(pull_per_step(0.0, 0.01), 0.0);
        assert_eq!(pull_per_step(1.0, 0.001), 1.0);
        // Critical damping of the k = 0.25 spring: κ = 1 − e⁻¹.
        assert!((damping_per_step(1.0, 0.25) - (1.0 - (-1.0f32).exp())).abs() < 1e-6);
        assert_eq!(damping_per_step(1.0, 0.0), 0.0);
    }
}
