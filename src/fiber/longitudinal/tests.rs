use super::*;
use crate::fiber::chiang::deon_m;

/// The f32 lobe against the f64 reference, over variances from (2·0.5°)²/4 to 4·(2·45°)² and
/// inclinations up to ±90°: relative error < 2e-4 where M > 1e-3 of its peak.
#[test]
fn deon_f32_matches_f64() {
    for v in [1.9e-5f64, 3e-4, 0.0171, 0.0685, 0.274, 2.0, 9.9] {
        let inv = (1.0 / v) as f32;
        let norm = (1.0 / (v * -(-2.0 / v).exp_m1())) as f32;
        let peak = deon_m(v, 0.0, 0.0);
        for i in 0..=60 {
            let ti = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * i as f64 / 60.0;
            for j in 0..=240 {
                let to = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * j as f64 / 240.0;
                let r = deon_m(v, ti, to);
                let (si, ci) = (ti.sin() as f32, ti.cos().max(0.0) as f32);
                let (so, co) = (to.sin() as f32, to.cos().max(0.0) as f32);
                let got = deon_m_f32(inv, norm, si, ci, so, co) as f64;
                assert!(got.is_finite() && got >= 0.0);
                if r > 1e-3 * peak {
                    assert!(
                        (got - r).abs() <= 2e-4 * r,
                        "v={v} θi={ti} θo={to}: {got} vs {r}"
                    );
                } else {
                    assert!(got <= 1.1e-3 * peak + 1e-30, "v={v}: tail {got} vs {r}");
                }
            }
        }
    }
}
