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

/// A directional light keeps scene.json's `{"direction", "irradiance"}` exactly (the tables'
/// scenes read unchanged); a point light is written as `{"position_m", "intensity"}` with
/// wisp's numbers unchanged, and both read back as they were written.
#[test]
fn writes_one_directional_or_point_light() {
    let d = Light::directional(glam::Vec3::new(0.0, 0.0, -2.0), glam::Vec3::splat(1.0)).unwrap();
    let dj = reference_light(&[d]).unwrap();
    let text = serde_json::to_string(&dj).unwrap();
    assert_eq!(
        text,
        r#"{"direction":[0.0,0.0,-1.0],"irradiance":[1.0,1.0,1.0]}"#
    );
    assert_eq!(serde_json::from_str::<LightJson>(&text).unwrap(), dj);

    let pos = glam::Vec3::new(0.25, 1.8, 0.3);
    let intensity = glam::Vec3::new(0.2, 0.1, 0.05);
    let p = Light::point(pos, intensity).unwrap();
    let pj = reference_light(&[p]).unwrap();
    assert_eq!(
        pj,
        LightJson::Point {
            position_m: pos.to_array(),
            intensity: intensity.to_array(),
        }
    );
    let text = serde_json::to_string(&pj).unwrap();
    assert!(text.contains(r#""position_m":[0.25,1.8,0.3]"#), "{text}");
    assert_eq!(serde_json::from_str::<LightJson>(&text).unwrap(), pj);
}

/// The point light's `intensity` means what Mitsuba's `point` emitter's does: irradiance
/// I / d² on a surface facing it at distance d (Mitsuba 3.9.1 `point.cpp`, sample_direction:
/// intensity x inv_dist²). wisp's light gives that at 0.5 m: 4 I.
#[test]
fn point_intensity_is_irradiance_times_distance_squared() {
    let pos = glam::Vec3::new(0.0, 1.7, 0.5);
    let intensity = glam::Vec3::new(0.2, 0.1, 0.05);
    let p = Light::point(pos, intensity).unwrap();
    let (toward, e) = p.toward_and_irradiance(glam::Vec3::new(0.0, 1.7, 0.0));
    assert!((toward - glam::Vec3::Z).length() < 1e-6);
    assert!((e - intensity * 4.0).abs().max_element() < 1e-6, "{e}");
}

/// No light, or two, is no reference scene: the error says how many there are.
#[test]
fn refuses_anything_but_one_light() {
    assert!(reference_light(&[]).unwrap_err().contains("has 0"));
    let d = Light::directional(glam::Vec3::NEG_Y, glam::Vec3::ONE).unwrap();
    let p = Light::point(glam::Vec3::new(2.0, 0.0, 0.0), glam::Vec3::ONE).unwrap();
    let e = reference_light(&[d, p]).unwrap_err();
    assert!(
        e.contains("exactly one light") && e.contains("has 2"),
        "{e}"
    );
}
