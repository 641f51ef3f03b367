use super::*;

fn light(t: f32) -> LightAtPoint {
    LightAtPoint {
        direct_fraction: t,
        tf: Vec3::splat(t),
        sigma_f2: Vec3::ZERO,
        crossings_behind: LightAtPoint::DENSE,
    }
}

#[test]
fn bins_and_biases_are_signed_means() {
    let truth = [light(0.1), light(0.9), light(0.6)];
    let est = [light(0.2), light(0.7), light(0.6)];
    let c = Comparison::new(&truth, &est);
    assert!((c.mae - (0.1 + 0.2 + 0.0) / 3.0).abs() < 1e-6);
    assert!((c.overall_bias - (0.1 - 0.2) / 3.0).abs() < 1e-6);
    assert_eq!(c.by_truth.map(|b| b.count), [1, 0, 1, 1]);
    assert!((c.by_truth[3].bias + 0.2).abs() < 1e-6);
    // By estimate, 0.7 falls in the 0.5–0.8 bin with 0.6.
    assert_eq!(c.by_estimate.map(|b| b.count), [0, 1, 2, 0]);
    assert!((c.worst_bin_bias(true, 1) - 0.2).abs() < 1e-6);
}

#[test]
fn sampled_vertices_are_distinct_and_in_range() {
    let v = sample_vertices(10_000, 3_000);
    assert_eq!(v.len(), 3_000);
    assert!(v.windows(2).all(|w| w[0] < w[1]));
    assert!(*v.last().unwrap() < 10_000);
    assert_eq!(sample_vertices(5, 10).len(), 5);
}
