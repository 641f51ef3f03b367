use super::*;

#[test]
fn ln_i0_reference_values() {
    // I0(1) = 1.2660658777520082, I0(10) = 2815.716628466254, I0(50) = 2.9325537838493355e20
    // (Abramowitz & Stegun Table 9.8; the digits as numpy.i0 prints them).
    assert!((ln_i0(1.0).exp() - 1.266_065_877_752_008_2).abs() < 1e-14);
    assert!((ln_i0(10.0).exp() / 2_815.716_628_466_254 - 1.0).abs() < 1e-13);
    assert!((ln_i0(50.0).exp() / 2.932_553_783_849_335_5e20 - 1.0).abs() < 1e-9);
    // The two branches meet at x = 30 (continuity of the function they both approximate).
    assert!((ln_i0(30.0) - ln_i0(30.000_000_001)).abs() < 1e-8);
}

#[test]
fn roughness_fit_round_trip() {
    use crate::fiber::{roughness_for_std, std_for_roughness};
    // MAPPING.md: β_R = 2.5/5/7.5/10° gives b = 0.107/0.197/0.276/0.347.
    for (beta, b) in [(2.5f64, 0.107), (5.0, 0.197), (7.5, 0.276), (10.0, 0.347)] {
        let got = roughness_for_std((2.0 * beta).to_radians());
        assert!((got - b).abs() < 1e-3, "β_R={beta}: {got}");
        assert!((std_for_roughness(got) - (2.0 * beta).to_radians()).abs() < 1e-12);
    }
    // s at β_n = 0.3 is 0.117 rad (MAPPING.md: 0.05/0.1/0.2/0.3 → 0.010/0.024/0.063/0.117).
    assert!((logistic_scale(0.3) - 0.117).abs() < 1e-3);
    assert!((logistic_scale(0.05) - 0.010).abs() < 1e-3);
}

#[test]
fn logistic_cdf_is_periodic_and_matches_density() {
    for s in [0.002, 0.117, 1.0, 4.3] {
        assert!((trimmed_logistic_cdf(-PI, s)).abs() < 1e-12);
        assert!((trimmed_logistic_cdf(0.0, s) - 0.5).abs() < 1e-12);
        for x in [-2.0, 0.3, 1.7, 3.0] {
            let a = trimmed_logistic_cdf(x, s);
            assert!((trimmed_logistic_cdf(x + 2.0 * PI, s) - a - 1.0).abs() < 1e-12);
            // Derivative of the CDF is the density (central difference).
            let e = 1e-6 * s.min(1.0);
            let d = (trimmed_logistic_cdf(x + e, s) - trimmed_logistic_cdf(x - e, s)) / (2.0 * e);
            let l = trimmed_logistic(x, s);
            assert!(
                (d - l).abs() <= 1e-5 * l.max(1e-3),
                "s={s} x={x}: {d} vs {l}"
            );
        }
    }
}

/// The closed form of w_f ⊛ ℓ against brute-force quadrature over x (20 000 nodes).
#[test]
fn w_forward_smoothed_matches_quadrature() {
    for s in [0.01, 0.117, 0.6, 4.3] {
        for y in [0.0, 0.05, 0.8, 1.6, 3.0, PI, -2.2] {
            let n = 20_000;
            let dx = 2.0 * PI / n as f64;
            let brute: f64 = (0..n)
                .map(|k| {
                    let x = -PI + (k as f64 + 0.5) * dx;
                    super::super::azimuthal::w_forward(y + x) * trimmed_logistic(x, s) * dx
                })
                .sum();
            let got = w_forward_smoothed(y, s);
            assert!((got - brute).abs() < 2e-5, "s={s} y={y}: {got} vs {brute}");
        }
    }
}
