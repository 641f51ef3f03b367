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
mod tests;
