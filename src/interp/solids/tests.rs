use super::*;
use crate::sim::{CapsuleCollider, SphereCollider};

#[test]
fn points_inside_end_on_the_surfaces_and_points_outside_do_not_move() {
    let c = Colliders {
        head: Affine3A::from_translation(Vec3::new(0.0, 1.6, 0.0)),
        head_radii_m: Vec3::new(0.08, 0.1, 0.09),
        spheres: vec![SphereCollider {
            center: Vec3::new(0.3, 1.0, 0.0),
            radius_m: 0.05,
        }],
        capsules: vec![CapsuleCollider {
            a: Vec3::new(0.0, 1.2, 0.0),
            b: Vec3::new(0.0, 1.45, 0.0),
            radius_m: 0.05,
        }],
        carriers: Vec::new(),
    };
    let view = SolidsView::new(&c);
    let mut strand = vec![
        Vec3::new(0.0, 1.7, 0.0),   // root, inside the head: kept
        Vec3::new(0.0, 1.62, 0.02), // inside the head
        Vec3::new(0.01, 1.3, 0.0),  // inside the capsule
        Vec3::new(0.31, 1.0, 0.0),  // inside the sphere
        Vec3::new(0.5, 1.0, 0.0),   // outside everything
    ];
    let before = strand.clone();
    assert!(view.push_radially(&mut strand));
    assert_eq!(strand[0], before[0]);
    let q = (strand[1] - Vec3::new(0.0, 1.6, 0.0)) / c.head_radii_m;
    assert!((q.length() - 1.0).abs() < 1e-5);
    assert!((strand[2] - Vec3::new(0.05, 1.3, 0.0)).length() < 1e-5);
    assert!((strand[3] - Vec3::new(0.35, 1.0, 0.0)).length() < 1e-5);
    assert_eq!(strand[4], before[4]);
}

/// A straight strand through a sphere (2 cm segments, radius 5 cm): after the push and
/// the length pass no segment is longer than before, the strand is no longer than before,
/// and its deepest point is far shallower than the 5 cm it reached.
#[test]
fn pushed_strands_keep_their_segment_lengths() {
    let c = Colliders {
        head: Affine3A::from_translation(Vec3::new(0.0, 10.0, 0.0)),
        head_radii_m: Vec3::splat(0.05),
        spheres: vec![SphereCollider {
            center: Vec3::ZERO,
            radius_m: 0.05,
        }],
        capsules: Vec::new(),
        carriers: Vec::new(),
    };
    let view = SolidsView::new(&c);
    let mut strand: Vec<Vec3> = (0..21)
        .map(|i| Vec3::new(-0.2 + 0.02 * i as f32, 0.001, 0.0))
        .collect();
    let mut scratch = vec![0.0; strand.len()];
    view.push_out(&mut strand, &mut scratch);
    let depth = strand
        .iter()
        .map(|p| (0.05 - p.length()).max(0.0))
        .fold(0.0f32, f32::max);
    for w in strand.windows(2) {
        assert!(w[0].distance(w[1]) <= 0.02 + 1e-6, "{w:?}");
    }
    assert!(depth < 0.01, "deepest {depth} m");
    assert!(strand.iter().all(|p| p.is_finite()));
}
