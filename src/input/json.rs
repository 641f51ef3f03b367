//! Strict JSON for wisp's JSON formats (hairstyles and scene files).
//!
//! serde_json and derived structs accept more than a format says:
//! - an array where an object is expected fills the fields in declaration order, so
//!   `"guides": [1, 2]` silently becomes 1 link of 2 m;
//! - a number beyond the range of `f32` becomes infinity, which validation then reports as
//!   "got inf" although the file says 1e308;
//! - a byte-order mark gives "expected value at line 1 column 1".
//!
//! [`from_str`] refuses all of these, naming the field, after a normal serde pass: the value
//! is serialized back and compared with the parsed text, so every place where the type has an
//! object must hold an object in the file, and every number must have survived the conversion.
//! Trailing text after the value is refused too, and so is a field the type did not keep: serde's
//! `deny_unknown_fields` does not reach the unit and newtype variants of an internally tagged
//! enum (serde-rs/serde#2123, #2294), so `{"type": "unit_variant", "zzz": 1}` would load.

use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value;

/// A JSON error at a field. `field` is a path such as `wisps.count` or `head.radii_m[0]`,
/// or `(top level)`.
#[derive(Clone, Debug, PartialEq)]
pub struct JsonError {
    /// Path of the field.
    pub field: String,
    /// What is wrong.
    pub message: String,
}

const TOP: &str = "(top level)";

fn top(message: String) -> JsonError {
    JsonError {
        field: TOP.to_string(),
        message,
    }
}

/// The UTF-8 text of a file: a UTF-8 byte-order mark is skipped (RFC 8259 §8.1 allows a parser
/// to ignore it), UTF-16/32 and invalid UTF-8 are refused with the position of the problem.
pub fn decode_text(bytes: &[u8]) -> Result<&str, JsonError> {
    let body = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    if body.starts_with(&[0, 0, 0xFE, 0xFF]) || body.starts_with(&[0xFF, 0xFE, 0, 0]) {
        return Err(top(
            "the file is UTF-32 text (it starts with a UTF-32 byte-order mark); save it as UTF-8"
                .into(),
        ));
    }
    if body.starts_with(&[0xFE, 0xFF]) || body.starts_with(&[0xFF, 0xFE]) {
        return Err(top(
            "the file is UTF-16 text (it starts with a UTF-16 byte-order mark); save it as UTF-8"
                .into(),
        ));
    }
    std::str::from_utf8(body).map_err(|e| {
        let at = e.valid_up_to();
        let before = &body[..at];
        let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
        let column = at
            - before
                .iter()
                .rposition(|&b| b == b'\n')
                .map_or(0, |p| p + 1)
            + 1;
        top(format!(
            "not UTF-8 text: byte 0x{:02x} at line {line} column {column} is not valid UTF-8",
            body[at]
        ))
    })
}

/// Parses `text` as one `T`, strictly (see the module doc).
pub fn from_str<T: DeserializeOwned + Serialize>(text: &str) -> Result<T, JsonError> {
    let de = &mut serde_json::Deserializer::from_str(text);
    let value: T = serde_path_to_error::deserialize(&mut *de).map_err(|e| {
        let field = e.path().to_string();
        JsonError {
            field: if field == "." { TOP.into() } else { field },
            message: e.into_inner().to_string(),
        }
    })?;
    de.end()
        .map_err(|e| top(format!("unexpected text after the JSON value: {e}")))?;
    // The text is valid JSON now; compare it with what the type made of it.
    let given: Value = serde_json::from_str(text).map_err(|e| top(e.to_string()))?;
    if let Ok(kept) = serde_json::to_value(&value) {
        let mut path = String::new();
        check_shape(&given, &kept, &mut path)?;
    }
    Ok(value)
}

/// Walks the file's value `given` beside the value the type kept, `kept`.
fn check_shape(given: &Value, kept: &Value, path: &mut String) -> Result<(), JsonError> {
    let here = |path: &str, message: String| JsonError {
        field: if path.is_empty() {
            TOP.into()
        } else {
            path.to_string()
        },
        message,
    };
    match (given, kept) {
        (Value::Array(_), Value::Object(fields)) => {
            let names: Vec<&str> = fields.keys().map(String::as_str).take(4).collect();
            Err(here(
                path,
                format!(
                    "must be an object with named fields ({{\"{}\": ...}}), not an array",
                    names.join("\": ..., \"")
                ),
            ))
        }
        (Value::Object(g), Value::Object(k)) => {
            for (name, gv) in g {
                if let Some(kv) = k.get(name) {
                    let len = path.len();
                    if !path.is_empty() {
                        path.push('.');
                    }
                    path.push_str(name);
                    check_shape(gv, kv, path)?;
                    path.truncate(len);
                } else if !gv.is_null() {
                    // Not kept: a field serde let through (a `null` is an absent option,
                    // which is not written back).
                    let names: Vec<&str> = k.keys().map(String::as_str).collect();
                    return Err(here(
                        path,
                        format!(
                            "unknown field `{name}`, expected {}",
                            if names.is_empty() {
                                "no fields".to_string()
                            } else {
                                format!("one of `{}`", names.join("`, `"))
                            }
                        ),
                    ));
                }
            }
            Ok(())
        }
        (Value::Array(g), Value::Array(k)) => {
            for (i, (gv, kv)) in g.iter().zip(k).enumerate() {
                let len = path.len();
                path.push_str(&format!("[{i}]"));
                check_shape(gv, kv, path)?;
                path.truncate(len);
            }
            Ok(())
        }
        // A number that became null: a float the field's type cannot hold (serde_json writes
        // non-finite floats as null).
        (Value::Number(n), Value::Null) => Err(here(
            path,
            format!(
                "{} is outside the range of a 32-bit float (about ±3.4e38)",
                n.as_f64()
                    .map_or_else(|| n.to_string(), |f| format!("{f:e}"))
            ),
        )),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests;
