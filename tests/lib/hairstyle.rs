//! Hairstyle files: every bad input gets an error naming the file, the field and the rule,
//! and nothing panics.

use wisp::hairstyle::{Hairstyle, HairstyleError, SMOOTH_JSON};

/// The smooth preset with one JSON edit applied (`path` of object keys, new value).
fn edited(path: &[&str], value: serde_json::Value) -> String {
    let mut v: serde_json::Value = serde_json::from_str(SMOOTH_JSON).unwrap();
    let mut at = &mut v;
    for k in &path[..path.len() - 1] {
        at = at.get_mut(*k).unwrap();
    }
    at.as_object_mut()
        .unwrap()
        .insert(path[path.len() - 1].to_string(), value);
    v.to_string()
}

fn removed(path: &[&str]) -> String {
    let mut v: serde_json::Value = serde_json::from_str(SMOOTH_JSON).unwrap();
    let mut at = &mut v;
    for k in &path[..path.len() - 1] {
        at = at.get_mut(*k).unwrap();
    }
    at.as_object_mut().unwrap().remove(path[path.len() - 1]);
    v.to_string()
}

fn error_of(text: &str) -> String {
    match Hairstyle::from_json(text, "hair.json") {
        Ok(_) => panic!("accepted an invalid hairstyle: {text}"),
        Err(e) => e.to_string(),
    }
}

fn assert_names(text: &str, field: &str, rule_word: &str) {
    let msg = error_of(text);
    assert!(msg.starts_with("hair.json"), "file not named: {msg}");
    assert!(
        msg.contains(&format!("`{field}`")),
        "field `{field}` not named: {msg}"
    );
    assert!(
        msg.contains(rule_word),
        "rule `{rule_word}` not stated: {msg}"
    );
}

#[test]
fn presets_are_valid() {
    assert_eq!(Hairstyle::default_smooth().name, "smooth");
    assert_eq!(Hairstyle::default_curly().name, "curly");
}

#[test]
fn missing_fields_are_named() {
    assert_names(&removed(&["wisps"]), "(top level)", "missing field `wisps`");
    assert_names(
        &removed(&["wisps", "count"]),
        "wisps",
        "missing field `count`",
    );
    assert_names(
        &removed(&["guides", "length_m"]),
        "guides",
        "missing field `length_m`",
    );
}

#[test]
fn wrong_types_are_named() {
    assert_names(
        &edited(&["wisps", "count"], "many".into()),
        "wisps.count",
        "invalid type",
    );
    assert_names(
        &edited(&["head", "radii_m"], serde_json::json!([0.1, 0.1])),
        "head.radii_m",
        "invalid length",
    );
    assert_names(
        &edited(&["fiber", "sigma_a"], serde_json::json!("brown")),
        "fiber.sigma_a",
        "invalid type",
    );
    assert_names(
        &edited(&["guides", "links"], serde_json::json!(-3)),
        "guides.links",
        "invalid value",
    );
}

#[test]
fn zero_and_negative_values_are_named() {
    assert_names(
        &edited(&["wisps", "count"], 0.into()),
        "wisps.count",
        "[1, 100000]",
    );
    assert_names(
        &edited(&["wisps", "strands_per_wisp"], 0.into()),
        "wisps.strands_per_wisp",
        ">= 1",
    );
    assert_names(
        &edited(&["guides", "length_m"], (-0.3).into()),
        "guides.length_m",
        "(0, 2]",
    );
    assert_names(
        &edited(&["strands", "points"], 1.into()),
        "strands.points",
        ">= 2",
    );
    assert_names(
        &edited(&["strands", "fibers_per_strand"], 0.into()),
        "strands.fibers_per_strand",
        "(0, 100000]",
    );
    assert_names(
        &edited(&["head", "radii_m"], serde_json::json!([0.07, 0.0, 0.09])),
        "head.radii_m[1]",
        "finite",
    );
    assert_names(
        &edited(&["fiber", "eta"], 0.5.into()),
        "fiber.eta",
        "(1, 4)",
    );
    assert_names(
        &edited(&["dynamics", "step_s"], 0.into()),
        "dynamics.step_s",
        "seconds",
    );
}

#[test]
fn nan_and_infinity_are_rejected() {
    // JSON has no NaN literal; a writer that emits one produces invalid JSON, which must still
    // be reported at the field where it stands.
    let text = SMOOTH_JSON.replace("\"length_m\": 0.34", "\"length_m\": NaN");
    assert_names(&text, "guides.length_m", "expected value");
    // Numbers too large for f32 become infinity in serde's f32 parsing, or are refused.
    let text = SMOOTH_JSON.replace("\"length_m\": 0.34", "\"length_m\": 1e60");
    let msg = error_of(&text);
    assert!(msg.contains("guides.length_m"), "{msg}");
}

#[test]
fn sizes_that_would_exhaust_memory_are_refused_before_allocating() {
    assert_names(
        &edited(&["wisps", "count"], 4_000_000_000u64.into()),
        "wisps.count",
        "[1, 100000]",
    );
    assert_names(
        &edited(&["wisps", "strands_per_wisp"], 1_000_000.into()),
        "wisps.strands_per_wisp",
        "exceeds the limit",
    );
    assert_names(
        &edited(&["strands", "points"], 100_000.into()),
        "strands.points",
        "exceeds the limit",
    );
    assert_names(
        &edited(&["guides", "links"], 100_000.into()),
        "guides.links",
        "[1, 256]",
    );
    // Beyond u32: a type error, still named.
    assert_names(
        &edited(&["wisps", "count"], serde_json::json!(1e20)),
        "wisps.count",
        "invalid type",
    );
}

#[test]
fn unknown_fields_and_broken_json_are_reported() {
    assert_names(
        &edited(&["wisps", "colour"], "red".into()),
        "wisps.colour",
        "unknown field",
    );
    let msg = error_of("{ \"name\": \"x\", ");
    assert!(msg.contains("hair.json"), "{msg}");
    let msg = error_of("");
    assert!(msg.contains("hair.json"), "{msg}");
}

#[test]
fn unreadable_file_is_an_io_error_naming_the_path() {
    let e = Hairstyle::load(std::path::Path::new("/no/such/dir/hair.json")).unwrap_err();
    assert!(matches!(e, HairstyleError::Io { .. }));
    assert!(e.to_string().contains("/no/such/dir/hair.json"));
}

/// The generated `dense` preset (issue 12's heavy scene) is smooth at Bertails 2005's scale:
/// 134 wisps × 653 one-fibre strands of 14 points, 1.14 M segments, and valid.
#[test]
fn dense_preset_is_smooth_at_bertails_scale() {
    let d = Hairstyle::dense();
    let s = Hairstyle::from_json(SMOOTH_JSON, "smooth").expect("smooth");
    assert_eq!(d.name, "dense");
    let strands = d.wisps.count as u64 * d.wisps.strands_per_wisp as u64;
    assert_eq!(strands, 87_502);
    assert_eq!(strands * (d.strands.points as u64 - 1), 1_137_526);
    assert_eq!(d.strands.fibers_per_strand, 1.0);
    assert!(d.validate().is_ok());
    // Everything else is smooth's.
    assert_eq!(d.fiber, s.fiber);
    assert_eq!(d.head.radii_m, s.head.radii_m);
    assert_eq!(d.guides.length_m, s.guides.length_m);
}
