use super::*;
use crate::hairstyle::{Hairstyle, generate};

#[test]
fn strands_of_a_wisp_lie_between_its_guides_and_roots_stay_on_guides_plane() {
    let style = Hairstyle::default_smooth();
    let (g, mut layout) = generate(&style);
    // Full-length strands without the generator's tip fan: their tips are the blend of the
    // guides' tips.
    layout.strand_length.fill(1.0);
    layout.rest_offset.clear();
    let mut geo = StrandGeometry::default();
    interpolate(&g, &layout, &style.curl, &g.rest, &mut geo);
    assert_eq!(
        geo.positions.len(),
        layout.count() * layout.points_per_strand
    );
    for s in 0..layout.count() {
        let wisp = layout.wisp_guides[layout.strand_wisp[s] as usize];
        let w = layout.strand_weights[s];
        let root: Vec3 = (0..3).map(|k| g.guide(wisp[k] as usize)[0] * w[k]).sum();
        assert!((geo.positions[s * layout.points_per_strand] - root).length() < 1e-6);
        let tip: Vec3 = (0..3)
            .map(|k| *g.guide(wisp[k] as usize).last().unwrap() * w[k])
            .sum();
        assert!((geo.positions[(s + 1) * layout.points_per_strand - 1] - tip).length() < 1e-6);
    }
    assert!(geo.tangents.iter().all(|t| (t.length() - 1.0).abs() < 1e-4));
    assert!(geo.lengths_m.iter().all(|l| l.is_finite() && *l >= 0.0));
}

#[test]
fn strands_end_short_of_their_guides_and_thin_toward_the_tips() {
    let style = Hairstyle::default_smooth();
    let (g, layout) = generate(&style);
    let mut full_layout = layout.clone();
    full_layout.strand_length.fill(1.0);
    full_layout.tip_taper = 0.0;
    let (mut geo, mut full) = (StrandGeometry::default(), StrandGeometry::default());
    interpolate(&g, &layout, &style.curl, &g.rest, &mut geo);
    interpolate(&g, &full_layout, &style.curl, &g.rest, &mut full);
    let n = layout.points_per_strand;
    let arc = |p: &[Vec3]| p.windows(2).map(|w| (w[1] - w[0]).length()).sum::<f32>();
    let v = style.strands.length_variation;
    assert!(
        v > 0.0 && layout.tip_taper > 0.0,
        "the preset varies its strands"
    );
    for s in 0..layout.count() {
        let f = layout.strand_length[s];
        assert!((1.0 - v..=1.0).contains(&f), "{f}");
        // Arc length follows the length fraction (within the spline's bending).
        let (a, b) = (
            arc(&geo.positions[s * n..(s + 1) * n]),
            arc(&full.positions[s * n..(s + 1) * n]),
        );
        assert!((a / b - f).abs() < 0.05, "strand {s}: {a} / {b} vs {f}");
        let share = &geo.fiber_share[s * n..(s + 1) * n];
        assert_eq!(share[0], 1.0);
        assert_eq!(share[n - 1], 0.0, "no fibre reaches past the tip");
        assert!(
            share.windows(2).all(|w| w[1] <= w[0]),
            "fibres only end: {share:?}"
        );
        // The fibre length filled into the map: a linear taper over the last fraction t of
        // the strand removes t/2 of its length.
        let filled: f32 = geo.lengths_m[s * n..(s + 1) * n].iter().sum();
        let expect = a * (1.0 - 0.5 * layout.tip_taper);
        assert!(
            (filled / expect - 1.0).abs() < 0.06,
            "strand {s}: {filled} vs {expect}"
        );
    }
    assert!(full.fiber_share.iter().all(|s| *s == 1.0));
}

#[test]
fn curls_keep_their_radius_around_the_centre_line() {
    let style = Hairstyle::default_curly();
    let (g, layout) = generate(&style);
    let mut straight = StrandGeometry::default();
    let mut curly = StrandGeometry::default();
    interpolate(&g, &layout, &CurlSpec::default(), &g.rest, &mut straight);
    interpolate(&g, &layout, &style.curl, &g.rest, &mut curly);
    let n = layout.points_per_strand;
    // Past the 2 cm ramp, every point sits at the helix radius from the centre line
    // (the offset is perpendicular to the local tangent by construction).
    let mut checked = 0;
    for s in 0..layout.count() {
        for i in n / 2..n {
            let d = (curly.positions[s * n + i] - straight.positions[s * n + i]).length();
            assert!((d - style.curl.radius_m).abs() < 1e-5, "offset {d}");
            checked += 1;
        }
    }
    assert!(checked > 0);
}

#[test]
fn degenerate_guides_give_finite_output() {
    let style = Hairstyle::default_curly();
    let (g, layout) = generate(&style);
    // All particles collapsed on one point: zero-length links everywhere.
    let collapsed = vec![Vec3::new(0.1, 0.2, 0.3); g.rest.len()];
    let mut geo = StrandGeometry::default();
    interpolate(&g, &layout, &style.curl, &collapsed, &mut geo);
    assert!(
        geo.positions
            .iter()
            .chain(&geo.tangents)
            .all(|v| v.is_finite())
    );
}
