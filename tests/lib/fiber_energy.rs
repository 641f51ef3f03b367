//! Physical invariants of the BCSDF: reciprocity, the hemispherical albedo with σa = 0 (white
//! furnace, brute-force quadrature), a_f + a_b ≤ 1, and the energy bookkeeping of Eq. 8.

use glam::Vec3;
use std::f64::consts::{FRAC_PI_2, PI};
use wisp::fiber::dual::{
    CosineReading, DualQuantities, lobe_integral, shares_direct, white_albedo,
};
use wisp::fiber::marschner::{Azimuth, bcsdf_exact};
use wisp::fiber::{Fiber, FiberParams, HairAngles, Lobe, LobeConstants};

/// Deterministic uniform numbers in [0, 1) (64-bit LCG, Knuth's constants).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn dir(&mut self) -> Vec3 {
        let z = 2.0 * self.next() - 1.0;
        let a = 2.0 * PI * self.next();
        let r = (1.0 - z * z).sqrt();
        Vec3::new((r * a.cos()) as f32, z as f32, (r * a.sin()) as f32)
    }
}

/// S(ωi, ωo) = S(ωo, ωi): swapping exchanges θi ↔ θo (θh unchanged, θd → −θd), φ → −φ and keeps
/// φh; every term depends on θd through sin²θd and N is even in φ.
#[test]
fn reciprocity_exact_and_tabulated() {
    let c = LobeConstants::from_params(&FiberParams::default());
    let fiber = Fiber::new(&FiberParams::default());
    let mut rng = Lcg(7);
    for _ in 0..300 {
        let (ti, to) = ((rng.next() - 0.5) * PI, (rng.next() - 0.5) * PI);
        let (pi_, po) = (rng.next() * 2.0 * PI, rng.next() * 2.0 * PI);
        let c2 = (pi_ + po).cos();
        let a = bcsdf_exact(&c, ti, to, po - pi_, c2);
        let b = bcsdf_exact(&c, to, ti, pi_ - po, c2);
        for l in 0..3 {
            for ch in 0..3 {
                let (x, y) = (a[l][ch], b[l][ch]);
                assert!(
                    (x - y).abs() <= 1e-9 * x.abs().max(1e-12),
                    "lobe {l}: {x} vs {y}"
                );
            }
        }
    }
    let u = Vec3::new(0.3, 0.9, -0.2).normalize();
    for _ in 0..1000 {
        let (wi, wo) = (rng.dir(), rng.dir());
        let a = fiber.bcsdf(&HairAngles::from_vectors(u, wi, wo).expect("unit"));
        let b = fiber.bcsdf(&HairAngles::from_vectors(u, wo, wi).expect("unit"));
        let tol = 1e-5 * a.max_element().max(1e-6);
        assert!((a - b).abs().max_element() <= tol, "{a} vs {b}");
    }
}

/// Hemispherical albedo ρ(θi) = ∫ S cos θo dωo = ∫∫ S cos²θo dθo dφ by midpoint quadrature
/// (0.5° in θo, 1° in φ) of the exact BCSDF, channel 0.
fn albedo(c: &LobeConstants, theta_i: f64, cos_2phi_h: f64) -> f64 {
    let (n_t, n_p) = (360, 360);
    let (dt, dp) = (PI / n_t as f64, 2.0 * PI / n_p as f64);
    let mut sum = 0.0;
    for i in 0..n_t {
        let to = -FRAC_PI_2 + (i as f64 + 0.5) * dt;
        let w = to.cos().powi(2) * dt * dp;
        for j in 0..n_p {
            let phi = -PI + (j as f64 + 0.5) * dp;
            let s = bcsdf_exact(c, theta_i, to, phi, cos_2phi_h);
            sum += (s[0][0] + s[1][0] + s[2][0]) * w;
        }
    }
    sum
}

