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
    let w = damping_weights(0.6, 4);
    damp_bending(&pos, &mut vel, &w);
    for (v, r) in vel.iter().zip(&rigid) {
        assert!((*v - *r).length() < 1e-6);
    }
    // Only the last link bends (its tip moves sideways relative to a still chain).
    let mut vel = vec![Vec3::ZERO; 4];
    vel[3] = Vec3::new(1.0, 0.0, 0.0);
    damp_bending(&pos, &mut vel, &w);
    assert!((vel[3].x - 0.4).abs() < 1e-6, "{}", vel[3]);
    // Stretching velocity along the link is not bending and is kept.
    let mut vel = vec![Vec3::ZERO; 4];
    vel[3] = Vec3::new(0.0, 1.0, 0.0);
    damp_bending(&pos, &mut vel, &w);
    assert!((vel[3] - Vec3::Y).length() < 1e-6);
    // κ = 1: every link turns with the root segment; κ = 0: nothing changes.
    let mut vel = vec![Vec3::ZERO; 4];
    vel[3] = Vec3::new(1.0, 0.0, 0.0);
    damp_bending(&pos, &mut vel, &damping_weights(1.0, 4));
    assert!(vel[3].length() < 1e-6);
    let before = vel.clone();
    damp_bending(&pos, &mut vel, &damping_weights(0.0, 4));
    assert_eq!(vel, before);
}

#[test]
fn bending_damping_is_exact_one_step_equals_two_half_steps() {
    // A straight 12-link chain along +Y whose links turn about Z at different rates; its
    // root segment (link 1) turns at 2 rad/s. The exact solution over c·dt = x equals two
    // solutions over x/2 (the old root-to-tip sweep failed this by 14% of the change at the
    // tip: it handed each link its parent's damped rotation within the same step).
    let pos: Vec<Vec3> = (0..13)
        .map(|i| Vec3::new(0.0, i as f32 * 0.02, 0.0))
        .collect();
    let rates = [
        0.0, 2.0, -1.0, 3.0, 0.5, -2.0, 1.0, 4.0, -3.0, 0.0, 2.5, -1.5, 1.0,
    ];
    let mut vel = vec![Vec3::ZERO; 13];
    for i in 1..13 {
        // v_i = v_{i-1} + ω_i ẑ × r_i with r_i = 0.02 ŷ: −0.02 ω_i along x.
        vel[i] = vel[i - 1] + Vec3::new(-0.02 * rates[i], 0.0, 0.0);
    }
    let x = 1.3f64;
    let kappa = |x: f64| (1.0 - (-x).exp()) as f32;
    let mut one = vel.clone();
    damp_bending(&pos, &mut one, &damping_weights(kappa(x), 13));
    let mut two = vel.clone();
    let half = damping_weights(kappa(x / 2.0), 13);
    damp_bending(&pos, &mut two, &half);
    damp_bending(&pos, &mut two, &half);
    for (a, b) in one.iter().zip(&two) {
        assert!((*a - *b).length() < 1e-6, "{a} vs {b}");
    }
    // The tip's rate against the closed form Σ Pₘ ωᵢ₋ₘ + (1 − Σ Pₘ) ω₁, in f64.
    let mut expected = 0.0f64;
    let mut mass = 0.0f64;
    let mut p = (-x).exp();
    for m in 0..=10 {
        expected += p * f64::from(rates[12 - m]);
        mass += p;
        p *= x / (m + 1) as f64;
    }
    expected += (1.0 - mass) * f64::from(rates[1]);
    let tip_rate = -f64::from(one[12].x - one[11].x) / 0.02;
    assert!(
        (tip_rate - expected).abs() < 1e-4,
        "{tip_rate} vs {expected}"
    );
    assert!((expected - 0.254).abs() < 1e-3, "{expected}");
}

#[test]
fn the_stiffness_keeps_its_meaning_at_the_reference_step() {
    // At 1/240 s and ζ = 1, the pull is the stiffness itself (the old definition).
    for s in [0.05f32, 0.25, 0.6, 0.9] {
        let w = bending_frequency_rad_s(s);
        let (k, _) = step_factors(w, 1.0, f64::from(REFERENCE_STEP_S));
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
