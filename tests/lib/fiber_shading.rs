//! The shading interface for both fibre models: true single scattering, the local-density
//! truncation of the back-scatter, the forward spread, Figure 5's composition, and the fibre JSON
//! (`model`, new fields, their defaults and errors).

use glam::Vec3;
use std::f32::consts::PI;
use wisp::fiber::{Fiber, FiberModel, FiberParams, HairAngles, LightAtPoint, ShadingMode};

fn fibers() -> Vec<Fiber> {
    [FiberModel::Marschner, FiberModel::Chiang]
        .into_iter()
        .map(|model| {
            Fiber::new(&FiberParams {
                model,
                sigma_a: [0.2, 0.35, 0.7],
                ..Default::default()
            })
        })
        .collect()
}

fn pairs() -> Vec<(Vec3, Vec3, Vec3)> {
    [
        (
            Vec3::new(0.1, 1.0, 0.2),
            Vec3::new(0.8, 0.3, 0.0),
            Vec3::new(-0.7, -0.2, 0.3),
        ),
        (
            Vec3::Y,
            Vec3::new(0.0, -0.5, 0.9),
            Vec3::new(0.3, 0.6, -0.7),
        ),
        (
            Vec3::new(0.3, 0.9, -0.2),
            Vec3::new(-0.4, 0.1, -0.9),
            Vec3::new(-0.5, -0.1, 0.8),
        ),
        (Vec3::X, Vec3::new(0.2, 0.0, 1.0), Vec3::new(-0.1, 0.2, 1.0)),
    ]
    .into_iter()
    .map(|(u, wi, wo)| (u.normalize(), wi.normalize(), wo.normalize()))
    .collect()
}

fn light(direct: f32, tf: f32, behind: f32) -> LightAtPoint {
    LightAtPoint {
        direct_fraction: direct,
        tf: Vec3::splat(tf),
        sigma_f2: Vec3::splat(0.03),
        crossings_behind: behind,
    }
}

fn close(a: Vec3, b: Vec3, rel: f32) -> bool {
    (a - b).abs().max_element() <= rel * a.abs().max(b.abs()).max_element().max(1e-9)
}

/// Issue 14 item 3: single scattering is S cos θi · direct_fraction (hard shadows). It no longer
/// sees T_f: a point behind hair (direct 0) that forward-scattered light still reaches (T_f =
/// 0.8) is black in single scattering; the old S cos θi T_f gave 0.8 S cos θi there.
#[test]
fn single_scattering_is_direct_light_only() {
    for fiber in fibers() {
        for (u, wi, wo) in pairs() {
            let a = HairAngles::from_vectors(u, wi, wo).expect("unit");
            let full = fiber.bcsdf(&a) * a.theta_i.cos();
            for direct in [1.0f32, 0.3] {
                let s = fiber.shade(
                    ShadingMode::SingleScattering,
                    u,
                    wi,
                    wo,
                    &light(direct, 1.0, 5.0),
                );
                assert!(
                    close(s, full * direct, 2e-5),
                    "{:?}: {s} vs {}",
                    fiber.model(),
                    full * direct
                );
            }
            let dark = fiber.shade(
                ShadingMode::SingleScattering,
                u,
                wi,
                wo,
                &light(0.0, 0.8, 5.0),
            );
            assert_eq!(dark, Vec3::ZERO);
            assert!(full.max_element() > 0.0);
        }
    }
}