/// White furnace (σa = 0). Measured with this quadrature (default fibre, eccentricity 1):
/// ρ = 0.93 at θ = 0, 1.020 at θ = 60° (max for |θ| ≤ 70°), 0.69 at −60°, and 1.79 at θ = −89.9°;
/// for β_R = 1°, 1.054 at 60° and 2.23 at −89.9°. Marschner's S is not energy conserving at
/// grazing incidence (its 1/cos²θd with lobes cut at θo = ±90°). Documented bound: ρ ≤ 1.06 for
/// |θi| ≤ 70° and ρ ≤ 2.5 everywhere (β_R from 1° to 30°). The dual tables divide by
/// max(1, ρ) (dual.rs, "White-furnace normalisation").
#[test]
fn white_furnace_albedo_bound() {
    let p = FiberParams {
        sigma_a: [0.0; 3],
        eccentricity: 1.0,
        ..Default::default()
    };
    let c = LobeConstants::from_params(&p);
    let fiber = Fiber::new(&p);
    for deg in [
        0.0f64, 30.0, -30.0, 60.0, -60.0, 70.0, 80.0, -80.0, 89.9, -89.9,
    ] {
        let t = deg.to_radians();
        let rho = albedo(&c, t, 1.0);
        assert!(rho.is_finite() && rho > 0.5, "θ={deg}: {rho}");
        if deg.abs() <= 70.0 {
            assert!(rho <= 1.06, "θ={deg}: ρ = {rho}");
        }
        assert!(rho <= 2.5, "θ={deg}: ρ = {rho}");
        // For a circular fibre the albedo does not depend on φi, so the ā_f + ā_b of the
        // outgoing-cosine reading (trap 4) before normalisation is this same integral.
        let sum = shares_direct(&c, t, CosineReading::Outgoing).albedo();
        assert!(
            (sum - rho).abs() < 0.01 * rho,
            "θ={deg}: ā_f + ā_b = {sum}, ρ = {rho}"
        );
        // The tables never exceed 1, and equal min(1, ρ) for a white fibre.
        let t_q = fiber.dual_tables().quantities_at(t);
        assert!(t_q.a_f[0] + t_q.a_b[0] <= 1.0 + 1e-12);
    }
    for beta in [1.0f32, 30.0] {
        let c = LobeConstants::from_params(&FiberParams {
            beta_r_deg: beta,
            ..p.clone()
        });
        for deg in [0.0f64, 60.0, -89.9, 89.9] {
            let rho = shares_direct(&c, deg.to_radians(), CosineReading::Outgoing).albedo();
            assert!(
                rho <= 2.5 && (deg.abs() > 70.0 || rho <= 1.06),
                "β={beta} θ={deg}: {rho}"
            );
        }
    }
}

/// ā_f + ā_b ≤ 1 at every grid θ, for light, dark, narrow and wide fibres (table values).
#[test]
fn a_f_plus_a_b_at_most_one() {
    for p in [
        FiberParams {
            sigma_a: [0.0; 3],
            ..Default::default()
        },
        FiberParams::default(),
        FiberParams {
            beta_r_deg: 1.0,
            sigma_a: [0.0; 3],
            ..Default::default()
        },
        FiberParams {
            beta_r_deg: 30.0,
            sigma_a: [0.0; 3],
            ..Default::default()
        },
    ] {
        let f = Fiber::new(&p);
        for q in &f.dual_tables().at {
            for ch in 0..3 {
                assert!(q.a_f[ch] + q.a_b[ch] <= 1.0 + 1e-12, "{p:?}: {q:?}");
            }
        }
    }
}

/// ∫_a^b f(φ) dφ with φ = a + (b − a)(1 − cos πu)/2 and midpoint nodes in u: nodes cluster
/// at both ends like u², which turns an |φ − a|^{−1/2} end singularity into a bounded integrand.
fn integrate_clustered(a: f64, b: f64, n: usize, f: impl Fn(f64) -> f64) -> f64 {
    let du = 1.0 / n as f64;
    (0..n)
        .map(|k| {
            let u = (k as f64 + 0.5) * du;
            let phi = a + (b - a) * 0.5 * (1.0 - (PI * u).cos());
            f(phi) * (b - a) * 0.5 * PI * (PI * u).sin() * du
        })
        .sum()
}

/// Eq. 8 bookkeeping: ∫ N_p(φ) dφ over the circle (quadrature in φ of the exact, root-solved
/// raw N_p, split at the caustics ±φc and clustered at the split points) equals ∫ A(p, h) dh / 2
/// (midpoint in γi, h = sin γi), per lobe: relative 1e-5.
#[test]
fn n_p_integrates_to_a_dh_over_2() {
    let c = LobeConstants::from_params(&FiberParams::default());
    for td_deg in [0.0f64, 25.0, 46.0, 60.0] {
        let az = Azimuth::new(c.eta, td_deg.to_radians().sin(), c.sigma_a);
        for p in 0..3u32 {
            let phi_c = if p == 2 && az.eta_prime < 2.0 {
                az.caustic(&c).phi_c
            } else {
                0.0
            };
            let mut cuts = vec![-PI, -phi_c, phi_c, PI];
            cuts.dedup();
            let by_phi: f64 = cuts
                .windows(2)
                .map(|w| integrate_clustered(w[0], w[1], 20_000, |phi| az.n_raw(p, phi)[0]))
                .sum();
            let m = 20_000;
            let dg = PI / m as f64;
            let by_h: f64 = (0..m)
                .map(|k| {
                    let g = -FRAC_PI_2 + (k as f64 + 0.5) * dg;
                    az.attenuation(p, g)[0] * g.cos() * dg / 2.0
                })
                .sum();
            assert!(
                (by_phi - by_h).abs() <= 1e-5 * by_h,
                "θd={td_deg} p={p}: {by_phi} vs {by_h}"
            );
        }
    }
}

