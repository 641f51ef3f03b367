use super::*;
use glam::Quat;

#[test]
fn offsets_round_trip_and_turn_with_the_centre_line() {
    let centre: Vec<Vec3> = (0..12)
        .map(|i| Vec3::new(0.01 * (i as f32).sin(), -0.02 * i as f32, 0.003 * i as f32))
        .collect();
    let target: Vec<Vec3> = centre
        .iter()
        .enumerate()
        .map(|(i, p)| *p + Vec3::new(0.004, 0.001 * i as f32, -0.002))
        .collect();
    let reference = Vec3::new(1.0, 0.2, 0.0);
    let mut off = vec![Vec3::ZERO; centre.len()];
    rest_offsets_of(&centre, reference, &target, &mut off);
    let mut back = centre.clone();
    apply_rest_offsets(&mut back, reference, &off);
    for (a, b) in back.iter().zip(&target) {
        assert!((*a - *b).length() < 1e-6, "{a} vs {b}");
    }
    // Rotating the centre line and the reference rotates the result (a rigid motion of
    // the guides carries the strand with them).
    let q = Quat::from_rotation_z(0.7) * Quat::from_rotation_x(-0.4);
    let mut moved: Vec<Vec3> = centre.iter().map(|p| q * *p).collect();
    apply_rest_offsets(&mut moved, q * reference, &off);
    for (a, b) in moved.iter().zip(&target) {
        assert!((*a - q * *b).length() < 1e-5, "{a} vs {}", q * *b);
    }
}
