//! Every table against direct numerical integration, at points between grid nodes, to the
//! tolerances documented in `TableResolution::DEFAULT` (about twice the measured errors); and
//! the readings of Eqs. 6 (trap 4) and 25 (trap 5) pinned.

use std::f64::consts::{FRAC_PI_2, PI};
use wisp::fiber::dual::{CosineReading, DualQuantities, n_g_direct, shares_direct, white_albedo};
use wisp::fiber::marschner::n_lobe;
use wisp::fiber::{Fiber, FiberParams, Lobe, LobeConstants};

struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Direct (untabulated) dual quantities at θ (degrees): lobe shares by quadrature over θo of
/// h-space azimuthal integrals recomputed at every node, normalised by the direct white albedo.
fn direct(c: &LobeConstants, deg: f64) -> DualQuantities {
    let t = deg.to_radians();
    DualQuantities::from_shares(
        c,
        &shares_direct(c, t, CosineReading::Outgoing),
        white_albedo(c, t),
    )
}

/// N_p tables against the exact root-solved N_p (random |θd| < 88°, φ, cos 2φh). Tolerances
/// (1/rad, absolute), default fibre: R 5e-4, TT 3e-4, TRT 6e-4 (measured 2.5e-4, 1.1e-4,
/// 2.8e-4); light fibre with eccentricity 0.85 (TRT peak 0.105): TRT 4e-3 (measured 2.1e-3).
#[test]
fn n_tables_match_exact() {
    let cases = [
        (FiberParams::default(), [5e-4, 3e-4, 6e-4]),
        (
            FiberParams {
                sigma_a: [0.1; 3],
                eccentricity: 0.85,
                ..Default::default()
            },
            [5e-3, 5e-3, 4e-3],
        ),
    ];
    for (p, tol) in cases {
        let c = LobeConstants::from_params(&p);
        let fiber = Fiber::new(&p);
        let mut rng = Lcg(11);
        for _ in 0..3000 {
            let td = rng.next() * 88f64.to_radians();
            let phi = rng.next() * PI;
            let c2 = 2.0 * rng.next() - 1.0;
            for lobe in Lobe::ALL {
                let e = n_lobe(&c, lobe, td.sin(), phi, c2);
                let t = fiber
                    .n_table(lobe, td as f32, phi as f32, c2 as f32)
                    .expect("a Marschner fibre has N tables");
                for ch in 0..3 {
                    let err = (e[ch] - t[ch] as f64).abs();
                    assert!(
                        err <= tol[lobe as usize],
                        "{lobe:?} θd={td} φ={phi} c2={c2}: {} vs {}",
                        e[ch],
                        t[ch]
                    );
                }
            }
        }
    }
}

/// Dual tables (interpolated at off-grid θ) against direct integration. Tolerances: ā_f, ā_b
/// 6e-4 absolute (measured 1.9e-4, 3.0e-4); Ā_b 2% relative (measured 0.7%); Δ̄_b 0.1° (0.02°);
/// σ̄_b 0.02° (0.003°); β̄_f, β̄_b 0.05°; also `forward_scatter` (f32 lerp) for ā_f, β̄_f².
#[test]
fn dual_tables_match_direct() {
    for p in [
        FiberParams::default(),
        FiberParams {
            sigma_a: [0.0; 3],
            beta_r_deg: 5.0,
            ..Default::default()
        },
    ] {
        let c = LobeConstants::from_params(&p);
        let fiber = Fiber::new(&p);
        for deg in [-77.3f64, -41.1, -0.7, 12.9, 47.3, 71.6, 83.1] {
            let r = direct(&c, deg);
            let q = fiber.dual_tables().quantities_at(deg.to_radians());
            let fs = fiber.forward_scatter(deg.to_radians().sin() as f32);
            for ch in 0..3 {
                let ctx = format!("{p:?} θ={deg} ch={ch}");
                assert!(
                    (q.a_f[ch] - r.a_f[ch]).abs() <= 6e-4,
                    "{ctx}: a_f {} vs {}",
                    q.a_f[ch],
                    r.a_f[ch]
                );
                assert!(
                    (q.a_b[ch] - r.a_b[ch]).abs() <= 6e-4,
                    "{ctx}: a_b {} vs {}",
                    q.a_b[ch],
                    r.a_b[ch]
                );
                assert!(
                    (fs.a_f[ch] as f64 - r.a_f[ch]).abs() <= 7e-4,
                    "{ctx}: forward_scatter a_f"
                );
                let rel = (q.big_a_b[ch] - r.big_a_b[ch]).abs() / r.big_a_b[ch].max(1e-3);
                assert!(
                    rel <= 0.02,
                    "{ctx}: A_b {} vs {}",
                    q.big_a_b[ch],
                    r.big_a_b[ch]
                );
                let dd = (q.delta_b[ch] - r.delta_b[ch]).abs().to_degrees();
                assert!(dd <= 0.1, "{ctx}: delta_b off by {dd}°");
                let ds = (q.sigma_b2[ch].sqrt() - r.sigma_b2[ch].sqrt())
                    .abs()
                    .to_degrees();
                assert!(ds <= 0.02, "{ctx}: sigma_b off by {ds}°");
                for (a, b) in [
                    (q.beta_f2[ch], r.beta_f2[ch]),
                    (q.beta_b2[ch], r.beta_b2[ch]),
                ] {
                    assert!(
                        (a.sqrt() - b.sqrt()).abs().to_degrees() <= 0.05,
                        "{ctx}: beta"
                    );
                }
                let bf = (fs.beta_f2[ch] as f64).sqrt() - r.beta_f2[ch].sqrt();
                assert!(
                    bf.abs().to_degrees() <= 0.05,
                    "{ctx}: forward_scatter beta_f"
                );
            }
        }
    }
}

