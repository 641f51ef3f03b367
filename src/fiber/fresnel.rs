//! Bravais indices and the generalised Fresnel factor of Marschner 2003 Appendix B.
//!
//! A ray inclined by θ to the fibre's normal plane refracts, once projected into that plane,
//! like a 2D ray through a medium of index η'(θ) (Bravais's law). The Fresnel factor of the
//! oblique 3D interface is recovered exactly from the projected angles with η' for the
//! perpendicular polarisation and a second parameter η''(θ) for the parallel one.
//!
//! **Trap 10 (η'' is not a refraction index).** The reading chosen: the projected refraction
//! angle γt is always given by Snell's law with η' (sin γi = η' sin γt); η'' only replaces the
//! index in the parallel reflectance formula R_p = ((η'' cos γi − cos γt)/(η'' cos γi + cos γt))².
//! Why: with this reading F(η', η'', γi) equals the ordinary 3D Fresnel reflectance at the true
//! incidence angle (cos ι = cos θ cos γi) to rounding, which is what App. B claims ("the factor
//! for oblique incidence may be computed from the projected angles"). The alternative (a
//! second Snell refraction with η'' for the parallel part) gives a different γt for that part and
//! errors of several percent at θ = 60° (pinned by `eta_dprime_is_not_a_refraction_index`).

/// Bravais's effective index η'(θ) = √(η² − sin²θ) / cos θ (Marschner 2003 App. B, with the
/// corrected derivation of the blog notes). Dimensionless, ≥ η; θ in radians, |θ| < π/2. The
/// caller bounds cos θ away from 0 (toward ±π/2 η' grows without bound).
pub fn eta_prime(eta: f64, sin_theta: f64) -> f64 {
    let cos2 = (1.0 - sin_theta * sin_theta).max(1e-12);
    ((eta * eta - sin_theta * sin_theta).max(0.0) / cos2).sqrt()
}

/// The second Bravais parameter η''(θ) = η² cos θ / √(η² − sin²θ) (Marschner 2003 App. B).
/// Dimensionless, in (0, η]; it is *not* an index of refraction (trap 10).
pub fn eta_double_prime(eta: f64, sin_theta: f64) -> f64 {
    let cos = (1.0 - sin_theta * sin_theta).max(0.0).sqrt();
    eta * eta * cos / (eta * eta - sin_theta * sin_theta).max(1e-12).sqrt()
}

/// Generalised Fresnel reflectance F(η', η'', γ) for unpolarised light (Marschner 2003 App. B):
/// projected incidence angle γ (radians, given by its cosine, in [0, 1]); the transmitted
/// projected angle obeys sin γ = η' sin γt. Returns a reflectance in [0, 1]; total internal
/// reflection (possible only when η' < 1) returns 1.
pub fn fresnel_generalized(eta_p: f64, eta_pp: f64, cos_gamma: f64) -> f64 {
    let cos_i = cos_gamma.clamp(0.0, 1.0);
    let sin2_i = 1.0 - cos_i * cos_i;
    let sin2_t = sin2_i / (eta_p * eta_p);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let r_s = (cos_i - eta_p * cos_t) / (cos_i + eta_p * cos_t);
    let r_p = (eta_pp * cos_i - cos_t) / (eta_pp * cos_i + cos_t);
    (0.5 * (r_s * r_s + r_p * r_p)).clamp(0.0, 1.0)
}

/// Ordinary dielectric Fresnel reflectance for unpolarised light, relative index η (transmitted
/// over incident), incidence angle given by its cosine. Used as the 3D reference of App. B.
pub fn fresnel_dielectric(eta: f64, cos_i: f64) -> f64 {
    fresnel_generalized(eta, eta, cos_i)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// App. B: F(η', η'', γ) on projected angles equals the 3D Fresnel factor on the true
    /// incidence angle, cos ι = cos θ cos γ (geometry of a ray hitting a cylinder).
    #[test]
    fn generalized_fresnel_equals_3d_fresnel() {
        let eta = 1.55;
        for i in 0..=16 {
            let theta = -1.5 + 3.0 * i as f64 / 16.0;
            for j in 0..=16 {
                let gamma = 1.55 * j as f64 / 16.0;
                let s = theta.sin();
                let f2 =
                    fresnel_generalized(eta_prime(eta, s), eta_double_prime(eta, s), gamma.cos());
                let f3 = fresnel_dielectric(eta, theta.cos() * gamma.cos());
                assert!((f2 - f3).abs() < 1e-12, "θ={theta} γ={gamma}: {f2} vs {f3}");
                // Leaving the fibre with 1/η', 1/η'' at the refracted angle is the same 3D
                // interface seen from inside: equal to the 3D Fresnel from inside.
                let ep = eta_prime(eta, s);
                let sin_gt = gamma.sin() / ep;
                let cos_gt = (1.0 - sin_gt * sin_gt).sqrt();
                let f_in = fresnel_generalized(1.0 / ep, 1.0 / eta_double_prime(eta, s), cos_gt);
                assert!((f_in - f3).abs() < 1e-12, "inside: {f_in} vs {f3}");
            }
        }
    }

    /// Trap 10: treating η'' as a refraction index for the parallel component (a second Snell
    /// refraction with η'') disagrees with the 3D Fresnel factor.
    #[test]
    fn eta_dprime_is_not_a_refraction_index() {
        let eta: f64 = 1.55;
        let theta: f64 = 60f64.to_radians();
        let gamma: f64 = 70f64.to_radians();
        let s = theta.sin();
        let (ep, epp) = (eta_prime(eta, s), eta_double_prime(eta, s));
        // Wrong reading: average of perpendicular with η' and parallel *as if* index η''.
        let cos_i = gamma.cos();
        let r_s = {
            let ct = (1.0 - (gamma.sin() / ep).powi(2)).sqrt();
            ((cos_i - ep * ct) / (cos_i + ep * ct)).powi(2)
        };
        let r_p_wrong = {
            let ct = (1.0 - (gamma.sin() / epp).powi(2)).max(0.0).sqrt();
            ((epp * cos_i - ct) / (epp * cos_i + ct)).powi(2)
        };
        let wrong = 0.5 * (r_s + r_p_wrong);
        let right = fresnel_generalized(ep, epp, cos_i);
        let reference = fresnel_dielectric(eta, theta.cos() * gamma.cos());
        assert!((right - reference).abs() < 1e-12);
        assert!(
            (wrong - reference).abs() > 0.02,
            "{wrong} vs {reference}: the wrong reading must be measurably off"
        );
    }

    #[test]
    fn normal_incidence_value() {
        // ((η − 1)/(η + 1))² = (0.55/2.55)² for η = 1.55 (textbook).
        let f = fresnel_dielectric(1.55, 1.0);
        assert!((f - (0.55f64 / 2.55).powi(2)).abs() < 1e-14);
    }
}
