//! Local back-scattering statistics of a disciplined hair cluster (Zinke et al. 2008 §3.2):
//! Ā_b (Eqs. 11, 13, 14), the mean shift Δ̄_b (the series above Eq. 16) and the spread σ̄_b² (the
//! series above Eq. 17), from a fibre's ā_f, ā_b, ᾱ_f, ᾱ_b, β̄_f², β̄_b² (all per colour channel;
//! angles in radians of x = θi + θo, variances in rad²).
//!
//! The printed fits (Eqs. 16, 17) are kept only as `*_printed` for the tests that show why
//! they are not used (traps 2 and 3, see `dual.rs`). Counting terms: the triple sum of Eq. 13
//! has n(n+1)/2 index triples with i − j − 1 + k = n, so every sum is a single series in
//! x = ā_f².

/// Upper clamp of ā_f before 1 − ā_f² divides anything (trap 6). With it, 1/(1 − ā_f²)³ ≤
/// 1.3·10⁵; physical fibres stay well below it (ā_f ≤ 0.8 at σa = 0, see tests). Why: the
/// factors amplify errors, d ln Ā_1 / d ln ā_f = 2/(1 − ā_f²), so a 1% error in ā_f = 0.9 is a
/// 10% error in Ā_b, and ā_f ≥ 1 (a non-conserving BCSDF, or interpolation) would make Ā_b,
/// Δ̄_b and σ̄_b infinite or negative. The alternative, no guard, fails `trap6_a_f_guard`.
pub const A_F_MAX: f64 = 0.99;

/// Ā_b of Eqs. 11, 13, 14: ā_b ā_f²/(1 − ā_f²) + ā_b³ ā_f²/(1 − ā_f²)³, with ā_f ≤ [`A_F_MAX`].
pub fn big_a_b(a_f: f64, a_b: f64) -> f64 {
    let x = a_f.min(A_F_MAX).powi(2);
    a_b * x / (1.0 - x) + a_b.powi(3) * x / (1.0 - x).powi(3)
}

/// Δ̄_b: exact closed form of the series above Eq. 16 (radians in x = θi + θo). With x = ā_f²,
/// Σ_i x^i = x/(1−x), Σ i x^i = x/(1−x)², Σ n(n+1)/2 x^n = x/(1−x)³, Σ n²(n+1)/2 x^n =
/// x(1+2x)/(1−x)⁴; the common factor ā_b x is cancelled so ā_f → 0 stays finite.
pub fn delta_b(a_f: f64, a_b: f64, alpha_f: f64, alpha_b: f64) -> f64 {
    let x = a_f.min(A_F_MAX).powi(2);
    let q = 1.0 - x;
    let ab2 = a_b * a_b;
    let num = alpha_b / q
        + 2.0 * alpha_f / (q * q)
        + ab2 * (3.0 * alpha_b / q.powi(3) + 2.0 * alpha_f * (1.0 + 2.0 * x) / q.powi(4));
    let den = 1.0 / q + ab2 / q.powi(3);
    num / den
}

/// Eq. 16 as printed (with its minus sign), for the trap-3 test.
pub fn delta_b_printed(a_f: f64, a_b: f64, alpha_f: f64, alpha_b: f64) -> f64 {
    let x = a_f * a_f;
    alpha_b * (1.0 - 2.0 * a_b * a_b / (1.0 - x).powi(2))
        + alpha_f * (2.0 * (1.0 - x).powi(2) + 4.0 * x * a_b * a_b) / (1.0 - x).powi(3)
}

/// σ̄_b² from the series above Eq. 17 (σ̄_b is the weighted mean of the path standard
/// deviations), summed until the remaining weight is below 10⁻¹² of the total. Radians².
pub fn sigma_b2(a_f: f64, a_b: f64, beta_f2: f64, beta_b2: f64) -> f64 {
    let x = a_f.min(A_F_MAX).powi(2);
    let ab2 = a_b * a_b;
    // Terms divided by ā_b x (weights x^{i−1}), as in `delta_b`.
    let (mut num, mut den) = (0.0, 0.0);
    let mut xi = 1.0; // x^{n−1}
    for n in 1..=200_000u32 {
        let nf = n as f64;
        let w1 = xi;
        let w3 = ab2 * nf * (nf + 1.0) * 0.5 * xi;
        num += w1 * (2.0 * nf * beta_f2 + beta_b2).sqrt()
            + w3 * (3.0 * beta_b2 + 2.0 * nf * beta_f2).sqrt();
        den += w1 + w3;
        xi *= x;
        if (w1 + w3) < 1e-12 * den {
            break;
        }
    }
    let s = num / den;
    s * s
}

/// Eq. 17 as printed (standard deviation), evaluated with angles in the caller's unit; for the
/// trap-2 test only.
pub fn sigma_b_printed(a_f: f64, a_b: f64, beta_f: f64, beta_b: f64) -> f64 {
    (1.0 + 0.7 * a_f * a_f)
        * (a_b * (2.0 * beta_f * beta_f + beta_b * beta_b).sqrt()
            + a_b.powi(3) * (2.0 * beta_f * beta_f + 3.0 * beta_b * beta_b).sqrt())
        / (a_b + a_b.powi(3) * (2.0 * beta_f + 3.0 * beta_b))
}

#[cfg(test)]
mod tests {
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
}
