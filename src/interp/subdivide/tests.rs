use super::*;
use crate::hairstyle::{Hairstyle, generate};
use crate::interp::{StrandGeometry, interpolate_among};
use proptest::prelude::*;

fn arc_m(p: &[Vec3]) -> f32 {
    p.windows(2).map(|w| (w[1] - w[0]).length()).sum()
}

proptest! {
    /// Invariants of cutting a polyline: the groom's points are kept exactly (at every
    /// `pieces`-th place), each added point lies on its segment at k / pieces of the way,
    /// so the arc length (the fibre the map fills) is unchanged.
    #[test]
    fn cutting_keeps_the_polyline(
        pts in proptest::collection::vec((-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0), 2..12),
        pieces in 1usize..6,
    ) {
        let coarse: Vec<Vec3> = pts.iter().map(|&(x, y, z)| Vec3::new(x, y, z)).collect();
        let n = subdivided_points(coarse.len(), pieces);
        prop_assert_eq!(n, (coarse.len() - 1) * pieces + 1);
        let mut fine = vec![Vec3::splat(f32::NAN); n];
        fine[..coarse.len()].copy_from_slice(&coarse);
        subdivide_in_place(&mut fine, coarse.len(), pieces);
        for (i, c) in coarse.iter().enumerate() {
            prop_assert_eq!(fine[i * pieces], *c);
        }
        for (s, w) in coarse.windows(2).enumerate() {
            for k in 1..pieces {
                let want = w[0] + (w[1] - w[0]) * (k as f32 / pieces as f32);
                prop_assert!((fine[s * pieces + k] - want).length() < 1e-5);
            }
        }
        prop_assert!((arc_m(&fine) - arc_m(&coarse)).abs() < 1e-4 * (1.0 + arc_m(&coarse)));
    }
}

#[test]
fn short_strands_are_left_alone() {
    assert_eq!(subdivided_points(0, 3), 0);
    assert_eq!(subdivided_points(1, 3), 1);
    assert_eq!(subdivided_points(5, 0), 5);
    let mut one = [Vec3::X];
    subdivide_in_place(&mut one, 1, 4);
    assert_eq!(one, [Vec3::X]);
}

/// Render strands interpolated with their segments cut in two are the groom's strands with
/// midpoints: the groom's points unchanged, its tangents there parallel, each point's
/// fibre length (and so what the map is filled with) summing to the same total, and the
/// tip taper's fibre share the same at the groom's points (it is linear in arc length, so
/// it is exact at the midpoints too).
#[test]
fn interpolated_strands_cut_in_two_are_the_same_hair() {
    let style = Hairstyle::default_smooth();
    let (g, layout) = generate(&style);
    let (mut one, mut two) = (StrandGeometry::default(), StrandGeometry::default());
    interpolate_among(&g, &layout, &style.curl, &g.rest, None, 1, &mut one);
    interpolate_among(&g, &layout, &style.curl, &g.rest, None, 2, &mut two);
    let n = one.points_per_strand;
    assert_eq!(two.points_per_strand, 2 * n - 1);
    assert_eq!(two.strand_count(), one.strand_count());
    for s in 0..one.strand_count() {
        for i in 0..n {
            let (a, b) = (s * n + i, s * (2 * n - 1) + 2 * i);
            assert_eq!(one.positions[a], two.positions[b]);
            assert!(one.tangents[a].dot(two.tangents[b]) > 1.0 - 1e-5, "{s} {i}");
            assert!((one.fiber_share[a] - two.fiber_share[b]).abs() < 1e-5);
        }
    }
    let total = |g: &StrandGeometry| g.lengths_m.iter().map(|&l| l as f64).sum::<f64>();
    let (t1, t2) = (total(&one), total(&two));
    // The taper's fibre length is the integral of a share linear along each piece: the
    // point rule is exact for it on the straight part and off by at most the tip's last
    // segment, so the totals agree to a fraction of one segment per strand.
    assert!((t1 - t2).abs() < 0.01 * t1, "{t1} {t2}");
}