/// The local back-scatter follows the hair behind the point (`crossings_behind`): none for an
/// isolated fibre (dual = single in full light), Zinke's full term for dense hair (+∞ is exactly
/// the default), and in between it grows with the crossings behind.
#[test]
fn back_scatter_follows_local_density() {
    for fiber in fibers() {
        for (u, wi, wo) in pairs() {
            let single = fiber.shade(
                ShadingMode::SingleScattering,
                u,
                wi,
                wo,
                &light(1.0, 1.0, 0.0),
            );
            let isolated = fiber.shade(
                ShadingMode::DualScattering,
                u,
                wi,
                wo,
                &light(1.0, 1.0, 0.0),
            );
            assert!(
                close(isolated, single, 1e-6),
                "{:?}: {isolated} vs {single}",
                fiber.model()
            );
            let dense = fiber.shade(
                ShadingMode::DualScattering,
                u,
                wi,
                wo,
                &light(0.4, 0.7, LightAtPoint::DENSE),
            );
            let default = fiber.shade(
                ShadingMode::DualScattering,
                u,
                wi,
                wo,
                &LightAtPoint {
                    direct_fraction: 0.4,
                    tf: Vec3::splat(0.7),
                    sigma_f2: Vec3::splat(0.03),
                    ..LightAtPoint::UNSHADOWED
                },
            );
            assert_eq!(dense, default);
            let mut prev = fiber.shade(
                ShadingMode::DualScattering,
                u,
                wi,
                wo,
                &light(0.4, 0.7, 0.0),
            );
            for n in [0.5f32, 1.0, 2.0, 4.0, 10.0, 1e4] {
                let v = fiber.shade(ShadingMode::DualScattering, u, wi, wo, &light(0.4, 0.7, n));
                assert!(
                    v.cmpge(prev - Vec3::splat(1e-7)).all(),
                    "n={n}: {v} < {prev}"
                );
                prev = v;
            }
            assert!(close(prev, dense, 1e-4), "{prev} vs {dense}");
            assert!(dense.max_element() > 0.0);
        }
    }
}

/// Figure 5's composition holds for both models: with d_b = 0 in full light the dual shader is the
/// single-scattering shader, and the scattered path is linear in T_f − direct_fraction at a
/// fixed spread (here none: the spread of the light that arrives depends on T_f itself,
/// `shader::arriving_spread`, tested in the library).
#[test]
fn dual_composition_both_models() {
    for model in [FiberModel::Marschner, FiberModel::Chiang] {
        let fiber = Fiber::new(&FiberParams {
            model,
            d_b: 0.0,
            ..Default::default()
        });
        for (u, wi, wo) in pairs() {
            let d = fiber.shade(
                ShadingMode::DualScattering,
                u,
                wi,
                wo,
                &LightAtPoint::UNSHADOWED,
            );
            let s = fiber.shade(
                ShadingMode::SingleScattering,
                u,
                wi,
                wo,
                &LightAtPoint::UNSHADOWED,
            );
            assert!(close(d, s, 1e-6), "{model:?}: {d} vs {s}");
            let a = fiber.shade(
                ShadingMode::DualScattering,
                u,
                wi,
                wo,
                &LightAtPoint {
                    sigma_f2: Vec3::ZERO,
                    ..light(0.0, 0.2, 9.0)
                },
            );
            let b = fiber.shade(
                ShadingMode::DualScattering,
                u,
                wi,
                wo,
                &LightAtPoint {
                    sigma_f2: Vec3::ZERO,
                    ..light(0.0, 0.6, 9.0)
                },
            );
            assert!(close(b, 3.0 * a, 1e-5), "{model:?}: {a} {b}");
            assert!(b.max_element() > 0.0);
        }
    }
}

/// The forward spread (Eq. 7's s̃_f window): at 180° forward-scattered light arrives from every
/// azimuth, so N^G is flat in φ and equals ∫N dφ/(2π); at Zinke's 90° TT's N^G still prefers
/// φ ≈ π. Both models.
#[test]
fn forward_spread_window() {
    for model in [FiberModel::Marschner, FiberModel::Chiang] {
        let iso = Fiber::new(&FiberParams {
            model,
            forward_spread_deg: 180.0,
            ..Default::default()
        });
        let zinke = Fiber::new(&FiberParams {
            model,
            ..Default::default()
        });
        for key in [0.0f32, 0.4, 1.2] {
            for l in 0..iso.dual_tables().n_g_lobes() {
                let values: Vec<f32> = (0..=36)
                    .map(|k| iso.dual_tables().n_g_lobe(l, key, PI * k as f32 / 36.0).x)
                    .collect();
                let mean = values.iter().sum::<f32>() / values.len() as f32;
                for v in &values {
                    assert!(
                        (v - mean).abs() <= 2e-3 * mean.max(1e-4),
                        "{model:?} lobe {l}: {values:?}"
                    );
                }
            }
            let d = zinke.dual_tables();
            assert!(
                d.n_g_lobe(1, key, PI).x > 2.0 * d.n_g_lobe(1, key, 0.0).x,
                "{model:?}"
            );
        }
    }
}

