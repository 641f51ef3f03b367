use super::*;
use std::f64::consts::PI;

/// Trap 3: the exact series agrees with Eq. 16 once its ᾱ_b sign is flipped to +, to
/// O(ā_b⁴); the printed sign is off by ≈ 4ᾱ_b ā_b²/(1 − ā_f²)².
#[test]
fn trap3_delta_b_sign() {
    let (a_f, a_b, al_f, al_b) = (0.6, 0.05, -0.05, 0.2);
    let exact = delta_b(a_f, a_b, al_f, al_b);
    let printed = delta_b_printed(a_f, a_b, al_f, al_b);
    let x: f64 = a_f * a_f;
    let corrected = al_b * (1.0 + 2.0 * a_b * a_b / (1.0 - x).powi(2))
        + al_f * (2.0 * (1.0 - x).powi(2) + 4.0 * x * a_b * a_b) / (1.0 - x).powi(3);
    let gap = 4.0 * al_b * a_b * a_b / (1.0 - x).powi(2);
    assert!(
        (exact - corrected).abs() < 0.05 * gap,
        "{exact} {corrected}"
    );
    assert!(
        (exact - printed - gap).abs() < 0.05 * gap,
        "{exact} {printed} {gap}"
    );
    // Brute-force check of the closed form against the literal triple sum.
    let mut num = 0.0;
    let mut den = 0.0;
    for i in 1..200 {
        let w = a_b * a_f.powi(2 * i);
        num += w * (2.0 * i as f64 * al_f + al_b);
        den += w;
    }
    for i in 1..60i32 {
        for j in 0..i {
            for k in (j + 1)..60 {
                let m = 2 * (i - j - 1 + k);
                let w = a_b.powi(3) * a_f.powi(m);
                num += w * (3.0 * al_b + m as f64 * al_f);
                den += w;
            }
        }
    }
    assert!((num / den - exact).abs() < 1e-9, "{} vs {exact}", num / den);
    assert!((den - big_a_b(a_f, a_b)).abs() < 1e-9);
}

/// Trap 2: Eq. 17 as printed changes with the angle unit; the series scales like an angle.
#[test]
fn trap2_sigma_b_units() {
    let (a_f, a_b) = (0.7, 0.3);
    let (bf, bb) = (0.05f64, 0.2f64);
    let deg = 180.0 / PI;
    let printed_rad = sigma_b_printed(a_f, a_b, bf, bb);
    let printed_deg = sigma_b_printed(a_f, a_b, bf * deg, bb * deg) / deg;
    assert!((printed_rad - printed_deg).abs() > 0.1 * printed_rad);
    let s_rad = sigma_b2(a_f, a_b, bf * bf, bb * bb).sqrt();
    let s_deg = sigma_b2(a_f, a_b, (bf * deg).powi(2), (bb * deg).powi(2)).sqrt() / deg;
    assert!((s_rad - s_deg).abs() < 1e-9 * s_rad);
    // Analytic case: with β_f = 0 every path has σ = √(k) β_b for k = 1 or 3 backward
    // events, so σ_b lies between β_b and √3 β_b.
    let s = sigma_b2(a_f, a_b, 0.0, bb * bb).sqrt();
    assert!(s > bb && s < 3f64.sqrt() * bb);
}

/// The closed forms of `big_a_b_behind` against the literal series: terms with deepest fibre
/// D ≤ N summed directly for each integer N (Eq. 11's i and Eq. 13's (i, j, k) enumerated,
/// D = i + 1 and D = i − j + k), then averaged over N ~ Poisson(n).
#[test]
fn truncation_matches_series() {
    let literal = |a_f: f64, a_b: f64, big_n: i64| {
        let x = a_f * a_f;
        let mut sum = 0.0;
        for i in 1..400i64 {
            if i < big_n {
                sum += a_b * x.powi(i as i32);
            }
        }
        for i in 1..60i64 {
            for j in 0..i {
                for k in (j + 1)..60 {
                    if i - j + k <= big_n {
                        sum += a_b.powi(3) * x.powi((i - j - 1 + k) as i32);
                    }
                }
            }
        }
        sum
    };
    for (a_f, a_b) in [(0.6, 0.05), (0.3, 0.2), (0.85, 0.1)] {
        // Dense limit: Zinke's Ā_b (truncated sums of 60 terms converge to 1e-9 here).
        assert!((big_a_b_behind(a_f, a_b, f64::INFINITY) - big_a_b(a_f, a_b)).abs() < 1e-15);
        assert!((literal(a_f, a_b, 1000) - big_a_b(a_f, a_b)).abs() < 1e-6 * big_a_b(a_f, a_b));
        for n in [0.0f64, 0.3, 1.0, 2.5, 7.0, 30.0] {
            // Poisson average of the literal series.
            let mut p = (-n).exp();
            let mut avg = 0.0;
            for big_n in 0..200i64 {
                if big_n > 0 {
                    p *= n / big_n as f64;
                }
                avg += p * literal(a_f, a_b, big_n);
            }
            let got = big_a_b_behind(a_f, a_b, n);
            assert!(
                (got - avg).abs() <= 1e-6 * big_a_b(a_f, a_b),
                "a_f={a_f} a_b={a_b} n={n}: {got} vs {avg}"
            );
            let r = truncation(
                glam::Vec3::splat(a_f as f32),
                glam::Vec3::splat(a_b as f32),
                n as f32,
            )
            .x as f64;
            assert!(
                (r - avg / big_a_b(a_f, a_b)).abs() < 2e-5,
                "f32 ratio {r} vs {}",
                avg / big_a_b(a_f, a_b)
            );
        }
    }
    // Isolated fibre: no local back-scattering; dense: exactly Zinke's.
    let v = glam::Vec3::splat(0.5);
    assert_eq!(truncation(v, v, 0.0), glam::Vec3::ZERO);
    assert_eq!(truncation(v, v, f32::NAN), glam::Vec3::ZERO);
    assert_eq!(truncation(v, v, f32::INFINITY), glam::Vec3::ONE);
}

/// Trap 6: ā_f = 1 (or above) is clamped; everything stays finite and positive.
#[test]
fn trap6_a_f_guard() {
    for a_f in [0.99, 0.999, 1.0, 1.5] {
        let a = big_a_b(a_f, 0.1);
        let d = delta_b(a_f, 0.1, 0.1, 0.1);
        let s = sigma_b2(a_f, 0.1, 0.01, 0.01);
        assert!(a.is_finite() && a > 0.0 && d.is_finite() && s.is_finite() && s > 0.0);
        assert_eq!(a, big_a_b(A_F_MAX, 0.1));
    }
}
