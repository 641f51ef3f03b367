//! Input mutations: bytes (truncation, bit flips, special words, splices) and JSON structure
//! (missing, duplicated and wrong-typed fields; NaN/inf/huge/negative numbers; out-of-range
//! indices; wrong enum strings; arrays for objects). Each returns a short description for the
//! failure report.

use super::Rng;
use serde_json::{Map, Number, Value};

/// Marker keys and strings rewritten after serialisation: a duplicated key, and raw tokens that
/// are not valid JSON numbers (NaN, Infinity) or that serde_json would not write (1e999).
const DUP: &str = "\u{1}DUP:";
const RAW: &str = "\u{1}RAW:";

// ---------------------------------------------------------------------------------------------
// Bytes.

/// Little-endian words that break length and offset fields, and float bit patterns.
const WORDS: [u32; 12] = [
    0,
    1,
    0x7FFF_FFFF,
    0x8000_0000,
    0xFFFF_FFFF,
    0xFFFF_FFF0,
    0x7FC0_0000, // f32 NaN
    0x7F80_0000, // f32 +inf
    0xFF80_0000, // f32 -inf
    0x7149_F2CA, // f32 1e30
    0x0000_0001, // f32 smallest denormal
    0xBF80_0000, // f32 -1
];

/// One byte-level mutation of `b`.
pub fn bytes(rng: &mut Rng, b: &mut Vec<u8>) -> String {
    let len = b.len();
    match rng.below(9) {
        0 => {
            let at = rng.below(len + 1);
            b.truncate(at);
            format!("truncate at {at}")
        }
        1 if len > 0 => {
            let flips = 1 + rng.below(8);
            for _ in 0..flips {
                let at = rng.below(len);
                b[at] ^= 1 << rng.below(8);
            }
            format!("{flips} bit flips")
        }
        2 if len >= 4 => {
            let w = *rng.pick(&WORDS);
            // Aligned words hit the GLB header, chunk lengths and f32 data.
            let at = rng.below(len / 4) * 4;
            b[at..at + 4].copy_from_slice(&w.to_le_bytes());
            format!("word {w:#010x} at {at}")
        }
        3 if len > 0 => {
            let at = rng.below(len);
            let n = 1 + rng.below(64.min(len - at));
            b.drain(at..at + n);
            format!("delete {n} bytes at {at}")
        }
        4 => {
            let at = rng.below(len + 1);
            let n = 1 + rng.below(32);
            let junk: Vec<u8> = (0..n).map(|_| rng.next_u64() as u8).collect();
            b.splice(at..at, junk);
            format!("insert {n} random bytes at {at}")
        }
        5 if len > 0 => {
            let at = rng.below(len);
            let n = 1 + rng.below(256.min(len - at));
            let chunk = b[at..at + n].to_vec();
            let to = rng.below(len + 1);
            b.splice(to..to, chunk);
            format!("copy {n} bytes from {at} to {to}")
        }
        6 => {
            b.splice(0..0, *b"\xEF\xBB\xBF");
            "UTF-8 byte-order mark".into()
        }
        7 => {
            let tails: [&[u8]; 5] = [b" x", b"}", b"\0", b"{}", b"\n\n]"];
            let tail = *rng.pick(&tails);
            b.extend_from_slice(tail);
            format!("append {:?}", String::from_utf8_lossy(tail))
        }
        _ => {
            b.truncate(rng.below(len.min(64) + 1));
            "truncate within the first 64 bytes".into()
        }
    }
}

// ---------------------------------------------------------------------------------------------
// JSON.

#[derive(Clone, Debug)]
enum Seg {
    Key(String),
    Index(usize),
}

fn paths(v: &Value, at: &mut Vec<Seg>, out: &mut Vec<Vec<Seg>>) {
    out.push(at.clone());
    match v {
        Value::Object(m) => {
            for (k, c) in m {
                at.push(Seg::Key(k.clone()));
                paths(c, at, out);
                at.pop();
            }
        }
        Value::Array(a) => {
            for (i, c) in a.iter().enumerate() {
                at.push(Seg::Index(i));
                paths(c, at, out);
                at.pop();
            }
        }
        _ => {}
    }
}