/// The fibre JSON: `model` is "marschner" (default) or "chiang"; the new fields have their
/// documented defaults; a bad value is refused naming the field and the rule.
#[test]
fn fiber_json_model_and_new_fields() {
    let p: FiberParams = serde_json::from_str(r#"{"model": "chiang", "azimuthal_roughness": 0.5}"#)
        .expect("valid fibre JSON");
    assert_eq!(p.model, FiberModel::Chiang);
    assert_eq!(p.azimuthal_roughness, 0.5);
    assert!(p.validate().is_ok());
    let d: FiberParams = serde_json::from_str("{}").expect("defaults");
    assert_eq!(d.model, FiberModel::Marschner);
    assert_eq!((d.azimuthal_roughness, d.forward_spread_deg), (0.3, 90.0));
    assert_eq!((d.d_f, d.d_b), (1.0, 0.5));
    let e =
        serde_json::from_str::<FiberParams>(r#"{"model": "kajiya"}"#).expect_err("unknown model");
    assert!(e.to_string().contains("unknown variant"), "{e}");
    for (p, prefix) in [
        (
            FiberParams {
                azimuthal_roughness: 0.0,
                ..Default::default()
            },
            "azimuthal_roughness must be in [0.01, 1]",
        ),
        (
            FiberParams {
                forward_spread_deg: 200.0,
                ..Default::default()
            },
            "forward_spread_deg must be in [1, 180]",
        ),
    ] {
        let e = p.validate().expect_err("must be refused");
        assert!(e.starts_with(prefix), "{e}");
    }
    // The longitudinal roughness Mitsuba needs for this fibre's R lobe (MAPPING.md: β_R = 7.5°
    // gives b = 0.276).
    assert!((FiberParams::default().chiang_longitudinal_roughness() - 0.276).abs() < 1e-3);
}

/// The forward-scattered light's fluence per unit flux (`dual::window_fluence`) against a
/// brute-force sum over directions: light spread uniformly in azimuth ψ over the window and,
/// independently, over inclinations θ (a Gaussian of 20°, any spread gives the same), each
/// direction delivering L cos θ to a fibre's projected width and carrying L cos θ |cos ψ|
/// along the shadow path. Midpoint sums of 2,000 × 400 nodes; asserted to 1e-4 relative.
/// Limits: 1 for a beam, π/2 for Zinke's 90° and for isotropic light (180°), continuous at 90°.
#[test]
fn window_fluence_is_fluence_over_flux() {
    use wisp::fiber::dual::window_fluence;
    let brute = |w: f64| {
        let (n_psi, n_theta) = (2000, 400);
        let (mut fluence, mut flux) = (0.0f64, 0.0f64);
        for i in 0..n_psi {
            let psi = -w + (i as f64 + 0.5) * 2.0 * w / n_psi as f64;
            for j in 0..n_theta {
                let theta = -1.5 + (j as f64 + 0.5) * 3.0 / n_theta as f64;
                let weight = (-0.5 * (theta / 20f64.to_radians()).powi(2)).exp();
                fluence += weight * theta.cos();
                flux += weight * theta.cos() * psi.cos().abs();
            }
        }
        fluence / flux
    };
    for deg in [1.0f64, 30.0, 60.0, 89.0, 90.0, 91.0, 120.0, 179.0] {
        let w = deg.to_radians();
        let (got, want) = (window_fluence(w), brute(w));
        assert!(
            (got - want).abs() <= 1e-4 * want,
            "w = {deg}°: {got} vs {want}"
        );
    }
    assert!((window_fluence(1e-9) - 1.0).abs() < 1e-9);
    let half_pi = std::f64::consts::FRAC_PI_2;
    assert!((window_fluence(half_pi) - half_pi).abs() < 1e-12);
    assert!((window_fluence(std::f64::consts::PI) - half_pi).abs() < 1e-12);
    let step = 1e-6;
    assert!((window_fluence(half_pi - step) - window_fluence(half_pi + step)).abs() < 1e-5);
}

/// Trap 11 for a light inclined to the fibre: Eq. 7's window lies in the shading fibre's own
/// azimuth, at the light's inclination θi. Brute force over the window's directions, built as
/// 3-vectors: the fibre intercepts cos θi of each (its projected width), the shadow path
/// carries |ω · ω_light| of each; fluence ÷ flux is their ratio. It is w/sin w across the
/// fibre, 1 along it, and falls monotonically between.
#[test]
fn an_inclined_light_s_window_fluence_is_fluence_over_flux() {
    use wisp::fiber::dual::{window_fluence, window_fluence_inclined};
    let brute = |w: f64, theta_i: f64| {
        let light = [theta_i.sin(), theta_i.cos(), 0.0];
        let n = 20_000;
        let (mut fluence, mut flux) = (0.0f64, 0.0f64);
        for k in 0..n {
            let psi = -w + (k as f64 + 0.5) * 2.0 * w / n as f64;
            let d = [
                theta_i.sin(),
                theta_i.cos() * psi.cos(),
                theta_i.cos() * psi.sin(),
            ];
            let along_axis = d[0];
            fluence += (1.0 - along_axis * along_axis).sqrt();
            flux += theta_i.cos() * (d[0] * light[0] + d[1] * light[1] + d[2] * light[2]).abs();
        }
        fluence / flux
    };
    for w_deg in [10.0f64, 45.0, 90.0, 120.0, 179.0] {
        let w = w_deg.to_radians();
        let mut last = f64::INFINITY;
        for t_deg in [0.0f64, 10.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0] {
            let t = t_deg.to_radians();
            let s2 = t.sin().powi(2);
            let (got, want) = (window_fluence_inclined(w, s2), brute(w, t));
            assert!(
                (got - want).abs() <= 1e-6 * want,
                "w = {w_deg}°, θi = {t_deg}°: {got} vs {want}"
            );
            // Monotone up to Zinke's 90°; wider windows count backward flux too.
            assert!(
                w_deg > 90.0 || got <= last + 1e-12,
                "not monotone at w = {w_deg}°, θi = {t_deg}°"
            );
            last = got;
        }
        assert_eq!(window_fluence_inclined(w, 0.0), window_fluence(w));
        assert!((window_fluence_inclined(w, 1.0) - 1.0).abs() < 1e-12);
    }
}

/// The shader's per-fibre table of d_f × the inclined window's fluence follows the closed form
/// to 3e-5 (relative) between its nodes and at them for windows up to 90° (1e-3 wider, where
/// the flux counted both ways has a kink), and stays finite and in [d_f, d_f × its value
/// across the fibre] for any sin θi, out-of-range ones included.
#[test]
fn the_gain_table_follows_the_closed_form() {
    use wisp::fiber::dual::{ScatteredGain, window_fluence_inclined};
    for (d_f, w_deg) in [(1.0f64, 90.0f64), (0.7, 90.0), (1.0, 30.0), (1.0, 150.0)] {
        let w = w_deg.to_radians();
        let table = ScatteredGain::new(d_f, w);
        for k in 0..=1000 {
            let si = -1.0 + 2.0 * k as f64 / 1000.0;
            let want = d_f * window_fluence_inclined(w, si * si);
            let got = table.at(si as f32) as f64;
            let tol = if w_deg <= 90.0 { 3e-5 } else { 1e-3 };
            assert!(
                (got - want).abs() <= tol * want,
                "d_f {d_f}, w {w_deg}°, sin θi {si}: {got} vs {want}"
            );
        }
        let hi = (d_f * window_fluence_inclined(w, 0.0)) as f32;
        for si in [1.5f32, -7.0, f32::INFINITY, f32::NEG_INFINITY] {
            let g = table.at(si);
            assert!(
                g.is_finite() && g >= d_f as f32 * 0.99999 && g <= hi * 1.00001,
                "{si}: {g}"
            );
        }
    }
}
