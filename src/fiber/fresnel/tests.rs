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
            let f2 = fresnel_generalized(eta_prime(eta, s), eta_double_prime(eta, s), gamma.cos());
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
