//! The sampler against the model it samples: per-sample weights in a white furnace, and
//! expectations of test functions against direct quadrature of the far-field lobes.

use super::*;
use crate::fiber::chiang::n_bar_direct;
use crate::fiber::{FiberModel, FiberParams};
use crate::rng::SplitMix64;

fn constants(sigma_a: [f32; 3], alpha_r_deg: f32) -> ChiangConstants {
    ChiangConstants::from_params(&FiberParams {
        model: FiberModel::Chiang,
        sigma_a,
        alpha_r_deg,
        ..Default::default()
    })
}

fn xi(rng: &mut SplitMix64) -> [f64; 5] {
    std::array::from_fn(|_| rng.open_unit_f64())
}

/// Unit direction at inclination θ to u = +Z and azimuth φ from +X (the frame `ScatterSampler::sample`
/// builds for `from` in the XZ plane at φ = 0).
fn dir(theta: f64, phi: f64) -> DVec3 {
    DVec3::new(
        theta.cos() * phi.cos(),
        theta.cos() * phi.sin(),
        theta.sin(),
    )
}

#[test]
fn white_fiber_weights_are_one_and_directions_unit() {
    // σa = 0: Σ_p A_p = 1 at every h, so the weight A_p / P_p is exactly 1 per sample.
    let c = constants([0.0; 3], -7.5);
    let sampler = ScatterSampler::new(&c);
    let mut rng = SplitMix64::new(3);
    for k in 0..20_000 {
        let from = dir(-1.5 + 3.0 * (k as f64 / 20_000.0), 0.0);
        let s = sampler
            .sample(DVec3::Z, from, xi(&mut rng))
            .expect("a sample");
        assert!((s.dir.length() - 1.0).abs() < 1e-12, "{:?}", s.dir);
        for w in s.weight {
            assert!((w - 1.0).abs() < 1e-12, "weight {w} at sample {k}");
        }
    }
}

#[test]
fn logistic_sample_inverts_its_cdf() {
    for s in [0.05, 0.3, 1.0, 3.0] {
        let l = TrimmedLogistic::new(s);
        for k in 0..=100 {
            let xi = k as f64 / 100.0;
            let x = l.sample(xi);
            assert!((-PI..=PI).contains(&x));
            assert!(
                (l.cdf(x) - xi).abs() < 1e-9,
                "s {s} ξ {xi}: C({x}) = {}",
                l.cdf(x)
            );
        }
    }
}

/// E[weight · g(direction)] by Monte Carlo against Σ_p ∫∫ M_p(θ, θ_from) N̄_p(θ_from, φ) g cos θ
/// dθ dφ by midpoint quadrature (N̄_p itself by quadrature over the offset, `n_bar_direct`):
/// the sampler draws the far-field model averaged over the fibre's width, lobes, tilt and
/// absorption included.
#[test]
fn expectations_match_quadrature_of_the_far_field_model() {
    let c = constants([0.545, 0.906, 1.78], -7.5);
    let sampler = ScatterSampler::new(&c);
    let a = DVec3::new(-0.5, 0.3, -0.6).normalize();
    type TestFn = fn(DVec3, DVec3) -> f64;
    let tests: [(&str, TestFn); 5] = [
        ("1", |_, _| 1.0),
        ("(1 + z)²", |w, _| (1.0 + w.z).powi(2)),
        ("(1 + x)²", |w, _| (1.0 + w.x).powi(2)),
        ("(1 + y)³", |w, _| (1.0 + w.y).powi(3)),
        ("exp(4 w·a)", |w, a| (4.0 * w.dot(a)).exp()),
    ];
    for theta_from in [0.0f64, 0.5, -1.1] {
        let from = dir(theta_from, 0.0);
        // Quadrature.
        let (nt, np) = (480, 480);
        let (dt, dp) = (PI / nt as f64, 2.0 * PI / np as f64);
        let nbar: Vec<[[f64; 3]; N_LOBES]> = (0..np)
            .map(|j| {
                let phi = -PI + (j as f64 + 0.5) * dp;
                std::array::from_fn(|p| n_bar_direct(&c, p, theta_from, phi, 400))
            })
            .collect();
        let mut exact = [[0.0f64; 3]; 5];
        for i in 0..nt {
            let th = -PI / 2.0 + (i as f64 + 0.5) * dt;
            let m: [f64; N_LOBES] = std::array::from_fn(|p| c.m(p, th, theta_from));
            for (j, nb) in nbar.iter().enumerate() {
                let phi = -PI + (j as f64 + 0.5) * dp;
                let w = dir(th, phi);
                let area = th.cos() * dt * dp;
                for (t, (_, g)) in tests.iter().enumerate() {
                    let gv = g(w, a) * area;
                    for p in 0..N_LOBES {
                        for ch in 0..3 {
                            exact[t][ch] += m[p] * nb[p][ch] * gv;
                        }
                    }
                }
            }
        }
        // Monte Carlo.
        let n = 400_000;
        let mut rng = SplitMix64::new(11);
        let mut mc = [[0.0f64; 3]; 5];
        let mut sq = [[0.0f64; 3]; 5];
        for _ in 0..n {
            let Some(s) = sampler.sample(DVec3::Z, from, xi(&mut rng)) else {
                continue;
            };
            for (t, (_, g)) in tests.iter().enumerate() {
                let gv = g(s.dir, a);
                for ch in 0..3 {
                    let x = s.weight[ch] * gv;
                    mc[t][ch] += x;
                    sq[t][ch] += x * x;
                }
            }
        }
        for (t, (name, _)) in tests.iter().enumerate() {
            for ch in 0..3 {
                let mean = mc[t][ch] / n as f64;
                let se = ((sq[t][ch] / n as f64 - mean * mean) / n as f64).sqrt();
                let want = exact[t][ch];
                // Five standard errors plus 0.3% for the quadrature (N̄ at 400 offsets, θ and φ
                // at 480 midpoints each).
                assert!(
                    (mean - want).abs() < 5.0 * se + 3e-3 * want.abs(),
                    "θ_from {theta_from}, g = {name}, channel {ch}: sampled {mean:.5} ± {se:.5}, quadrature {want:.5}"
                );
            }
        }
    }
}