/// N^G tables against a direct convolution (midpoint quadrature of the exact N_p over
/// [φ − π/2, φ + π/2], 4000 nodes). Tolerance 3e-4 absolute (measured 1.1e-4 for R).
#[test]
fn n_g_tables_match_direct() {
    let p = FiberParams::default();
    let c = LobeConstants::from_params(&p);
    let fiber = Fiber::new(&p);
    let mut rng = Lcg(5);
    for _ in 0..30 {
        let td = rng.next() * 85f64.to_radians();
        let phi = rng.next() * PI;
        for lobe in Lobe::ALL {
            let e = n_g_direct(&c, lobe, td, phi, FRAC_PI_2, 4000);
            let t = fiber.dual_tables().n_g(lobe, td as f32, phi as f32);
            for ch in 0..3 {
                assert!(
                    (e[ch] - t[ch] as f64).abs() <= 3e-4,
                    "{lobe:?} θd={td} φ={phi}: {} vs {}",
                    e[ch],
                    t[ch]
                );
            }
        }
    }
}

/// Trap 5: Eq. 25 read as a convolution depends on φ (TT's N^G is largest facing away from the
/// light, φ = π, and small at φ = 0), and integrates like N: ∫ N^G dφ = ∫ N dφ (a convolution
/// with a unit-area kernel). The printed, φ-independent reading would be flat.
#[test]
fn trap5_n_g_is_a_convolution() {
    let fiber = Fiber::new(&FiberParams {
        sigma_a: [0.2; 3],
        ..Default::default()
    });
    let d = fiber.dual_tables();
    let tt0 = d.n_g(Lobe::TT, 0.2, 0.0).x;
    let tt_pi = d.n_g(Lobe::TT, 0.2, std::f32::consts::PI).x;
    assert!(tt_pi > 5.0 * tt0, "{tt_pi} vs {tt0}");
    let c = fiber.lobe_constants();
    for lobe in Lobe::ALL {
        let n = 2000;
        let dphi = PI / n as f64;
        let (mut ng, mut nn) = (0.0, 0.0);
        for k in 0..n {
            let phi = (k as f64 + 0.5) * dphi;
            ng += 2.0 * d.n_g(lobe, 0.2, phi as f32).x as f64 * dphi;
            // Circular fibre: cos 2φh irrelevant at eccentricity 1; use the exact lobe at c2 = 1
            // with η (the tables ignore eccentricity), via a circular copy of the constants.
            let circ = LobeConstants {
                eccentricity: 1.0,
                ..*c
            };
            nn += 2.0 * n_lobe(&circ, lobe, 0.2f64.sin(), phi, 1.0)[0] * dphi;
        }
        assert!(
            (ng - nn).abs() <= 2e-3 * nn.max(1e-3),
            "{lobe:?}: {ng} vs {nn}"
        );
    }
}

/// Trap 4: the tables use the outgoing cosine (energy fraction). At θ = 80° with σa = 0 the
/// printed incident-cosine reading gives ā_f ≈ 0.33 against ≈ 0.57, and the two agree within 3%
/// at θ = 0 where the lobes are narrow around θo = −θi.
#[test]
fn trap4_outgoing_cosine() {
    let p = FiberParams {
        sigma_a: [0.0; 3],
        eccentricity: 1.0,
        ..Default::default()
    };
    let c = LobeConstants::from_params(&p);
    let fiber = Fiber::new(&p);
    let sum_f = |s: &wisp::fiber::dual::LobeShares| (0..3).map(|l| s.forward[l][0]).sum::<f64>();
    let t = 80f64.to_radians();
    let out = sum_f(&shares_direct(&c, t, CosineReading::Outgoing));
    let inc = sum_f(&shares_direct(&c, t, CosineReading::Incident));
    let table = fiber.dual_tables().quantities_at(t).a_f[0] * white_albedo(&c, t).max(1.0);
    assert!((table - out).abs() < 1e-3, "{table} vs {out}");
    assert!(out > 1.5 * inc, "{out} vs {inc}");
    let out0 = sum_f(&shares_direct(&c, 0.0, CosineReading::Outgoing));
    let inc0 = sum_f(&shares_direct(&c, 0.0, CosineReading::Incident));
    assert!((out0 - inc0).abs() < 0.03 * out0);
}
