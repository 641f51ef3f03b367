use super::*;

/// MAPPING.md's table: β_R = 2.5/5/7.5/10° gives b = 0.107/0.197/0.276/0.347 (3 digits).
#[test]
fn roughness_matches_the_mapping_table() {
    for (beta_deg, b) in [(2.5, 0.107), (5.0, 0.197), (7.5, 0.276), (10.0, 0.347)] {
        let got = longitudinal_roughness_for_std(2.0 * f64::to_radians(beta_deg));
        assert!((got - b).abs() < 6e-4, "beta {beta_deg}: {got} vs {b}");
    }
    assert_eq!(longitudinal_roughness_for_std(f64::NAN), 0.0);
    assert_eq!(longitudinal_roughness_for_std(-1.0), 0.0);
}

#[test]
fn maps_fields_and_model() {
    let f = serde_json::json!({"eta": 1.6, "sigma_a": [0.1, 0.2, 0.3], "beta_r_deg": 5.0,
        "alpha_r_deg": -3.0, "azimuthal_roughness": 0.3});
    let m = mitsuba_hair(&f);
    assert_eq!((m.int_ior, m.ext_ior, m.scale_tilt), (1.6, 1.0, -3.0));
    assert_eq!(m.sigma_a, [0.1, 0.2, 0.3]);
    assert_eq!(m.azimuthal_roughness, MARSCHNER_AZIMUTHAL_ROUGHNESS);
    let mut c = f.clone();
    c["model"] = "chiang".into();
    assert_eq!(fiber_model(&c), "chiang");
    assert_eq!(mitsuba_hair(&c).azimuthal_roughness, 0.3);
}
