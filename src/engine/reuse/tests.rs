use super::*;
use glam::Vec3;

#[test]
fn equal_inputs_are_reused_and_any_change_rebuilds() {
    let mut positions = vec![Vec3::ONE; 4];
    let others = vec![Vec3::ZERO; 2];
    let mut kept = Kept::default();
    assert!(
        !kept.unchanged_or_record(&[&positions, &others]),
        "first build"
    );
    assert!(kept.unchanged_or_record(&[&positions, &others]));
    positions[2].x = f32::from_bits(positions[2].x.to_bits() + 1);
    assert!(
        !kept.unchanged_or_record(&[&positions, &others]),
        "one ulp moved"
    );
    assert!(kept.unchanged_or_record(&[&positions, &others]));
    positions[0] = Vec3::NAN;
    assert!(!kept.unchanged_or_record(&[&positions, &others]));
    assert!(
        !kept.unchanged_or_record(&[&positions, &others]),
        "NaN never reuses"
    );
    positions[0] = Vec3::ZERO;
    assert!(!kept.unchanged_or_record(&[&positions, &others]));
    assert!(kept.unchanged_or_record(&[&positions, &others]));
    assert!(!kept.unchanged_or_record(&[&positions]), "a slice fewer");
    assert!(
        !kept.unchanged_or_record(&[&positions, &positions]),
        "swapped contents"
    );
    kept.forget();
    assert!(
        !kept.unchanged_or_record(&[&positions, &positions]),
        "forgotten"
    );
}
