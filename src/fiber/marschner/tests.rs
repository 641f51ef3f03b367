use super::*;
use crate::fiber::FiberParams;

fn consts() -> LobeConstants {
    LobeConstants::from_params(&FiberParams::default())
}

#[test]
fn m_has_unit_area_in_theta_o() {
    // Trapezoid over a range wide enough to hold the whole Gaussian (analytic area 1).
    let c = consts();
    for lobe in Lobe::ALL {
        let n = 40000;
        let (a, b) = (-6.0, 6.0);
        let dx = (b - a) / n as f64;
        let area: f64 = (0..=n)
            .map(|i| {
                let w = if i == 0 || i == n { 0.5 } else { 1.0 };
                w * longitudinal_m(&c, lobe, 0.1, a + i as f64 * dx)
            })
            .sum::<f64>()
            * dx;
        assert!((area - 1.0).abs() < 1e-9, "{lobe:?}: {area}");
    }
}

/// Trap 9: 1/cos²θd is floored at cos θd = 0.01 (≤ 10⁴), reached only at the corner
/// θi = −θo = ±90°, where S stays finite; just inside the floor it is the true 1/cos²θd.
#[test]
fn grazing_floor() {
    assert_eq!(inv_cos2_theta_d(PI / 2.0), 1e4);
    assert_eq!(inv_cos2_theta_d(-PI / 2.0), 1e4);
    let td = 89.0f64.to_radians();
    assert!((inv_cos2_theta_d(td) - 1.0 / td.cos().powi(2)).abs() < 1e-9);
    let c = consts();
    let s = bcsdf_exact(&c, PI / 2.0, -PI / 2.0, 0.0, 1.0);
    assert!(s.iter().flatten().all(|x| x.is_finite() && *x >= 0.0));
}

#[test]
fn smoothstep_is_reversed() {
    assert_eq!(smoothstep_paper(2.0, 2.3, 1.9), 1.0);
    assert_eq!(smoothstep_paper(2.0, 2.3, 2.0), 1.0);
    assert_eq!(smoothstep_paper(2.0, 2.3, 2.4), 0.0);
    assert!((smoothstep_paper(2.0, 2.3, 2.15) - 0.5).abs() < 1e-12);
}

#[test]
fn roots_reproduce_phi() {
    let az = Azimuth::new(1.55, 0.3, [0.5; 3]);
    for p in 0..3 {
        for i in 0..200 {
            let phi = -PI + 2.0 * PI * (i as f64 + 0.5) / 200.0;
            let (r, n) = az.roots(p, phi);
            for &g in &r[..n] {
                let back = wrap_pi(az.phi(p, g) - phi);
                assert!(back.abs() < 1e-10, "p={p} φ={phi} γ={g} err={back}");
            }
        }
    }
}

/// Trap 8: TT has no path for |φ| < 2c (c = asin 1/η'), and N is exactly 0 there.
#[test]
fn tt_no_path_is_zero() {
    let az = Azimuth::new(1.55, 0.0, [0.0; 3]);
    let c = (1.0 / 1.55f64).asin();
    assert_eq!(az.roots(1, 2.0 * c - 0.01).1, 0);
    assert_eq!(az.n_raw(1, 0.0), [0.0; 3]);
    assert!(az.n_raw(1, 2.0 * c + 0.05)[0] > 0.0);
    // Raw TRT reaches only |φ| ≤ |4c − π| = 19.3° at θd = 0 (Eq. 3 at h = ±1): beyond, no
    // root and exactly 0; the smoothed lobe there is the glints alone.
    let reach = (4.0 * c - PI).abs();
    for phi in [reach + 1e-3, 0.5, 1.5, PI] {
        assert_eq!(az.roots(2, phi).1, 0, "φ={phi}");
        assert_eq!(az.n_raw(2, phi), [0.0; 3]);
    }
    assert!(az.n_raw(2, reach - 1e-3)[0] > 0.0);
}