/// The smoothed TRT lobe (§5.2.2) does not conserve Eq. 8's energy exactly: it removes the
/// caustic power with notches and adds k_G-scaled glints. Measured here for the default fibre
/// (k_G = 0.5): smoothed/raw = 0.59 at θd = 0, 0.43 at 30°, 0.48 at 46° (merge), 1.00 once the
/// caustic has faded (θd ≥ 60°): the notches remove more power than the k_G = 0.5 glints put
/// back. Asserted range [0.4, 1.0 + 1e-6]. The renderer's tables use the smoothed lobe, as the
/// paper does.
#[test]
fn smoothed_trt_energy_is_close_to_raw() {
    let c = LobeConstants::from_params(&FiberParams::default());
    for td_deg in [0.0f64, 30.0, 46.0, 50.0, 70.0] {
        let s = td_deg.to_radians().sin();
        let smoothed = lobe_integral(&c, Lobe::TRT, s, |_| 1.0)[0];
        let az = Azimuth::new(c.eta, s, c.sigma_a);
        let m = 20_000;
        let dg = PI / m as f64;
        let raw: f64 = (0..m)
            .map(|k| {
                let g = -FRAC_PI_2 + (k as f64 + 0.5) * dg;
                az.attenuation(2, g)[0] * g.cos() * dg / 2.0
            })
            .sum();
        let ratio = smoothed / raw;
        assert!((0.4..=1.0 + 1e-6).contains(&ratio), "θd={td_deg}: {ratio}");
    }
}

/// DualQuantities from direct lobe shares, for use by the colour-ordering test.
fn direct_quantities(p: &FiberParams, deg: f64) -> DualQuantities {
    let c = LobeConstants::from_params(p);
    let t = deg.to_radians();
    DualQuantities::from_shares(
        &c,
        &shares_direct(&c, t, CosineReading::Outgoing),
        white_albedo(&c, t),
    )
}

/// Lighter absorption gives larger ā_f in every channel (at every table θ), and brown hair
/// (pbrt eumelanin 1.3: σa = [0.545, 0.906, 1.78]) has ā_f red > green > blue.
#[test]
fn color_ordering() {
    let brown = Fiber::new(&FiberParams::default());
    let light = Fiber::new(&FiberParams {
        sigma_a: [0.2, 0.35, 0.7],
        ..Default::default()
    });
    for (qb, ql) in brown.dual_tables().at.iter().zip(&light.dual_tables().at) {
        for ch in 0..3 {
            assert!(ql.a_f[ch] > qb.a_f[ch], "{:?} vs {:?}", ql.a_f, qb.a_f);
        }
        assert!(
            qb.a_f[0] > qb.a_f[1] && qb.a_f[1] > qb.a_f[2],
            "{:?}",
            qb.a_f
        );
    }
    let q = direct_quantities(&FiberParams::default(), 0.0);
    assert!(q.a_f[0] > q.a_f[1] && q.a_f[1] > q.a_f[2]);
}

/// The TRT energy a circular fibre sends into |φ| ≤ `window` (radians) at θd, channel 0: the
/// smoothed lobe of §5.2.2 (notches + glints, as the tables use it) and the raw Eq. 8 lobe
/// integrated in h with no caustic clamp (200 000 midpoint nodes in γi).
fn trt_energy(p: &FiberParams, theta_d_deg: f64, window: f64) -> (f64, f64) {
    let c = LobeConstants::from_params(&FiberParams {
        eccentricity: 1.0,
        ..p.clone()
    });
    let s = theta_d_deg.to_radians().sin();
    let inside = |phi: f64| {
        if wisp::fiber::marschner::wrap_pi(phi).abs() <= window {
            1.0
        } else {
            0.0
        }
    };
    let smoothed = wisp::fiber::dual::LobeSamples::new(&c, Lobe::TRT, s, 8192).integral(inside)[0];
    let az = Azimuth::new(c.eta, s, c.sigma_a);
    let n = 200_000;
    let dg = PI / n as f64;
    let raw: f64 = (0..n)
        .map(|k| {
            let g = -FRAC_PI_2 + (k as f64 + 0.5) * dg;
            az.attenuation(2, g)[0] * g.cos() * dg * 0.5 * inside(az.phi(2, g))
        })
        .sum();
    (smoothed, raw)
}

