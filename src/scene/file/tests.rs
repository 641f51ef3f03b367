use super::*;

fn refused(text: &str) -> (String, String) {
    match SceneFile::from_json(text, "s.json") {
        Err(SceneError::Invalid { field, rule, .. }) => (field, rule),
        Err(SceneError::Parse { field, message, .. }) => (field, message),
        Err(e @ SceneError::Io { .. }) => panic!("{e}"),
        Ok(s) => panic!("accepted {text}: {s:?}"),
    }
}

#[test]
fn an_empty_object_is_the_default_scene_and_printing_round_trips() {
    let (file, scene) = SceneFile::from_json("{}", "s.json").unwrap();
    assert_eq!(file, SceneFile::default());
    assert_eq!(scene.lights.len(), 1);
    let (again, scene2) = SceneFile::from_json(&file.to_json(), "s.json").unwrap();
    assert_eq!(again, file);
    assert_eq!(scene2, scene);
}

#[test]
fn two_lights_and_a_fixed_camera_parse() {
    let text = r#"{"camera": {"type": "fixed", "position_m": [0, 1.6, 1], "target_m": [0, 1.6, 0]},
        "lights": [{"type": "directional", "direction": [0, -1, 0], "irradiance": [1, 1, 1]},
                   {"type": "point", "position_m": [1, 2, 1], "intensity": [4, 4, 4]}],
        "exposure_stops": 1}"#;
    let (_, scene) = SceneFile::from_json(text, "s.json").unwrap();
    assert!(matches!(scene.camera, CameraSetup::Fixed(_)));
    // Exposure +1 stop doubles every light and the ambient.
    match scene.lights[1] {
        Light::Point { intensity, .. } => assert_eq!(intensity, Vec3::splat(8.0)),
        _ => panic!("not a point light"),
    }
    assert_eq!(scene.ambient, Vec3::new(0.07, 0.08, 0.1));
}

#[test]
fn bad_fields_are_named() {
    let cases = [
        (r#"{"lights": []}"#, "lights"),
        (
            r#"{"lights": [{"type": "point", "position_m": [0, 0, 0]}]}"#,
            "lights[0]",
        ),
        (
            r#"{"lights": [{"type": "directional", "direction": [0, 0, 0], "irradiance": [1, 1, 1]}]}"#,
            "lights[0].direction",
        ),
        (
            r#"{"lights": [{"type": "directional", "direction": [0, -1, 0], "irradiance": [1, -1, 1]}]}"#,
            "lights[0].irradiance",
        ),
        (
            r#"{"lights": [{"type": "spot", "direction": [0, -1, 0]}]}"#,
            "lights[0]",
        ),
        (r#"{"image": {"width": 8, "height": 800}}"#, "image.width"),
        (
            r#"{"image": {"width": "big", "height": 800}}"#,
            "image.width",
        ),
        (r#"{"ambient": [1e39, 0, 0]}"#, "ambient"),
        (r#"{"exposure_stops": 99}"#, "exposure_stops"),
        (
            r#"{"camera": {"type": "fixed", "position_m": [0, 0, 0], "target_m": [0, 0, 0]}}"#,
            "camera.position_m",
        ),
        (
            r#"{"camera": {"type": "fixed", "position_m": [0, 0, 1], "target_m": [0, 0, 0], "fov_y_deg": 180}}"#,
            "camera.fov_y_deg",
        ),
        (r#"{"colour": [1, 1, 1]}"#, "colour"),
        (r#"{"ambient": NaN}"#, "ambient"),
        (r#"{"quality": "fast"}"#, "quality"),
        (r#"{"quality": 2}"#, "quality"),
    ];
    for (text, field) in cases {
        let (got, rule) = refused(text);
        assert!(
            got.starts_with(field),
            "{text}: field {got} ({rule}), want {field}"
        );
        assert!(!rule.is_empty());
    }
}

#[test]
fn a_point_light_inside_the_hair_is_refused() {
    let inside = [Light::point(Vec3::new(0.1, 1.6, 0.0), Vec3::ONE).unwrap()];
    let head = Vec3::new(0.0, 1.6, 0.0);
    let (field, rule) = check_point_lights_outside(&inside, head, 0.4).unwrap_err();
    assert_eq!(field, "lights[0].position_m");
    assert!(rule.contains("inside the hair"), "{rule}");
    let outside = [Light::point(Vec3::new(1.0, 1.6, 0.0), Vec3::ONE).unwrap()];
    assert!(check_point_lights_outside(&outside, head, 0.4).is_ok());
}

#[test]
fn a_quality_level_is_read_and_printed_back_and_absent_by_default() {
    let (file, _) = SceneFile::from_json(r#"{"quality": "preview"}"#, "s.json").unwrap();
    assert_eq!(file.quality, Some(Quality::Preview));
    let (again, _) = SceneFile::from_json(&file.to_json(), "printed").unwrap();
    assert_eq!(again, file);
    // The default scene names no level, so printing it says nothing of one.
    assert!(!SceneFile::default().to_json().contains("quality"));
}

/// `framing` of the engine's camera: each name is read (and printed back), absent leaves the
/// choice to the motion (`None`); an unknown name, an unknown field beside it and a framing
/// on a fixed camera are refused, naming the camera.
#[test]
fn the_follow_head_camera_takes_a_framing_and_refuses_what_it_does_not_know() {
    for f in Framing::ALL {
        let text = format!(
            r#"{{"camera": {{"type": "follow_head", "framing": "{}"}}}}"#,
            f.name()
        );
        let (file, scene) = SceneFile::from_json(&text, "s.json").unwrap();
        assert_eq!(scene.camera, CameraSetup::Framed(Some(f)));
        assert!(
            file.to_json()
                .contains(&format!("\"framing\": \"{}\"", f.name()))
        );
        assert_eq!(
            SceneFile::from_json(&file.to_json(), "s.json").unwrap().0,
            file
        );
    }
    let (file, scene) =
        SceneFile::from_json(r#"{"camera": {"type": "follow_head"}}"#, "s").unwrap();
    assert_eq!(scene.camera, CameraSetup::Framed(None));
    assert!(!file.to_json().contains("framing"));
    for text in [
        r#"{"camera": {"type": "follow_head", "framing": "legs"}}"#,
        r#"{"camera": {"type": "follow_head", "framing": "upper", "zoom": 2}}"#,
        r#"{"camera": {"type": "fixed", "position_m": [0, 0, 1], "target_m": [0, 0, 0], "framing": "upper"}}"#,
    ] {
        let (field, message) = refused(text);
        assert!(field.starts_with("camera"), "{text}: {field}: {message}");
    }
}
