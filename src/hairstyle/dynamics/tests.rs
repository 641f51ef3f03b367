use super::*;

#[test]
fn new_fields_are_validated_and_default_when_absent() {
    assert!(SimParams::default().validate().is_ok());
    let p: SimParams = serde_json::from_str(r#"{ "damping_per_s": 2.0 }"#).expect("parses");
    assert_eq!(p.ftl_correction, SimParams::default().ftl_correction);
    assert_eq!(p.max_catch_up_s, 0.25);
    for (bad, field) in [
        (
            SimParams {
                ftl_correction: 1.5,
                ..SimParams::default()
            },
            "ftl_correction",
        ),
        (
            SimParams {
                max_catch_up_s: 0.0,
                ..SimParams::default()
            },
            "max_catch_up_s",
        ),
        (
            SimParams {
                bending_damping_ratio: f32::NAN,
                ..SimParams::default()
            },
            "bending_damping_ratio",
        ),
    ] {
        let err = bad.validate().expect_err("must be rejected");
        assert!(err.starts_with(field), "{err}");
        assert!(bad.sanitized().validate().is_ok());
    }
}