/// Issue 14 item 1, the presets' caustic parameters. Marschner's smoothing replaces the TRT
/// caustic by a notch (removing the fold's energy) and two glints t k_G A(h_c) Δh g(φ ∓ φc; w_c).
/// Near a fold N = A/√(2|φ''||φ − φc|), so the notch removes A √(w_c/|φ''|) 2^{−5/4} Γ(¼) per
/// caustic, while a glint adds k_G A Δh with Δh = 2√(2w_c/|φ''|): they balance at
/// k_G = 2^{−5/4} Γ(¼)/(2√2) = 0.539 for any w_c and θd, provided Δh_M does not clip Δh. Δh_M
/// is only needed where φ'' → 0 (the merge, θd ≈ 46.9°).
///
/// Measured (σa = 0.2, circular fibre), TRT energy smoothed / raw (raw: Eq. 8 integrated in h,
/// no clamp) over the glint window |φ| ≤ 20° and over the circle, θd = 0…55°:
/// - paper defaults k_G 0.5, w_c 15°, Δh_M 0.5 (the presets until now): window 0.33–0.37 before
///   the merge (0.42 in the fade after it), total 0.44–0.58 (the glint 2.7–3× too weak, as the
///   issue measured);
/// - the k_G 1, w_c 5°, Δh_M 2: window 1.03–2.4, total 1.31–2.2 (creates energy);
/// - **chosen** k_G 0.54, w_c 5°, Δh_M 0.7: window 0.78–1.00, total 0.81–1.00 (Δh_M clips only
///   from θd ≈ 35°; with Δh_M 1 or 2 the merge overshoots to 1.17 and 1.86).
///
/// w_c = 5° is below Table 1's 10–25°: a 15° glint centred on φc = 18.6° (θd = 0) puts a third
/// of the caustic's energy beyond the raw lobe's reach (19.3°). The N_TRT table error with it is
/// 1.9e-3 (peak 0.059; 5.7e-4 of 0.026 with the paper's values).
#[test]
fn preset_caustics_conserve_trt_energy() {
    let k = 2f64.powf(-1.25) * 3.625_609_908_221_908 / (2.0 * 2f64.sqrt());
    assert!((k - 0.539).abs() < 5e-4, "{k}");
    // The balance itself: unclipped (Δh_M 2) with a narrow w_c, the smoothing keeps the energy.
    let balanced = FiberParams {
        sigma_a: [0.2; 3],
        k_g: k as f32,
        w_c_deg: 2.0,
        delta_h_m: 2.0,
        ..Default::default()
    };
    let (s, r) = trt_energy(&balanced, 0.0, PI);
    assert!((s / r - 1.0).abs() < 0.03, "balanced smoothing: {}", s / r);
    let window = 20f64.to_radians();
    let thetas = [0.0, 15.0, 30.0, 40.0, 44.0, 46.0, 48.0, 50.0, 55.0];
    let paper = FiberParams {
        sigma_a: [0.2; 3],
        ..Default::default()
    };
    for td in thetas {
        let (s, r) = trt_energy(&paper, td, window);
        println!("paper values θd={td}: window {:.3}", s / r);
        if td < 46.9 {
            assert!(s / r < 0.4, "paper values θd={td}: window {}", s / r);
        }
    }
    for name in ["smooth", "curly"] {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("hairstyles")
            .join(format!("{name}.json"));
        let style: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&path).expect("preset")).expect("JSON");
        let fiber: FiberParams =
            serde_json::from_value(style["fiber"].clone()).expect("fibre block");
        assert_eq!(
            (fiber.k_g, fiber.w_c_deg, fiber.delta_h_m),
            (0.54, 5.0, 0.7)
        );
        let p = FiberParams {
            sigma_a: [0.2; 3],
            ..fiber
        };
        for td in thetas {
            let (sw, rw) = trt_energy(&p, td, window);
            let (st, rt) = trt_energy(&p, td, PI);
            println!("{name} θd={td}: window {:.3} total {:.3}", sw / rw, st / rt);
            assert!(
                (0.75..=1.001).contains(&(sw / rw)) && (0.8..=1.001).contains(&(st / rt)),
                "{name} θd={td}: window {}, total {}",
                sw / rw,
                st / rt
            );
        }
    }
}
