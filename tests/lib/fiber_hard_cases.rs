//! Hard cases of the fibre model: grazing and exactly ±90° angles, the caustic merge, h → ±1,
//! φ exactly at ±φc, extreme absorption, lobe widths and eccentricities, degenerate vectors.
//! Every value must be finite and inside the bound stated next to it (with its derivation).

use glam::Vec3;
use std::f64::consts::PI;
use wisp::fiber::marschner::{Azimuth, bcsdf_exact, eta_star, gaussian, n_lobe};
use wisp::fiber::{
    Fiber, FiberModel, FiberParams, HairAngles, LightAtPoint, Lobe, LobeConstants, ShadingMode,
};

const THETAS_DEG: [f64; 11] = [
    0.0, 45.0, -45.0, 80.0, -80.0, 89.9, -89.9, 90.0, -90.0, 30.0, -60.0,
];
const PHIS_DEG: [f64; 9] = [0.0, 10.0, -25.0, 45.0, 90.0, -120.0, 170.0, 180.0, -180.0];

fn finite3(v: [f64; 3]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// Analytic bounds on the azimuthal lobes for A ≤ 1:
/// N_R = A cos γi / 4 ≤ 1/4; N_TT = A cos γi / (2|dφ/dγi|) with |dφ/dγi| ≥ 2 − 2/η' (cos γi ≤
/// cos γt), so N_TT ≤ 1 / (4 (1 − 1/η')); smoothed N_TRT: glints ≤ t k_G Δh_M · 2 g(0, w_c) plus
/// the notched raw term; bound 2.0 (measured max 0.175 over θd, φ, cos 2φh grids for σa = 0,
/// eccentricity 0.85, 1, 1/0.85 and β_R = 1°).
fn n_bound(lobe: Lobe, eta_prime: f64, c: &LobeConstants) -> f64 {
    match lobe {
        Lobe::R => 0.25 + 1e-12,
        Lobe::TT => 1.0 / (4.0 * (1.0 - 1.0 / eta_prime)) + 1e-12,
        Lobe::TRT => 2.0 + c.k_g * c.delta_h_m * 2.0 * gaussian(0.0, c.w_c),
    }
}

fn check_params(p: &FiberParams) {
    assert!(p.validate().is_ok(), "{p:?}");
    let c = LobeConstants::from_params(p);
    // M ≤ its peak 1/(√(2π) 2β_TT) (unit-area Gaussian of std 2β); 1/cos²θd ≤ 10⁴ (trap 9).
    let m_max = gaussian(0.0, 2.0 * c.beta[1]);
    for &ti in &THETAS_DEG {
        for &to in &THETAS_DEG {
            for &ph in &PHIS_DEG {
                for cos_2phi_h in [-1.0, 0.0, 1.0] {
                    let s = bcsdf_exact(
                        &c,
                        ti.to_radians(),
                        to.to_radians(),
                        ph.to_radians(),
                        cos_2phi_h,
                    );
                    for lobe in Lobe::ALL {
                        let v = s[lobe as usize];
                        assert!(finite3(v), "{lobe:?} θi={ti} θo={to} φ={ph}: {v:?}");
                        assert!(v.iter().all(|x| *x >= 0.0));
                        let td = 0.5 * (to - ti).to_radians();
                        let az =
                            wisp::fiber::marschner::azimuth_for(&c, lobe, td.sin(), cos_2phi_h);
                        let bound = m_max * n_bound(lobe, az.eta_prime, &c) * 1e4;
                        assert!(v.iter().all(|x| *x <= bound), "{lobe:?} {v:?} > {bound}");
                        let n = n_lobe(&c, lobe, td.sin(), ph.to_radians(), cos_2phi_h);
                        let nb = n_bound(lobe, az.eta_prime, &c);
                        assert!(n.iter().all(|x| *x <= nb), "{lobe:?} N={n:?} > {nb}");
                    }
                }
            }
        }
    }
    let fiber = Fiber::new(p);
    check_fiber(&fiber);
}

fn check_fiber(fiber: &Fiber) {
    let d = fiber.dual_tables();
    for q in &d.at {
        for ch in 0..3 {
            assert!((0.0..1.0).contains(&q.a_f[ch]), "a_f {:?}", q.a_f);
            assert!(q.a_b[ch] >= 0.0 && q.a_f[ch] + q.a_b[ch] <= 1.0 + 1e-12);
            assert!(q.big_a_b[ch].is_finite() && q.big_a_b[ch] >= 0.0);
            assert!(q.delta_b[ch].is_finite());
            assert!(q.sigma_b2[ch].is_finite() && q.sigma_b2[ch] >= 0.0);
            assert!(q.beta_f2[ch].is_finite() && q.beta_f2[ch] >= 0.0);
            assert!(q.beta_b2[ch].is_finite() && q.beta_b2[ch] >= 0.0);
            // Shifts are energy-weighted means of the lobe shifts: inside their range.
            let means: Vec<f64> = match fiber.model() {
                FiberModel::Marschner => {
                    let c = fiber.lobe_constants();
                    (0..3).map(|l| 2.0 * c.alpha[l]).collect()
                }
                FiberModel::Chiang => {
                    let c = fiber.chiang_constants();
                    (0..4).map(|l| c.mean_x(l)).collect()
                }
            };
            let lo = means.iter().copied().fold(f64::MAX, f64::min);
            let hi = means.iter().copied().fold(f64::MIN, f64::max);
            assert!(q.alpha_f[ch] >= lo - 1e-12 && q.alpha_f[ch] <= hi + 1e-12);
            assert!(q.alpha_b[ch] >= lo - 1e-12 && q.alpha_b[ch] <= hi + 1e-12);
        }
    }
    for s in [
        -1.0f32,
        -0.99999,
        -0.7,
        0.0,
        0.5,
        0.99999,
        1.0,
        2.0,
        -3.0,
        f32::NAN,
    ] {
        let f = fiber.forward_scatter(s);
        assert!(f.a_f.is_finite() && f.beta_f2.is_finite());
        assert!(f.a_f.min_element() >= 0.0 && f.a_f.max_element() < 1.0);
        assert!(f.beta_f2.min_element() >= 0.0);
    }
    let u = Vec3::Y;
    let dirs = hard_directions();
    let lights = [
        LightAtPoint::UNSHADOWED,
        LightAtPoint {
            direct_fraction: 0.0,
            tf: Vec3::new(0.3, 0.2, 0.1),
            sigma_f2: Vec3::splat(0.05),
            crossings_behind: LightAtPoint::DENSE,
        },
        LightAtPoint {
            direct_fraction: 0.5,
            tf: Vec3::splat(0.2),
            sigma_f2: Vec3::ZERO,
            crossings_behind: LightAtPoint::DENSE,
        },
        LightAtPoint {
            direct_fraction: f32::NAN,
            tf: Vec3::splat(f32::INFINITY),
            sigma_f2: Vec3::splat(-1.0),
            crossings_behind: LightAtPoint::DENSE,
        },
    ];
    for mode in [
        ShadingMode::DualScattering,
        ShadingMode::SingleScattering,
        ShadingMode::KajiyaKay,
        ShadingMode::Visibility,
    ] {
        for wi in &dirs {
            for wo in &dirs {
                for light in &lights {
                    let v = fiber.shade(mode, u, *wi, *wo, light);
                    assert!(
                        v.is_finite() && v.min_element() >= 0.0,
                        "{mode:?} {wi} {wo} {v}"
                    );
                }
            }
        }
    }
}

/// `Visibility` is the shadows alone: the direct fraction for any directions (degenerate ones
/// too: a fibre with no usable tangent still has its shadow), clamped to [0, 1], NaN as 0, and
/// blind to T_f, the spread and the fibre model.
#[test]
fn visibility_is_the_direct_fraction_alone() {
    let fiber = Fiber::new(&FiberParams::default());
    let u = Vec3::Y;
    let dirs = hard_directions();
    for (direct, want) in [
        (0.0f32, 0.0f32),
        (0.37, 0.37),
        (1.0, 1.0),
        (1.5, 1.0),
        (-0.2, 0.0),
        (f32::NAN, 0.0),
        (f32::INFINITY, 0.0),
    ] {
        let light = LightAtPoint {
            direct_fraction: direct,
            tf: Vec3::new(0.9, 0.1, f32::NAN),
            sigma_f2: Vec3::splat(3.0),
            crossings_behind: 7.0,
        };
        for wi in &dirs {
            for wo in &dirs {
                for tangent in [u, Vec3::ZERO] {
                    let v = fiber.shade(ShadingMode::Visibility, tangent, *wi, *wo, &light);
                    assert_eq!(v, Vec3::splat(want), "direct {direct} {wi} {wo}");
                }
            }
        }
    }
}

/// Unit directions at the hard inclinations (±u included), plus degenerate ones.
fn hard_directions() -> Vec<Vec3> {
    let mut v = Vec::new();
    for &t in &THETAS_DEG {
        for &p in &[0.0f64, 33.0, 180.0, -90.0] {
            let (t, p) = (t.to_radians(), p.to_radians());
            v.push(Vec3::new(
                (t.cos() * p.cos()) as f32,
                t.sin() as f32,
                (t.cos() * p.sin()) as f32,
            ));
        }
    }
    v.extend([
        Vec3::Y,
        -Vec3::Y,
        Vec3::ZERO,
        Vec3::splat(f32::NAN),
        Vec3::new(1e-30, 0.0, 0.0),
    ]);
    v
}

#[test]
fn default_fiber_hard_angles() {
    check_params(&FiberParams::default());
}

#[test]
fn absorption_zero_and_hundred() {
    for s in [0.0, 100.0] {
        check_params(&FiberParams {
            sigma_a: [s; 3],
            ..Default::default()
        });
    }
    // σa = 100 per radius: every internal path is absorbed (exp(−200 cos γt) underflows except
    // at |h| → 1, where Fresnel sends almost everything back): a_f is carried by R alone.
    let f = Fiber::new(&FiberParams {
        sigma_a: [100.0; 3],
        ..Default::default()
    });
    let s = &f.dual_tables().shares[f.dual_tables().theta.len() / 2];
    assert!(
        s.forward[1][0] < 1e-6 && s.forward[2][0] < 1e-6,
        "{:?}",
        s.forward
    );
    assert!(s.forward[0][0] > 0.01);
}

#[test]
fn beta_r_from_1_to_30_degrees() {
    for b in [1.0, 2.0, 5.0, 10.0, 20.0, 30.0] {
        check_params(&FiberParams {
            beta_r_deg: b,
            ..Default::default()
        });
    }
}

#[test]
fn eccentricity_085_and_inverse() {
    for e in [0.85f32, 1.0 / 0.85] {
        check_params(&FiberParams {
            eccentricity: e,
            ..Default::default()
        });
    }
    // a and 1/a swap η₁* and η₂*, i.e. flip the sign of cos 2φh (Marschner 2003 §5.2.3).
    for c2 in [-1.0, -0.3, 0.0, 0.6, 1.0] {
        let a = eta_star(1.55, 0.85, c2);
        let b = eta_star(1.55, 1.0 / 0.85, -c2);
        assert!((a - b).abs() < 1e-12);
        assert!(a > 1.0);
    }
}

/// η' crosses 2 at |θd| = asin(√((4 − η²)/3)) = 46.87° for η = 1.55 (Eq. 4 with h_c = 0):
/// N_TRT stays finite and continuous through the merge (no jump larger than the change over
/// neighbouring steps allows).
#[test]
fn caustic_merge_crossing() {
    let c = LobeConstants::from_params(&FiberParams::default());
    let merge = ((4.0 - 1.55f64 * 1.55) / 3.0).sqrt().asin();
    assert!((merge.to_degrees() - 46.87).abs() < 0.01);
    for phi_deg in [0.0f64, 5.0, 12.0, 20.0, 40.0] {
        let mut prev: Option<f64> = None;
        for k in -200..=200 {
            let td = merge + k as f64 * 1e-4;
            let n = n_lobe(&c, Lobe::TRT, td.sin(), phi_deg.to_radians(), 1.0);
            assert!(finite3(n) && n[0] >= 0.0, "θd={td} φ={phi_deg}: {n:?}");
            if let Some(p) = prev {
                // Step of 1e-4 rad in θd: the lobe (≤ 2/rad) cannot jump by more than 0.05.
                assert!((n[0] - p).abs() < 0.05, "jump at θd={td}: {p} -> {}", n[0]);
            }
            prev = Some(n[0]);
        }
    }
    // Exactly at η' = 2: h_c = 0, d²φ/dh² = 0 and φ'(0) = 0; t = 1, notch = 0 at φ = 0.
    let s = ((4.0f64 - 1.55 * 1.55) / 3.0).sqrt();
    let az = Azimuth::new(1.55, s, c.sigma_a);
    assert!((az.eta_prime - 2.0).abs() < 1e-12);
    for phi in [0.0, 1e-9, -1e-6, 0.1] {
        assert!(finite3(az.n_trt_smoothed(&c, phi)));
    }
}

/// φ exactly at ±φc (before the merge): the notch is 0 and the raw term is infinite (trap 7);
/// the result must equal the one-sided limits.
#[test]
fn phi_exactly_at_caustic() {
    let c = LobeConstants::from_params(&FiberParams::default());
    for td_deg in [0.0f64, 20.0, 40.0, 46.0] {
        let az = Azimuth::new(1.55, td_deg.to_radians().sin(), c.sigma_a);
        let ca = az.caustic(&c);
        assert_eq!(ca.t, 1.0);
        for sign in [1.0, -1.0] {
            let at = az.n_trt_smoothed(&c, sign * ca.phi_c);
            assert!(finite3(at), "{at:?}");
            for eps in [1e-7, -1e-7] {
                let near = az.n_trt_smoothed(&c, sign * ca.phi_c + eps);
                assert!(
                    (near[0] - at[0]).abs() < 1e-3,
                    "θd={td_deg}: {at:?} vs {near:?}"
                );
            }
        }
    }
}

/// h → ±1 (γi → ±π/2): grazing entry, Fresnel → 1, N → 0, everything finite.
#[test]
fn h_to_plus_minus_one() {
    let c = LobeConstants::from_params(&FiberParams::default());
    let az = Azimuth::new(1.55, 0.3, c.sigma_a);
    for g in [PI / 2.0, -PI / 2.0, PI / 2.0 - 1e-12, -PI / 2.0 + 1e-9] {
        for p in 0..3 {
            let a = az.attenuation(p, g);
            assert!(finite3(a) && a.iter().all(|x| (0.0..=1.0).contains(x)));
            assert!(az.phi(p, g).is_finite() && az.dphi_dgamma_i(p, g).is_finite());
        }
        // Fresnel → 1 at grazing: A(0) → 1, A(p ≥ 1) → 0.
        assert!(az.attenuation(0, g)[0] > 0.999);
    }
    // φ = ±π is reached by R only at h = ∓1: N_R = A cos γi / 4 = 0 there.
    for phi in [PI, -PI] {
        let n = az.n_raw(0, phi);
        assert!(n[0].abs() < 1e-12, "{n:?}");
    }
    // TT's range edge φ = 2c is reached at h = 1: N_TT → 0 continuously.
    let cc = (1.0 / az.eta_prime).asin();
    let n = az.n_raw(1, 2.0 * cc + 1e-9);
    assert!(n[0] < 1e-3, "{n:?}");
}

/// With no forward scattering in the map (UNSHADOWED), Figure 5 reduces to the direct path:
/// (f_s + d_b f_back) cos θi; the alternative T_f·d_f reading would add d_f (1 by default) × more.
#[test]
fn dual_unshadowed_is_direct_only() {
    let fiber = Fiber::new(&FiberParams::default());
    let u = Vec3::Y;
    let wi = Vec3::new(0.8, 0.3, 0.0).normalize();
    let wo = Vec3::new(-0.7, -0.2, 0.3).normalize();
    let dual = fiber.shade(
        ShadingMode::DualScattering,
        u,
        wi,
        wo,
        &LightAtPoint::UNSHADOWED,
    );
    let single = fiber.shade(
        ShadingMode::SingleScattering,
        u,
        wi,
        wo,
        &LightAtPoint::UNSHADOWED,
    );
    // Local back-scattering only adds: dual ≥ single, and by less than the back lobe's peak.
    assert!(dual.cmpge(single).all(), "{dual} {single}");
    let a = HairAngles::from_vectors(u, wi, wo).expect("valid");
    let (ab, _, s2) = fiber.dual_tables().back_at(a.theta_i);
    let peak = ab * 2.0
        / std::f32::consts::PI
        / (0.5 * (a.theta_o - a.theta_i)).cos().powi(2)
        / (2.0 * std::f32::consts::PI * s2).powf(0.5)
        * fiber.params().d_b
        * a.theta_i.cos();
    assert!(
        (dual - single).cmple(peak * 1.0001).all(),
        "{} vs {peak}",
        dual - single
    );
    // Fully shadowed with T_f = 0: nothing.
    let dark = LightAtPoint {
        direct_fraction: 0.0,
        tf: Vec3::ZERO,
        sigma_f2: Vec3::splat(0.1),
        crossings_behind: LightAtPoint::DENSE,
    };
    assert_eq!(
        fiber.shade(ShadingMode::DualScattering, u, wi, wo, &dark),
        Vec3::ZERO
    );
}

/// Shading must not depend on how the map's light is split only through clamped garbage:
/// direct_fraction > T_f (possible with ā^n̄ averaging) gives no negative scattered share.
#[test]
fn direct_fraction_above_tf_is_clamped() {
    let fiber = Fiber::new(&FiberParams::default());
    let u = Vec3::Y;
    let wi = Vec3::new(0.8, 0.3, 0.0).normalize();
    let wo = Vec3::new(-0.7, 0.1, 0.3).normalize();
    let l1 = LightAtPoint {
        direct_fraction: 0.5,
        tf: Vec3::splat(0.2),
        sigma_f2: Vec3::ZERO,
        crossings_behind: LightAtPoint::DENSE,
    };
    let l2 = LightAtPoint {
        direct_fraction: 0.5,
        tf: Vec3::splat(0.5),
        sigma_f2: Vec3::ZERO,
        crossings_behind: LightAtPoint::DENSE,
    };
    assert_eq!(
        fiber.shade(ShadingMode::DualScattering, u, wi, wo, &l1),
        fiber.shade(ShadingMode::DualScattering, u, wi, wo, &l2)
    );
}

/// Figure 5's composition: with d_b = 0 and full direct light the dual shader is the single
/// scattering shader; the scattered path is linear in T_f − directFraction.
#[test]
fn dual_composition_properties() {
    let fiber = Fiber::new(&FiberParams {
        d_b: 0.0,
        ..Default::default()
    });
    let u = Vec3::new(0.1, 1.0, 0.2).normalize();
    let pairs = [
        (Vec3::new(0.8, 0.3, 0.0), Vec3::new(-0.7, -0.2, 0.3)),
        (Vec3::new(0.0, -0.5, 0.9), Vec3::new(0.3, 0.6, -0.7)),
        (Vec3::new(-0.4, 0.1, -0.9), Vec3::new(-0.5, -0.1, 0.8)),
    ];
    for (wi, wo) in pairs {
        let (wi, wo) = (wi.normalize(), wo.normalize());
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
        assert!(
            (d - s).abs().max_element() <= 1e-6 * s.max_element().max(1e-6),
            "{d} vs {s}"
        );
        // Linear in T_f at a fixed spread: none here, since the spread of the light that
        // arrives depends on T_f itself (`shader::arriving_spread`).
        let scattered = |t: f32| {
            let l = LightAtPoint {
                direct_fraction: 0.0,
                tf: Vec3::splat(t),
                sigma_f2: Vec3::ZERO,
                crossings_behind: LightAtPoint::DENSE,
            };
            fiber.shade(ShadingMode::DualScattering, u, wi, wo, &l)
        };
        let (a, b) = (scattered(0.2), scattered(0.6));
        assert!(
            (b - 3.0 * a).abs().max_element() <= 1e-5 * b.max_element().max(1e-6),
            "{a} {b}"
        );
        assert!(b.max_element() > 0.0);
    }
}

/// Kajiya-Kay's diffuse colour comes from σa (TT + TRT energy at normal incidence): brown hair
/// is red > green > blue, and lighter hair is brighter in every channel.
#[test]
fn kajiya_kay_color_from_absorption() {
    let u = Vec3::Y;
    let wi = Vec3::new(1.0, 0.0, 0.0);
    let wo = Vec3::new(0.0, 0.0, 1.0); // θi = θo = 0: the white specular peak adds equally
    let brown = Fiber::new(&FiberParams::default());
    let light = Fiber::new(&FiberParams {
        sigma_a: [0.1, 0.2, 0.4],
        ..Default::default()
    });
    let shade = |f: &Fiber| f.shade(ShadingMode::KajiyaKay, u, wi, wo, &LightAtPoint::UNSHADOWED);
    let (b, l) = (shade(&brown), shade(&light));
    assert!(b.x > b.y && b.y > b.z, "{b}");
    assert!(l.cmpgt(b).all(), "{l} vs {b}");
}

/// The Chiang model where it breaks: grazing and exactly ±90° angles (every pair of
/// `hard_directions`, degenerate vectors included), σa = 0 and 1000, longitudinal roughness
/// β_R = 0.5° (v_TT = 7.6e-5 rad²) and 45°, azimuthal roughness 0.01 (s = 0.1°) and 1 (s = 4.3
/// rad, near uniform), tilt ±20°, η near 1 and 3.9. Every table value and every shaded value is
/// finite and non-negative (`check_fiber`), and the BCSDF is finite everywhere.
#[test]
fn chiang_hard_cases() {
    let base = FiberParams {
        model: FiberModel::Chiang,
        ..Default::default()
    };
    let cases = [
        base.clone(),
        FiberParams {
            sigma_a: [0.0; 3],
            ..base.clone()
        },
        FiberParams {
            sigma_a: [1000.0; 3],
            ..base.clone()
        },
        FiberParams {
            beta_r_deg: 0.5,
            azimuthal_roughness: 0.01,
            ..base.clone()
        },
        FiberParams {
            beta_r_deg: 45.0,
            azimuthal_roughness: 1.0,
            ..base.clone()
        },
        FiberParams {
            alpha_r_deg: 20.0,
            eta: 1.01,
            ..base.clone()
        },
        FiberParams {
            alpha_r_deg: -20.0,
            eta: 3.9,
            ..base.clone()
        },
    ];
    for p in cases {
        assert!(p.validate().is_ok(), "{p:?}");
        let fiber = Fiber::new(&p);
        check_fiber(&fiber);
        for wi in hard_directions() {
            for wo in hard_directions() {
                if let Some(a) = HairAngles::from_vectors(Vec3::Y, wi, wo) {
                    let s = fiber.bcsdf(&a);
                    assert!(
                        s.is_finite() && s.min_element() >= 0.0,
                        "{p:?} {wi} {wo}: {s}"
                    );
                }
            }
        }
    }
}
