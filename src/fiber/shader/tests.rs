use super::arriving::arriving_spread;
use super::*;
use crate::fiber::{Fiber, FiberModel, FiberParams, ShadingMode};

/// Figure 5's forward-scattered term carries d_f times the window's fluence per unit flux
/// at the light's inclination (`dual::window_fluence_inclined`: π/2 for Zinke's 90° window
/// and a light across the fibre, 1 along it): a fully shadowed point (direct 0) shades
/// that much brighter than with the literal factor d_f, in both fibre models and at every
/// inclination, and a directly lit point with T_f = direct (nothing scattered) does not
/// change.
#[test]
fn scattered_light_carries_the_window_fluence() {
    use crate::fiber::dual::{ScatteredGain, window_fluence_inclined};
    for model in [FiberModel::Marschner, FiberModel::Chiang] {
        let fiber = Fiber::new(&FiberParams {
            model,
            ..Default::default()
        });
        let d_f = fiber.params().d_f as f64;
        let half_pi = std::f32::consts::FRAC_PI_2;
        assert!((fiber.scattered_gain.at(0.0) - d_f as f32 * half_pi).abs() < 1e-6);
        assert!((fiber.scattered_gain.at(1.0) - d_f as f32).abs() < 1e-6);
        let mut literal = fiber.clone();
        // A window of zero width is a beam: fluence = flux at any inclination.
        literal.scattered_gain = ScatteredGain::new(d_f, 0.0);
        for wi in [
            Vec3::new(0.8, 0.0, 0.1),
            Vec3::new(0.8, 0.3, 0.1),
            Vec3::new(0.3, 0.9, -0.2),
            Vec3::new(0.05, -0.99, 0.02),
        ] {
            let wi = wi.normalize();
            let want = window_fluence_inclined(90f64.to_radians(), (wi.y * wi.y) as f64);
            check_gain(&fiber, &literal, wi, want as f32, model);
        }
    }
}

fn check_gain(fiber: &Fiber, literal: &Fiber, wi: Vec3, gain: f32, model: FiberModel) {
    let (u, wo) = (Vec3::Y, Vec3::new(-0.6, -0.1, -0.5).normalize());
    let shadowed = LightAtPoint {
        direct_fraction: 0.0,
        tf: Vec3::new(0.3, 0.2, 0.1),
        sigma_f2: Vec3::splat(0.05),
        crossings_behind: LightAtPoint::DENSE,
    };
    let (a, b) = (
        fiber.shade(ShadingMode::DualScattering, u, wi, wo, &shadowed),
        literal.shade(ShadingMode::DualScattering, u, wi, wo, &shadowed),
    );
    assert!(b.min_element() > 0.0, "{model:?}: {b}");
    assert!(
        (a - b * gain).abs().max_element() <= 1e-4 * a.max_element(),
        "{model:?}, ωi {wi}: {a} vs {b} × {gain}"
    );
    let lit = LightAtPoint {
        direct_fraction: 0.4,
        tf: Vec3::splat(0.4),
        ..shadowed
    };
    assert_eq!(
        fiber.shade(ShadingMode::DualScattering, u, wi, wo, &lit),
        literal.shade(ShadingMode::DualScattering, u, wi, wo, &lit)
    );
}

