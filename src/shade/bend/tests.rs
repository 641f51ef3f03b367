use super::*;

/// Three points turning by `deg` degrees at the middle one.
fn corner(deg: f32) -> Vec<Vec3> {
    let t = deg.to_radians();
    vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, -0.01, 0.0),
        Vec3::new(0.01 * t.sin(), -0.01 - 0.01 * t.cos(), 0.0),
    ]
}

#[test]
fn a_vertex_is_bent_beyond_beta_r() {
    let test = BendTest::for_beta_r_deg(7.5);
    let t = Vec3::NEG_Y;
    assert_eq!(
        test.directions(&corner(7.3), t, 3, 1, 1),
        Directions::One(t)
    );
    let Directions::Two(a, b) = test.directions(&corner(7.7), t, 3, 1, 1) else {
        panic!("a 7.7° bend is two directions at β_R = 7.5°");
    };
    assert!((a - Vec3::NEG_Y).length() < 1e-6);
    assert!((a.dot(b) - 7.7f32.to_radians().cos()).abs() < 1e-6);
    // A wider lobe tolerates the same bend.
    assert_eq!(
        BendTest::for_beta_r_deg(10.0).directions(&corner(7.7), t, 3, 1, 1),
        Directions::One(t)
    );
    // A reversal is bent whatever the lobe.
    assert!(matches!(
        BendTest::for_beta_r_deg(45.0).directions(&corner(170.0), t, 3, 1, 1),
        Directions::Two(..)
    ));
}

/// Points turning by `turns[k]` degrees at inner vertex k + 1, in one plane.
fn curve(turns: &[f32]) -> Vec<Vec3> {
    let mut p = vec![Vec3::ZERO, Vec3::new(0.0, -0.01, 0.0)];
    let mut a = 0.0f32;
    for t in turns {
        a += t.to_radians();
        let last = p[p.len() - 1];
        p.push(last + 0.01 * Vec3::new(a.sin(), -a.cos(), 0.0));
    }
    p
}

#[test]
fn an_even_curve_is_shaded_once_and_its_corners_twice() {
    let test = BendTest::for_beta_r_deg(7.5);
    let t = Vec3::NEG_Y;
    // An even curl of 20° a segment: one direction inside; the vertices next to the
    // ends turn more than twice an end's (straight) and are corners.
    let curl = curve(&[20.0; 8]);
    let n = curl.len();
    for i in 2..n - 2 {
        assert_eq!(
            test.directions(&curl, t, n, 1, i),
            Directions::One(t),
            "vertex {i}"
        );
    }
    assert!(matches!(
        test.directions(&curl, t, n, 1, 1),
        Directions::Two(..)
    ));
    assert!(matches!(
        test.directions(&curl, t, n, 1, n - 2),
        Directions::Two(..)
    ));
    // A 70° turn between gentle ones (the dense scene's roots), and the 30° after it.
    let root = curve(&[5.0, 70.0, 30.0, 6.0, 6.0, 6.0]);
    let n = root.len();
    let two = |i| matches!(test.directions(&root, t, n, 1, i), Directions::Two(..));
    assert_eq!(
        (1..n - 1).map(two).collect::<Vec<_>>(),
        [false, true, true, false, false, false]
    );
}

/// A strand whose segments are cut into pieces (`interp::subdivide`) bends where the
/// groom's polyline bends, and nowhere else: its added points are straight, and a groom
/// point's neighbours are read a whole groom segment away, so an even curve stays one
/// direction per point as it is uncut (read one point away, a cut curve's neighbours
/// would look straight and every point turning by more than β_R would be a corner).
#[test]
fn cut_segments_bend_where_the_groom_bends() {
    let test = BendTest::for_beta_r_deg(7.5);
    let t = Vec3::NEG_Y;
    for turns in [&[20.0f32; 8][..], &[5.0, 70.0, 30.0, 6.0, 6.0, 6.0][..]] {
        let coarse = curve(turns);
        let n = coarse.len();
        for pieces in [2usize, 3] {
            let m = crate::interp::subdivided_points(n, pieces);
            let mut fine = vec![Vec3::ZERO; m];
            fine[..n].copy_from_slice(&coarse);
            crate::interp::subdivide_in_place(&mut fine, n, pieces);
            for i in 0..m {
                let got = test.directions(&fine, t, m, pieces, i);
                let want = if i % pieces == 0 {
                    test.directions(&coarse, t, n, 1, i / pieces)
                } else {
                    Directions::One(t)
                };
                match (got, want) {
                    (Directions::One(_), Directions::One(_)) => {}
                    (Directions::Two(a, b), Directions::Two(c, d)) => {
                        assert!(a.dot(c) > 1.0 - 1e-5 && b.dot(d) > 1.0 - 1e-5, "{i}");
                    }
                    _ => panic!("pieces {pieces}, point {i}: {got:?}, uncut {want:?}"),
                }
            }
        }
    }
}

#[test]
fn ends_degenerate_and_non_finite_points_keep_the_tangent() {
    let test = BendTest::for_beta_r_deg(7.5);
    let t = Vec3::NEG_Y;
    let p = corner(30.0);
    assert_eq!(test.directions(&p, t, 3, 1, 0), Directions::One(t));
    assert_eq!(test.directions(&p, t, 3, 1, 2), Directions::One(t));
    // Two strands of 3: vertex 3 starts the second strand.
    let two: Vec<Vec3> = p.iter().chain(p.iter()).copied().collect();
    assert_eq!(test.directions(&two, t, 3, 1, 3), Directions::One(t));
    assert!(matches!(
        test.directions(&two, t, 3, 1, 4),
        Directions::Two(..)
    ));
    let mut same = p.clone();
    same[1] = same[0];
    assert_eq!(test.directions(&same, t, 3, 1, 1), Directions::One(t));
    let mut nan = p.clone();
    nan[2] = Vec3::new(f32::NAN, 0.0, 0.0);
    assert_eq!(test.directions(&nan, t, 3, 1, 1), Directions::One(t));
    assert_eq!(test.directions(&p, t, 2, 1, 1), Directions::One(t));
    assert_eq!(test.directions(&p[..2], t, 3, 1, 1), Directions::One(t));
}
