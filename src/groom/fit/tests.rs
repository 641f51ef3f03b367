use super::*;

#[test]
fn recovers_a_known_scale_and_offset() {
    // Roots on a cap of the ellipsoid, expressed in centimetres around another centre:
    // the fit must find scale 0.01 and the centre back.
    let r = Vec3::new(0.076, 0.098, 0.094);
    let (scale, offset) = (0.01f32, Vec3::new(0.5, -170.0, 3.0));
    let mut roots = Vec::new();
    for i in 0..400 {
        let polar = 1.3 * (i as f32 / 400.0).sqrt();
        let az = i as f32 * 2.399;
        let d = Vec3::new(polar.sin() * az.sin(), polar.cos(), polar.sin() * az.cos());
        let on = d / (d / r).length(); // exactly on the surface
        roots.push((on - offset * scale) / scale);
    }
    let p = fit_to_head(&roots, &[], 0.0, r).unwrap();
    assert!((p.scale / scale - 1.0).abs() < 1e-3, "{p:?}");
    for q in &roots {
        assert!(surface_distance_m(p.apply(*q), r) < 1e-4);
    }
}