fn get_mut<'a>(v: &'a mut Value, path: &[Seg]) -> Option<&'a mut Value> {
    let mut at = v;
    for s in path {
        at = match s {
            Seg::Key(k) => at.as_object_mut()?.get_mut(k)?,
            Seg::Index(i) => at.as_array_mut()?.get_mut(*i)?,
        };
    }
    Some(at)
}

fn show(path: &[Seg]) -> String {
    let mut s = String::new();
    for seg in path {
        match seg {
            Seg::Key(k) => {
                s.push('.');
                s.push_str(k);
            }
            Seg::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    if s.is_empty() { ".".into() } else { s }
}

fn num(f: f64) -> Value {
    Number::from_f64(f).map_or(Value::Null, Value::Number)
}

fn raw(token: &str) -> Value {
    Value::String(format!("{RAW}{token}"))
}

/// A replacement value: hostile numbers, raw non-JSON tokens, wrong types, wrong enums.
fn hostile_value(rng: &mut Rng, old: &Value) -> Value {
    let old_n = old.as_f64().unwrap_or(1.0);
    match rng.below(6) {
        0 => num(*rng.pick(&[
            0.0, -0.0, -1.0, 0.5, 1e30, -1e30, 1e308, -1e308, 3.5e38, 1e-45, 1e-320, 2.0, 1e9,
        ])),
        1 => {
            // Integers and indices: near and far out of range.
            let choices = [
                Value::from(old_n as i64 + 1),
                Value::from((old_n as i64).saturating_mul(1000)),
                Value::from(255u64),
                Value::from(65_535u64),
                Value::from(4_294_967_295u64),
                Value::from(4_294_967_296u64),
                Value::from(u64::MAX),
                Value::from(-1i64),
                Value::from(i64::MIN),
                Value::from(9_007_199_254_740_993u64),
            ];
            rng.pick(&choices).clone()
        }
        2 => {
            let tokens: [&str; 9] = [
                "NaN",
                "Infinity",
                "-Infinity",
                "1e999",
                "-1e999",
                "0x10",
                "01",
                "1.",
                "18446744073709551616",
            ];
            raw(tokens[rng.below(tokens.len())])
        }
        3 => Value::String(
            (*rng.pick(&[
                "",
                "bogus",
                "LINEAR",
                "STEP",
                "CUBICSPLINE",
                "linear",
                "translation",
                "rotation",
                "scale",
                "weights",
                "SCALAR",
                "VEC4",
                "MAT4",
                "data:application/octet-stream;base64,AAAA",
                "data:,",
                "../../../../etc/passwd",
                "/dev/zero",
                "%2e%2e/x.bin",
                "\u{feff}",
            ]))
            .to_string(),
        ),
        4 => rng
            .pick(&[
                Value::Null,
                Value::Bool(true),
                Value::Array(vec![]),
                Value::Object(Map::new()),
                serde_json::json!([1, 2]),
                serde_json::json!({"a": 1}),
                Value::String("1.0".into()),
            ])
            .clone(),
        _ => {
            // Deep nesting (serde_json stops at 128 levels).
            let depth = *rng.pick(&[5usize, 127, 129, 1000]);
            let mut v = Value::from(0);
            for _ in 0..depth {
                v = Value::Array(vec![v]);
            }
            v
        }
    }
}

/// A replacement of the same JSON type, chosen to break it: an out-of-range index for an
/// integer, NaN/inf/huge for a float, a wrong enum for a string.
fn typed_value(rng: &mut Rng, old: &Value) -> Value {
    match old {
        Value::Number(n) if n.is_u64() || n.is_i64() => {
            let i = n.as_i64().unwrap_or(0);
            let choices = [
                Value::from(i + 1),
                Value::from(i.saturating_mul(1000) + 7),
                Value::from(-1i64),
                Value::from(255u64),
                Value::from(4_294_967_295u64),
                Value::from(u64::MAX),
                num(i as f64 + 0.5),
            ];
            rng.pick(&choices).clone()
        }
        Value::Number(_) => {
            if rng.chance(0.3) {
                {
                    let tokens: [&str; 4] = ["NaN", "Infinity", "-Infinity", "1e999"];
                    raw(tokens[rng.below(tokens.len())])
                }
            } else {
                num(*rng.pick(&[0.0, -0.0, -1.0, 1e30, -1e30, 1e308, 3.5e38, 1e-45, 1e-320]))
            }
        }
        _ => hostile_value(rng, old),
    }
}

/// A path: with probability 0.6 a key is chosen first among the distinct keys (so that rare
/// keys such as an animation target's `node` are hit as often as common ones), then a node
/// with that key; otherwise any node.
fn pick_path(rng: &mut Rng, all: &[Vec<Seg>]) -> Vec<Seg> {
    let key_of = |p: &Vec<Seg>| match p.last() {
        Some(Seg::Key(k)) => k.clone(),
        Some(Seg::Index(_)) => "[]".to_string(),
        None => String::new(),
    };
    if rng.chance(0.6) {
        let mut keys: Vec<String> = all.iter().map(key_of).collect();
        keys.sort();
        keys.dedup();
        let key = rng.pick(&keys).clone();
        let with: Vec<&Vec<Seg>> = all.iter().filter(|p| key_of(p) == key).collect();
        return (*rng.pick(&with)).clone();
    }
    rng.pick(all).clone()
}

/// One structural mutation of the JSON value `v`.
pub fn json(rng: &mut Rng, v: &mut Value) -> String {
    let mut all = Vec::new();
    paths(v, &mut Vec::new(), &mut all);
    let path = pick_path(rng, &all);
    let Some((last, parent_path)) = path.split_last() else {
        // The root: swap the object for an array of its values, or for a scalar.
        let old = v.clone();
        *v = if rng.chance(0.5) {
            Value::Array(
                old.as_object()
                    .map(|m| m.values().cloned().collect())
                    .unwrap_or_default(),
            )
        } else {
            hostile_value(rng, &old)
        };
        return "replace the root".into();
    };
    let where_ = show(&path);
    let is_leaf = get_mut(v, &path).is_some_and(|n| !n.is_object() && !n.is_array());
    if is_leaf && rng.chance(0.6) {
        let node = get_mut(v, &path).expect("path exists");
        let old = node.clone();
        *node = typed_value(rng, &old);
        return format!("replace {where_} with {}", short(&node.to_string()));
    }
    match rng.below(7) {
        0 => {
            // Missing.
            let Some(parent) = get_mut(v, parent_path) else {
                return "nothing".into();
            };
            match (parent, last) {
                (Value::Object(m), Seg::Key(k)) => {
                    m.remove(k);
                }
                (Value::Array(a), Seg::Index(i)) if *i < a.len() => {
                    a.remove(*i);
                }
                _ => {}
            }
            format!("remove {where_}")
        }
        1 => {
            // Duplicated (same or other value).
            let Some(parent) = get_mut(v, parent_path) else {
                return "nothing".into();
            };
            match (parent, last) {
                (Value::Object(m), Seg::Key(k)) => {
                    let old = m.get(k).cloned().unwrap_or(Value::Null);
                    let dup = if rng.chance(0.5) {
                        old.clone()
                    } else {
                        hostile_value(rng, &old)
                    };
                    m.insert(format!("{DUP}{k}"), dup);
                    format!("duplicate {where_}")
                }
                (Value::Array(a), Seg::Index(i)) if *i < a.len() => {
                    let item = a[*i].clone();
                    a.insert(*i, item);
                    format!("duplicate array item {where_}")
                }
                _ => "nothing".into(),
            }
        }
        2 => {
            // Array for object, object for array.
            let Some(node) = get_mut(v, &path) else {
                return "nothing".into();
            };
            let new = match &*node {
                Value::Object(m) => Value::Array(m.values().cloned().collect()),
                Value::Array(a) => Value::Object(
                    a.iter()
                        .enumerate()
                        .map(|(i, x)| (i.to_string(), x.clone()))
                        .collect(),
                ),
                other => Value::Array(vec![other.clone()]),
            };
            *node = new;
            format!("change the kind of {where_}")
        }
        3 => {
            // Array length.
            let Some(node) = get_mut(v, &path) else {
                return "nothing".into();
            };
            if let Value::Array(a) = node {
                if rng.chance(0.5) && !a.is_empty() {
                    let n = rng.below(a.len());
                    a.truncate(n);
                    format!("shorten {where_} to {n}")
                } else {
                    let item = a.first().cloned().unwrap_or(Value::from(0));
                    let n = *rng.pick(&[1usize, 2, 100]);
                    for _ in 0..n {
                        a.push(item.clone());
                    }
                    format!("extend {where_} by {n}")
                }
            } else {
                let old = node.clone();
                *node = hostile_value(rng, &old);
                format!("replace {where_}")
            }
        }
        4 => {
            // An unknown field beside a known one.
            let Some(Value::Object(m)) = get_mut(v, parent_path) else {
                return "nothing".into();
            };
            m.insert("unknown_field".into(), Value::from(1));
            format!("unknown field beside {where_}")
        }
        _ => {
            let Some(node) = get_mut(v, &path) else {
                return "nothing".into();
            };
            let old = node.clone();
            *node = hostile_value(rng, &old);
            format!("replace {where_} with {}", short(&node.to_string()))
        }
    }
}

fn short(s: &str) -> String {
    let s: String = s.chars().take(40).collect();
    s.replace(RAW, "").replace('\u{1}', "")
}

/// The JSON text of `v`, with duplicated keys and raw tokens written out.
pub fn to_text(v: &Value) -> String {
    let s = serde_json::to_string(v).expect("a Value serialises");
    // serde_json writes U+0001 as \u0001.
    let s = s.replace("\"\\u0001DUP:", "\"");
    let mut out = String::with_capacity(s.len());
    let mut rest = s.as_str();
    let marker = "\"\\u0001RAW:";
    while let Some(at) = rest.find(marker) {
        out.push_str(&rest[..at]);
        let after = &rest[at + marker.len()..];
        let end = after.find('"').unwrap_or(after.len());
        out.push_str(&after[..end]);
        rest = &after[(end + 1).min(after.len())..];
    }
    out.push_str(rest);
    out
}

// ---------------------------------------------------------------------------------------------
// GLB.

/// A GLB split into its JSON and binary chunk, or `None` when `b` is not a well-formed GLB.
pub fn split_glb(b: &[u8]) -> Option<(Value, Vec<u8>)> {
    let u32_at = |at: usize| Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?));
    if !b.starts_with(b"glTF") {
        return None;
    }
    let json_len = u32_at(12)? as usize;
    let json: Value = serde_json::from_slice(b.get(20..20 + json_len)?).ok()?;
    let bin_at = 20 + json_len.div_ceil(4) * 4;
    let bin = match u32_at(bin_at) {
        Some(n) => b.get(bin_at + 8..bin_at + 8 + n as usize)?.to_vec(),
        None => Vec::new(),
    };
    Some((json, bin))
}

/// A GLB of `json` text and a binary chunk, with correct lengths.
pub fn make_glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut j = json.as_bytes().to_vec();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + j.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    if !bin.is_empty() {
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
    }
    out
}

/// Hostile float values: not numbers, infinities, huge, zero, negative, denormal, near the top.
pub const FLOATS: [f32; 9] = [
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    1e30,
    -1e30,
    0.0,
    -1.0,
    1e-40,
    3.4e38,
];

/// Overwrites one f32 of `bin` (4-byte aligned) with a hostile value: keyframe times and
/// values, vertex data.
pub fn floats(rng: &mut Rng, bin: &mut [u8]) -> String {
    if bin.len() < 4 {
        return "nothing".into();
    }
    let v: f32 = *rng.pick(&FLOATS);
    let n = 1 + rng.below(16);
    for _ in 0..n {
        let at = rng.below(bin.len() / 4) * 4;
        bin[at..at + 4].copy_from_slice(&v.to_le_bytes());
    }
    format!("{n} floats set to {v}")
}
