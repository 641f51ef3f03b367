use super::*;

fn disc(n: u32) -> Vec<Vec2> {
    (0..n)
        .map(|i| {
            let rho = ((i as f32 + 0.5) / n as f32).sqrt();
            Vec2::from_angle(i as f32 * 2.399_963) * rho
        })
        .collect()
}

#[test]
fn the_cumulative_width_rises_from_zero_to_the_fibers_summed_width() {
    let pts = disc(30);
    let mut p = Profiles::default();
    assert!(p.prepare(&Bundle {
        radius_m: 2e-3,
        fiber_radius_m: 4e-5,
        points: &pts,
    }));
    assert!((p.total - 30.0 * 2.0 * 0.02).abs() < 1e-5);
    for pat in 0..PATTERNS {
        let base = (pat * SAMPLES) as u32;
        let mut last = -1.0;
        for i in 0..=400 {
            let u = -1.1 + 2.2 * i as f32 / 400.0;
            let a = p.cumulative(base, u);
            assert!(a >= last - 1e-6, "monotone");
            last = a;
        }
        assert_eq!(p.cumulative(base, -1.03), 0.0);
        assert!((p.cumulative(base, 1.03) - p.total).abs() < 1e-4);
    }
}

#[test]
fn one_fiber_or_fibers_as_wide_as_the_bundle_are_not_a_bundle() {
    let mut p = Profiles::default();
    let one = [Vec2::ZERO];
    let pts = disc(8);
    let b = |radius_m, points| Bundle {
        radius_m,
        fiber_radius_m: 1e-3,
        points,
    };
    assert!(!p.prepare(&b(2e-3, &one)));
    assert!(!p.prepare(&b(1e-3, &pts)));
    assert!(!p.prepare(&b(f32::NAN, &pts)));
    assert!(p.prepare(&b(3e-3, &pts)));
}
