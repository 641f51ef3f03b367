use super::*;

#[test]
fn catmull_rom_passes_through_ends_and_reproduces_a_line() {
    // On collinear, evenly spaced points, uniform Catmull-Rom with reflected phantoms is the
    // line itself (the Hermite tangents equal the chord), so samples are exact.
    let ctrl: Vec<Vec3> = (0..5)
        .map(|i| Vec3::new(i as f32, 2.0 * i as f32, 0.0))
        .collect();
    let mut out = vec![Vec3::ZERO; 17];
    catmull_rom_resample(&ctrl, &mut out);
    for (k, p) in out.iter().enumerate() {
        let u = k as f32 * 4.0 / 16.0;
        assert!(
            (*p - Vec3::new(u, 2.0 * u, 0.0)).length() < 1e-5,
            "{k}: {p}"
        );
    }
}
