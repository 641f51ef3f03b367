use super::*;

#[test]
fn the_presets_need_no_advice() {
    assert!(Hairstyle::default_smooth().advisories().is_empty());
    assert!(Hairstyle::dense().advisories().is_empty());
    let curly = Hairstyle::default_curly();
    assert!(curly.advisories().is_empty(), "{:?}", curly.advisories());
    // The curly preset is just under the limit: 0.26 m × 1.12 / 120 segments over a
    // 30 mm period is 29.1°.
    let turn = curly.curl_turn_per_segment_deg().unwrap();
    assert!((turn - 29.12).abs() < 0.01, "{turn}");
}

#[test]
fn coarse_curls_are_named_with_the_points_that_fix_them() {
    let mut style = Hairstyle::default_curly();
    style.strands.points = 61; // 58° per segment: curls with too few points
    let advice = style.advisories();
    assert_eq!(advice.len(), 1);
    assert_eq!(advice[0].field, "strands.points");
    // 360° × 0.2912 m / (30° × 0.03 m) = 116.5 → 117 segments, 118 points.
    assert!(
        advice[0].message.contains("118 points"),
        "{}",
        advice[0].message
    );
    assert!(advice[0].message.contains("58°"), "{}", advice[0].message);
    // The number it names is enough, and one fewer is not.
    style.strands.points = 118;
    assert!(style.advisories().is_empty());
    style.strands.points = 117;
    assert_eq!(style.advisories().len(), 1);
}

#[test]
fn straight_hair_and_degenerate_curls_get_none() {
    let mut style = Hairstyle::default_curly();
    style.curl.radius_m = 0.0;
    style.strands.points = 3;
    assert!(style.advisories().is_empty());
    assert_eq!(style.curl_turn_per_segment_deg(), None);
}