/// Trap 7: just below the merge (η' = 1.999) TRT has three roots for small φ, found by
/// bracketing each monotone piece.
#[test]
fn trp_finds_three_roots_near_merge() {
    // Choose θd so that η'(θd) = 1.999 for η = 1.55: sin²θd = (η'² − η²)/(η'² − 1).
    let ep: f64 = 1.999;
    let sin_td = ((ep * ep - 1.55 * 1.55) / (ep * ep - 1.0)).sqrt();
    let az = Azimuth::new(1.55, sin_td, [0.0; 3]);
    assert!((az.eta_prime - ep).abs() < 1e-9);
    let caustic = az.caustic(&consts());
    let (_, n) = az.roots(2, caustic.phi_c * 0.5);
    assert_eq!(n, 3);
}

/// Marschner's Eq. 10 replaces Snell's law by the cubic γt ≈ (3c/π)γi − (4c/π³)γi³ (c =
/// asin(1/η')), making φ̂ a cubic in γi. Measured here for N_TT at θd = 0, σa = 0: the
/// difference from the exact roots, relative to N_TT's peak, over φ ∈ [2c, π].
#[test]
fn cubic_eq10_error_is_measurable() {
    let az = Azimuth::new(1.55, 0.0, [0.0; 3]);
    let ep = az.eta_prime;
    let c = (1.0 / ep).asin();
    let phi_hat = |g: f64| (6.0 * c / PI - 2.0) * g - 8.0 * c / PI.powi(3) * g.powi(3) + PI;
    let dphi_hat = |g: f64| (6.0 * c / PI - 2.0) - 24.0 * c / PI.powi(3) * g * g;
    let n_cubic = |phi: f64| {
        // φ̂ decreases from 2π − 2c to 2c over γi ∈ [−π/2, π/2]: bisection.
        let (mut a, mut b) = (-PI / 2.0, PI / 2.0);
        for _ in 0..100 {
            let m = 0.5 * (a + b);
            if phi_hat(m) > phi { a = m } else { b = m }
        }
        let g = 0.5 * (a + b);
        az.attenuation(1, g)[0] * g.cos() / (2.0 * dphi_hat(g).abs())
    };
    let peak = az.n_raw(1, PI)[0];
    let mut worst: f64 = 0.0;
    for k in 0..=400 {
        let phi = 2.0 * c + 1e-6 + (PI - 2.0 * c) * k as f64 / 400.0;
        worst = worst.max((n_cubic(phi) - az.n_raw(1, phi)[0]).abs());
    }
    // Measured 0.074 × peak: the cubic's 0.75° error in γt is amplified near the range
    // edge where dφ/dh is steep. Exact roots are used; this pins that the cubic would not
    // be a free substitute.
    assert!(
        worst > 0.03 * peak && worst < 0.2 * peak,
        "{worst} vs peak {peak}"
    );
}

#[test]
fn chord_is_2_cos_gamma_t() {
    // Normal incidence through the centre: chord = diameter = 2 radii (analytic).
    let az = Azimuth::new(1.55, 0.0, [1.0; 3]);
    let a = az.attenuation(1, 0.0);
    let f = fresnel_generalized(1.55, 1.55, 1.0);
    assert!((a[0] - (1.0 - f).powi(2) * (-2.0f64).exp()).abs() < 1e-14);
    // Off-centre ray, chord from an independent 2D intersection: the refracted ray
    // enters at (−cos γi, sin γi)... its chord through a unit circle is 2 cos γt.
    let gi: f64 = 0.7;
    let gt = (gi.sin() / 1.55).asin();
    let entry = (-(gi.cos()), gi.sin());
    // Direction of the refracted ray: rotate the inward normal (1, 0) rotated... compute
    // via the circle intersection: p + s d with |p + s d| = 1, s > 0.
    let d = ((gi - gt).cos(), -(gi - gt).sin());
    let b = entry.0 * d.0 + entry.1 * d.1;
    let s = -2.0 * b; // since |entry| = 1, roots s = 0 and s = −2 b
    assert!(
        (s - 2.0 * gt.cos()).abs() < 1e-12,
        "{s} vs {}",
        2.0 * gt.cos()
    );
}