/// The arriving light's spread against the Poisson sum it stands for, term by term in f64:
/// with N ~ Poisson(n̄) crossings of β² each, a ray of N crossings arriving with weight
/// ā^N, the forward-scattered light (N ≥ 1) has spread E[N β² ā^N; N ≥ 1] / E[ā^N; N ≥ 1].
#[test]
fn arriving_spread_is_the_poisson_weighted_order() {
    let beta2 = 0.02f64;
    for &n_bar in &[0.01f64, 0.3, 1.0, 4.0, 15.0, 40.0] {
        for &a in &[0.05f64, 0.38, 0.62, 0.95] {
            let (mut num, mut den, mut p) = (0.0f64, 0.0f64, (-n_bar).exp());
            for k in 1..400 {
                p *= n_bar / k as f64;
                num += k as f64 * beta2 * p * a.powi(k);
                den += p * a.powi(k);
            }
            let want = num / den;
            let direct = (-n_bar).exp() as f32;
            let tf = (-n_bar * (1.0 - a)).exp() as f32;
            let got = arriving_spread(Vec3::splat((n_bar * beta2) as f32), direct, Vec3::splat(tf));
            let rel = (got.x as f64 - want).abs() / want;
            assert!(
                rel < 2e-3,
                "n̄ {n_bar}, ā {a}: {} against {want} ({rel:e})",
                got.x
            );
        }
    }
}

/// The limits: one crossing keeps its own spread, deep hair keeps n̄ā crossings' worth
/// (not Zinke's n̄), nothing crossed stays 0, and underflowed or zero light stays finite.
#[test]
fn arriving_spread_limits_and_hard_cases() {
    let s = arriving_spread(Vec3::splat(0.001 * 0.02), (-0.001f32).exp(), Vec3::ONE);
    assert!((s.x - 0.02).abs() < 1e-4, "{s}");
    let (n, a) = (40.0f32, 0.5f32);
    let deep = arriving_spread(
        Vec3::splat(n * 0.02),
        (-n).exp(),
        Vec3::splat((-n * (1.0 - a)).exp()),
    );
    assert!(
        (deep.x - n * a * 0.02).abs() < 1e-3 * n * a * 0.02,
        "{deep}"
    );
    assert_eq!(arriving_spread(Vec3::ZERO, 1.0, Vec3::ONE), Vec3::ZERO);
    for (direct, tf) in [
        (0.0, Vec3::ZERO),
        (0.0, Vec3::ONE),
        (1e-38, Vec3::splat(1e-38)),
    ] {
        let v = arriving_spread(Vec3::splat(3.0), direct, tf);
        assert!(
            v.is_finite() && v.min_element() >= 0.0,
            "{direct} {tf}: {v}"
        );
    }
}

/// Trap 9: a direction along ±u has no azimuth; it takes the other's (φ = 0), and the
/// angles are those of the limit along that azimuth.
#[test]
fn direction_along_tangent_has_phi_zero() {
    let u = Vec3::Y;
    let wo = Vec3::new(0.6, -0.8, 0.0);
    let a = HairAngles::from_vectors(u, u, wo).expect("valid");
    assert_eq!(a.phi, 0.0);
    assert!((a.theta_i - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
    let b = HairAngles::from_vectors(u, -u, -u).expect("valid");
    assert_eq!(b.phi, 0.0);
    assert!(HairAngles::from_vectors(Vec3::ZERO, u, wo).is_none());
    assert!(HairAngles::from_vectors(u, Vec3::splat(f32::NAN), wo).is_none());
}

/// The frame-free angles agree with the definitions: θ = asin(ω·u), φ = φo − φi.
#[test]
fn angles_match_definitions() {
    let u = Vec3::Z;
    let (ti, pi_, to, po) = (0.3f32, 0.4f32, -0.5f32, 2.9f32);
    let d = |t: f32, p: f32| Vec3::new(t.cos() * p.cos(), t.cos() * p.sin(), t.sin());
    let a = HairAngles::from_vectors(u, d(ti, pi_), d(to, po)).expect("valid");
    assert!((a.theta_i - ti).abs() < 1e-5 && (a.theta_o - to).abs() < 1e-5);
    assert!((a.phi - (po - pi_)).abs() < 1e-5, "{}", a.phi);
    // cos 2φh = cos(φi + φo) up to the frame's azimuth origin ψ: cos(φi + φo − 2ψ); the
    // frame built from u = +Z is the identity (ψ = 0).
    assert!(
        (a.cos_2phi_h - (pi_ + po).cos()).abs() < 1e-5,
        "{}",
        a.cos_2phi_h
    );
}
