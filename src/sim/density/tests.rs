use super::*;
use glam::Quat;

#[test]
fn b_spline_weights_partition_unity_and_their_derivatives_sum_to_zero() {
    for k in 0..200 {
        let u = -3.0 + k as f32 * 0.0371;
        let (_, w, d) = weights(u);
        assert!((w.iter().sum::<f32>() - 1.0).abs() < 1e-6, "{u}");
        assert!(d.iter().sum::<f32>().abs() < 1e-6, "{u}");
        assert!(w.iter().all(|w| *w >= 0.0));
    }
    // Continuity across a node boundary (u = n + ½): the same weights per node.
    let (b0, w0, d0) = weights(2.5 - 1e-5);
    let (b1, w1, d1) = weights(2.5 + 1e-5);
    assert_eq!(b1, b0 + 1);
    assert!((w0[1] - w1[0]).abs() < 1e-4 && (w0[2] - w1[1]).abs() < 1e-4);
    assert!(w0[0] < 1e-4 && w1[2] < 1e-4);
    assert!((d0[1] - d1[0]).abs() < 1e-3 && (d0[2] - d1[1]).abs() < 1e-3);
}

fn grid_of(points: &[Vec3], head: Affine3A, threshold: f32) -> DensityGrid {
    let mut g = DensityGrid::new(0.02, 0.1);
    let v = vec![Vec3::ZERO; points.len()];
    // One "guide" per point; each stands for 1e-6 m³ (1/8 of a cell).
    let vol = vec![1e-6; points.len()];
    assert!(g.build(head, points, &v, 1, &vol, threshold));
    g
}

#[test]
fn volume_is_conserved_and_the_field_is_continuous() {
    let head =
        Affine3A::from_rotation_translation(Quat::from_rotation_y(0.7), Vec3::new(0.1, 1.6, -0.2));
    let pts: Vec<Vec3> = (0..50)
        .map(|i| head.transform_point3(Vec3::new(0.003 * i as f32, 0.01, -0.004 * i as f32)))
        .collect();
    let g = grid_of(&pts, head, 0.05);
    let total: f32 = g.nodes.iter().map(|n| n.x).sum::<f32>() * 0.02f32.powi(3);
    assert!((total - 50e-6).abs() < 1e-9, "{total}");
    // Along a line through the hair, φ and ∇ẽ change by little between close points: no
    // jump at node boundaries (the map's cell-constant field jumped by its full value).
    let mut prev: Option<HairAround> = None;
    for k in 0..400 {
        let x = head.transform_point3a(Vec3A::new(-0.02 + k as f32 * 0.0005, 0.01, -0.05));
        let h = g.around(x);
        if let Some(p) = prev {
            assert!((h.volume_fraction - p.volume_fraction).abs() < 0.01, "{k}");
            assert!(
                (h.excess_gradient_per_m - p.excess_gradient_per_m).length() < 2.0,
                "{k}: {} vs {}",
                h.excess_gradient_per_m,
                p.excess_gradient_per_m
            );
        }
        prev = Some(h);
    }
}

#[test]
fn the_gradient_matches_finite_differences_and_points_into_the_hair() {
    let head =
        Affine3A::from_rotation_translation(Quat::from_rotation_x(-0.4), Vec3::new(0.0, 1.5, 0.0));
    // A clump of 200 particles around one point: dense in the middle.
    let centre = Vec3::new(0.02, 1.45, 0.03);
    let pts: Vec<Vec3> = (0..200)
        .map(|i| {
            let a = i as f32 * 2.399;
            let r = 0.012 * ((i as f32 + 0.5) / 200.0).sqrt();
            centre + Vec3::new(r * a.cos(), 0.004 * (a * 3.0).sin(), r * a.sin())
        })
        .collect();
    let threshold = 0.0;
    let g = grid_of(&pts, head, threshold);
    let excess = |x: Vec3A| g.around(x).volume_fraction - threshold;
    let x = Vec3A::from(centre) + Vec3A::new(0.011, 0.003, -0.006);
    let h = g.around(x);
    let eps = 1e-4;
    let fd = Vec3A::new(
        excess(x + Vec3A::X * eps) - excess(x - Vec3A::X * eps),
        excess(x + Vec3A::Y * eps) - excess(x - Vec3A::Y * eps),
        excess(x + Vec3A::Z * eps) - excess(x - Vec3A::Z * eps),
    ) / (2.0 * eps);
    assert!(
        (h.excess_gradient_per_m - fd).length() < 0.02 * fd.length(),
        "{} vs {fd}",
        h.excess_gradient_per_m
    );
    // The density rises toward the clump's centre, so the push −∇ẽ points away from it.
    assert!(h.excess_gradient_per_m.dot(Vec3A::from(centre) - x) > 0.0);
}

#[test]
fn mean_velocity_is_the_local_average_and_zero_far_away() {
    let head = Affine3A::IDENTITY;
    let pts = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.004, 0.0, 0.0)];
    let vel = [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
    let mut g = DensityGrid::new(0.02, 0.1);
    assert!(g.build(head, &pts, &vel, 1, &[1e-6, 1e-6], 0.5));
    let h = g.around(Vec3A::new(0.002, 0.0, 0.0));
    assert!((h.mean_velocity_m_s - Vec3A::new(0.5, 0.5, 0.0)).length() < 0.1);
    assert_eq!(h.excess_gradient_per_m, Vec3A::ZERO, "below the threshold");
    let far = g.around(Vec3A::new(5.0, 0.0, 0.0));
    assert_eq!(far, HairAround::default());
}

#[test]
fn degenerate_input_gives_an_inactive_grid() {
    let mut g = DensityGrid::new(0.02, 0.1);
    assert!(!g.build(Affine3A::IDENTITY, &[], &[], 1, &[], 0.1));
    let nan = [Vec3::NAN];
    assert!(!g.build(Affine3A::IDENTITY, &nan, &[Vec3::ZERO], 1, &[1e-6], 0.1));
    // Hair spread over 100 m at 2 cm spacing: far beyond MAX_NODES.
    let spread = [Vec3::ZERO, Vec3::splat(100.0)];
    assert!(!g.build(
        Affine3A::IDENTITY,
        &spread,
        &[Vec3::ZERO; 2],
        1,
        &[1e-6, 1e-6],
        0.1
    ));
    assert_eq!(g.around(Vec3A::ZERO), HairAround::default());
}
