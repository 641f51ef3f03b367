use super::*;
use serde::Deserialize;

#[derive(Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Inner {
    a: u32,
    #[serde(default)]
    b: f32,
}

#[derive(Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Outer {
    inner: Inner,
    list: [f32; 2],
}

fn err(text: &str) -> JsonError {
    from_str::<Outer>(text).expect_err(text)
}

#[test]
fn accepts_the_plain_form() {
    let o: Outer = from_str(r#"{"inner": {"a": 1, "b": 2.5}, "list": [1, 2]}"#).unwrap();
    assert_eq!(o.inner, Inner { a: 1, b: 2.5 });
}

#[test]
fn refuses_an_array_for_an_object() {
    let e = err(r#"{"inner": [1, 2], "list": [1, 2]}"#);
    assert_eq!(e.field, "inner");
    assert!(e.message.contains("must be an object"), "{e:?}");
}

#[test]
fn refuses_a_number_beyond_f32() {
    let e = err(r#"{"inner": {"a": 1, "b": 1e308}, "list": [1, 2]}"#);
    assert_eq!(e.field, "inner.b");
    assert!(e.message.contains("1e308"), "{e:?}");
    let e = err(r#"{"inner": {"a": 1}, "list": [1, -4e38]}"#);
    assert_eq!(e.field, "list[1]");
}

#[test]
fn refuses_trailing_text() {
    let e = err(r#"{"inner": {"a": 1}, "list": [1, 2]} x"#);
    assert_eq!(e.field, "(top level)");
    assert!(e.message.contains("after the JSON value"), "{e:?}");
}

#[test]
fn text_skips_a_utf8_bom_and_refuses_utf16() {
    assert_eq!(decode_text(b"\xEF\xBB\xBF{}").unwrap(), "{}");
    assert!(
        decode_text(b"\xFF\xFE{\0}\0")
            .unwrap_err()
            .message
            .contains("UTF-16")
    );
    let e = decode_text(b"{\n  \"a\": \xC3(").unwrap_err();
    assert!(e.message.contains("line 2 column 8"), "{e:?}");
}

/// serde's caveat (serde-rs/serde#2123, #2294): `deny_unknown_fields` on an internally tagged
/// enum does not reach its unit variants.
#[derive(Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
enum Tagged {
    Bare,
    Fields { x: f32 },
}

#[derive(Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Holder {
    items: Vec<Tagged>,
}

#[test]
fn refuses_an_unknown_field_in_a_unit_variant_of_a_tagged_enum() {
    let text = r#"{"items": [{"type": "fields", "x": 1}, {"type": "bare", "zzz": [1, 2]}]}"#;
    // serde alone lets it through: the caveat this check is for.
    assert!(serde_json::from_str::<Holder>(text).is_ok());
    let e = from_str::<Holder>(text).expect_err(text);
    assert_eq!(e.field, "items[1]");
    assert_eq!(e.message, "unknown field `zzz`, expected one of `type`");
    // A struct variant is refused by serde itself, naming its fields.
    let e = from_str::<Holder>(r#"{"items": [{"type": "fields", "x": 1, "zzz": 0}]}"#)
        .expect_err("struct variant");
    assert!(
        e.message.contains("unknown field `zzz`, expected `x`"),
        "{e:?}"
    );
    // An absent option written as null (not written back) is not an unknown field.
    assert_eq!(from_str::<Maybe>(r#"{"o": null}"#), Ok(Maybe { o: None }));
}

#[derive(Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Maybe {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    o: Option<f32>,
}
