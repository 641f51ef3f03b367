use super::*;
use proptest::prelude::*;

proptest! {
    /// Every point of the triangle whose .x is in the band has its .y in the range
    /// (points drawn by barycentric weights; a hair of rounding allowed).
    #[test]
    fn the_extent_holds_every_point_of_the_band(
        p in prop::array::uniform3((-50.0f32..50.0, -50.0f32..50.0)),
        w in (0.0f32..1.0, 0.0f32..1.0),
        band in (0.0f32..3.0, 0.0f32..3.0),
    ) {
        let p = p.map(|(x, y)| Vec2::new(x, y));
        let (u, v) = if w.0 + w.1 > 1.0 { (1.0 - w.0, 1.0 - w.1) } else { w };
        let q = p[0] + (p[1] - p[0]) * u + (p[2] - p[0]) * v;
        let (from, to) = (q.x - band.0, q.x + band.1);
        let (lo, hi) = extent_across(p, (from, to)).expect("a point lies in the band");
        prop_assert!(q.y >= lo - 1e-3 && q.y <= hi + 1e-3, "{} not in {}..{}", q.y, lo, hi);
    }
}

/// Hand cases: a band missing the triangle, a level edge, a corner alone in the band.
#[test]
fn hand_cases() {
    let t = [
        Vec2::new(0.0, 0.0),
        Vec2::new(10.0, 0.0),
        Vec2::new(0.0, 10.0),
    ];
    assert_eq!(extent_across(t, (11.0, 12.0)), None);
    assert_eq!(extent_across(t, (0.0, 0.0)), Some((0.0, 10.0)));
    assert_eq!(extent_across(t, (5.0, 5.0)), Some((0.0, 5.0)));
    assert_eq!(extent_across(t, (9.0, 20.0)), Some((0.0, 1.0)));
    assert_eq!(span(t, (5.0, 6.0)), Some((-2.0, 9.0)));
    assert!(narrowable(t));
    assert!(!narrowable([t[0], t[0] + Vec2::new(0.01, 0.0), t[2]]));
    assert!(!narrowable([t[0], t[1], Vec2::new(0.0, 1e6)]));
}
