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

/// Ā_b for a point with a finite amount of hair behind it: the expected number of fibre crossings
/// n that a light ray still makes after the point, continuing along the light direction until it
/// leaves the hair (`LightAtPoint::crossings_behind`).
///
/// **Derivation.** Write x = ā_f². In the sums of Eqs. 11 and 13, a path whose deepest
/// back-scattering happens at the D-th fibre behind the point carries x^{D−1}: Eq. 11's term i
/// is D = i + 1, and Eq. 13's term (i, j, k) reaches D = i − j + k with exponent
/// i − j − 1 + k = D − 1; counting the (i, j, k) with a given D gives D(D − 1)/2 of them. So
/// Ā_b(∞) = Σ_{D≥2} (ā_b + ā_b³ D(D−1)/2) x^{D−1}: Zinke's closed forms assume infinitely many
/// fibres behind the point. With N fibres behind, only D ≤ N exist, and the partial sums are
/// Ā_1(N) = ā_b (x − x^N)/(1 − x) and Ā_3(N) = ā_b³ (x/(1−x)³ − t(N)) with the tail
/// t(N) = x^N/2 · (N(N−1)/(1−x) + (2N−1)/(1−x)² + (1+x)/(1−x)³). The number of fibres behind a
/// point is Poisson with mean n (the map's reading of crossing counts, DESIGN "Counts to
/// transmittance"), and averaging over it with E[x^N] = q = e^{−n(1−x)}, E[N x^N] = n x q,
/// E[N(N−1) x^N] = (nx)² q gives
///   E Ā_1 = ā_b (x(1 − e^{−n}) − q + e^{−n})/(1 − x),
///   E Ā_3 = ā_b³ (x/(1−x)³ − q/2 · ((nx)²/(1−x) + (2nx − 1)/(1−x)² + (1+x)/(1−x)³)).
/// Both vanish like n² as n → 0 (an isolated fibre gets no local back-scattering: a path needs
/// at least two fibres behind it) and tend to Eqs. 11 and 13 as n → ∞. Pinned against the
/// literal truncated series in `truncation_matches_series`.
pub fn big_a_b_behind(a_f: f64, a_b: f64, n: f64) -> f64 {
    if n.is_infinite() && n > 0.0 {
        return big_a_b(a_f, a_b);
    }
    let n = if n.is_nan() { 0.0 } else { n.max(0.0) };
    let x = a_f.min(A_F_MAX).powi(2);
    let u = 1.0 - x;
    let q = (-n * u).exp();
    let e = (-n).exp();
    let a1 = a_b * (x * (1.0 - e) - q + e) / u;
    let nx = n * x;
    let a3 = a_b.powi(3)
        * (x / u.powi(3)
            - 0.5 * q * (nx * nx / u + (2.0 * nx - 1.0) / (u * u) + (1.0 + x) / u.powi(3)));
    (a1 + a3).max(0.0)
}

/// The factor Ā_b(n)/Ā_b(∞) of [`big_a_b_behind`] per channel, in [0, 1], in f32 for the shader
/// (`a_f`, `a_b` from the dual tables at the light's inclination). 1 exactly for n = +∞ (dense
/// hair, the default), 0 for n ≤ 0 or NaN.
#[inline]
pub fn truncation(a_f: glam::Vec3, a_b: glam::Vec3, n: f32) -> glam::Vec3 {
    if n == f32::INFINITY {
        return glam::Vec3::ONE;
    }
    if n.is_nan() || n <= 0.0 {
        return glam::Vec3::ZERO;
    }
    let e = (-n).exp();
    let x_max = (A_F_MAX * A_F_MAX) as f32;
    let f = |a_f: f32, a_b: f32| {
        let x = (a_f * a_f).clamp(0.0, x_max);
        let u = 1.0 - x;
        let q = (-n * u).exp();
        let ab2 = a_b * a_b;
        let full = x / u + ab2 * x / (u * u * u);
        if full.is_nan() || full <= 0.0 {
            return 0.0;
        }
        let nx = n * x;
        let a1 = (x * (1.0 - e) - q + e) / u;
        let a3 = ab2
            * (x / (u * u * u)
                - 0.5 * q * (nx * nx / u + (2.0 * nx - 1.0) / (u * u) + (1.0 + x) / (u * u * u)));
        ((a1 + a3) / full).clamp(0.0, 1.0)
    };
    glam::Vec3::new(f(a_f.x, a_b.x), f(a_f.y, a_b.y), f(a_f.z, a_b.z))
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
mod tests;
