//! Reading the glTF container and its data: GLB chunks, buffers (GLB binary chunk, `data:`
//! base64 URIs, relative files) and accessors as f32.
//!
//! The GLB container and accessor data are read here rather than through the gltf crate's
//! readers because those index slices after trusting the header lengths (a header whose length
//! is below 12 underflows `length − 12`); every offset below is checked, so a truncated or
//! corrupt file is an error, never a panic. The JSON itself is parsed and validated by the
//! gltf crate, and then checked further where the crate's validation has gaps: it does not
//! check an animation channel's `target` (an out-of-range node or an unknown `path` made the
//! crate unwrap and panic later).
//!
//! Every size is bounded before it is allocated: the file and each external buffer are read
//! through [`crate::input::read_capped`], the JSON may hold at most [`MAX_JSON_CONTAINERS`]
//! objects and arrays (each becomes a struct of up to a few hundred bytes), and all accessor
//! data decoded during one load shares one budget of [`MAX_DECODED_VALUES`] numbers (one
//! accessor read by a thousand channels is charged a thousand times).

use std::path::Path;

use gltf::accessor::{DataType, Dimensions};
use gltf::json::validation::Checked;

use super::MotionError;
use crate::input::{ReadError, read_capped};

/// Largest glTF file (`.glb` or `.gltf`) read, in bytes.
pub const MAX_FILE_BYTES: u64 = 256 << 20;
/// Largest total of external buffer files (`.bin` next to a `.gltf`) read for one load, bytes.
pub const MAX_BUFFER_BYTES: u64 = 256 << 20;
/// Most JSON objects and arrays in a glTF document. A real rig with meshes has a few thousand;
/// without a bound, 256 MB of `{},` would deserialize into tens of gigabytes of structs.
pub const MAX_JSON_CONTAINERS: usize = 1_000_000;
/// Most accessor values (numbers) decoded during one load, over all accessors: 64 M values,
/// 256 MB as f32.
pub const MAX_DECODED_VALUES: usize = 64 << 20;
/// Most problems listed in one message (a broken file can have thousands).
const MAX_LISTED: usize = 8;

/// Buffer contents and the parsed document.
pub(crate) struct Loaded {
    pub(crate) doc: gltf::Document,
    /// Folder of the file, for relative URIs (images); `None` for bytes given in memory.
    pub(crate) base_dir: Option<std::path::PathBuf>,
    pub(crate) buffers: Vec<Vec<u8>>,
    /// Accessor values that may still be decoded in this load (see [`MAX_DECODED_VALUES`]).
    pub(crate) decoded_left: std::cell::Cell<usize>,
}

pub(crate) fn invalid(file: &str, reason: impl Into<String>) -> MotionError {
    MotionError::Invalid {
        file: file.to_string(),
        reason: reason.into(),
    }
}

fn read_u32(bytes: &[u8], at: usize) -> Option<u32> {
    let b = bytes.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// Splits a GLB into its JSON chunk and optional BIN chunk, checking every length.
fn split_glb<'a>(bytes: &'a [u8], file: &str) -> Result<(&'a [u8], Option<&'a [u8]>), MotionError> {
    let truncated = |reason: String| MotionError::Truncated {
        file: file.to_string(),
        reason,
    };
    let version = read_u32(bytes, 4).ok_or_else(|| {
        truncated(format!(
            "{} bytes, shorter than the 12-byte header",
            bytes.len()
        ))
    })?;
    if version != 2 {
        return Err(invalid(
            file,
            format!("GLB version {version}, only 2 is supported"),
        ));
    }
    let declared = read_u32(bytes, 8).ok_or_else(|| {
        truncated(format!(
            "{} bytes, shorter than the 12-byte header",
            bytes.len()
        ))
    })? as usize;
    if declared > bytes.len() {
        return Err(truncated(format!(
            "header declares {declared} bytes, the file has {}",
            bytes.len()
        )));
    }
    let body = &bytes[..declared];
    let json_len =
        read_u32(body, 12).ok_or_else(|| truncated("no JSON chunk header".to_string()))? as usize;
    if read_u32(body, 16) != Some(0x4E4F_534A) {
        return Err(invalid(file, "the first GLB chunk is not JSON"));
    }
    let json = body
        .get(20..20usize.saturating_add(json_len))
        .ok_or_else(|| truncated(format!("JSON chunk of {json_len} bytes runs past the end")))?;
    let bin_at = 20 + json_len.div_ceil(4) * 4;
    let bin = match (read_u32(body, bin_at), read_u32(body, bin_at + 4)) {
        (Some(len), Some(0x004E_4942)) => {
            let start = bin_at + 8;
            Some(
                body.get(start..start.saturating_add(len as usize))
                    .ok_or_else(|| {
                        truncated(format!("BIN chunk of {len} bytes runs past the end"))
                    })?,
            )
        }
        _ => None,
    };
    Ok((json, bin))
}

/// Objects and arrays in a JSON text, counted without parsing (string contents skipped).
fn count_containers(json: &[u8]) -> usize {
    let (mut n, mut in_string, mut escaped) = (0usize, false, false);
    for &b in json {
        if in_string {
            if escaped {
                escaped = false;
            } else if b == b'\\' {
                escaped = true;
            } else if b == b'"' {
                in_string = false;
            }
        } else {
            match b {
                b'"' => in_string = true,
                b'{' | b'[' => n += 1,
                _ => {}
            }
        }
    }
    n
}

/// "a; b; c (and 12 more)": the first few items of a long list.
pub(crate) fn short_list(items: impl ExactSizeIterator<Item = String>, sep: &str) -> String {
    let total = items.len();
    let shown: Vec<String> = items.take(MAX_LISTED).collect();
    let mut s = shown.join(sep);
    if total > shown.len() {
        s.push_str(&format!(" (and {} more)", total - shown.len()));
    }
    s
}

/// The gltf crate's error as one short sentence (its own Display lists every problem and
/// starts with "invalid glTF:", which our message already says).
fn describe(e: gltf::Error) -> String {
    match e {
        gltf::Error::Validation(list) => {
            let n = list.len();
            let items = list.into_iter().map(|(path, err)| format!("{path}: {err}"));
            format!(
                "{n} problem{}: {}",
                if n == 1 { "" } else { "s" },
                short_list(items, "; ")
            )
        }
        gltf::Error::Deserialize(e) => format!("JSON: {e}"),
        other => other.to_string(),
    }
}

/// Indices the gltf crate's validation trusts (it indexes `accessors` with a primitive's
/// POSITION attribute before checking it, and panics) or never checks (each animation channel's
/// target node and path, which its accessors then unwrap). Run before the crate's validation.
fn check_trusted_indices(root: &gltf::json::Root) -> Result<(), String> {
    let mut problems = Vec::new();
    let position = Checked::Valid(gltf::json::mesh::Semantic::Positions);
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            if let Some(acc) = prim.attributes.get(&position)
                && acc.value() >= root.accessors.len()
            {
                problems.push(format!(
                    "meshes[{m}].primitives[{p}].attributes.POSITION: accessor {} is out of range (the file has {} accessors)",
                    acc.value(),
                    root.accessors.len()
                ));
            }
        }
    }
    for (a, anim) in root.animations.iter().enumerate() {
        for (c, ch) in anim.channels.iter().enumerate() {
            let node = ch.target.node.value();
            if node >= root.nodes.len() {
                problems.push(format!(
                    "animations[{a}].channels[{c}].target.node: {node} is out of range (the file has {} nodes)",
                    root.nodes.len()
                ));
            }
            if matches!(ch.target.path, Checked::Invalid) {
                problems.push(format!(
                    "animations[{a}].channels[{c}].target.path: not one of \"translation\", \"rotation\", \"scale\", \"weights\""
                ));
            }
        }
    }
    if problems.is_empty() {
        return Ok(());
    }
    let n = problems.len();
    Err(format!(
        "{n} problem{}: {}",
        if n == 1 { "" } else { "s" },
        short_list(problems.into_iter(), "; ")
    ))
}

/// Parses the container and resolves the buffers.
pub(crate) fn parse(
    bytes: &[u8],
    file: &str,
    base_dir: Option<&Path>,
) -> Result<Loaded, MotionError> {
    // A UTF-8 byte-order mark before a .gltf's JSON is skipped (glTF §3.1 forbids writing one,
    // RFC 8259 lets a reader ignore it).
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let (json, bin) = if bytes.starts_with(b"glTF") {
        split_glb(bytes, file)?
    } else if bytes.iter().find(|b| !b.is_ascii_whitespace()) == Some(&b'{') {
        (bytes, None)
    } else {
        let head: Vec<String> = bytes.iter().take(8).map(|b| format!("{b:02x}")).collect();
        return Err(MotionError::NotGltf {
            file: file.to_string(),
            reason: if bytes.is_empty() {
                "the file is empty".to_string()
            } else {
                format!(
                    "starts with bytes [{}], neither the GLB magic \"glTF\" nor a JSON object",
                    head.join(" ")
                )
            },
        });
    };
    let containers = count_containers(json);
    if containers > MAX_JSON_CONTAINERS {
        return Err(invalid(
            file,
            format!(
                "the JSON has {containers} objects and arrays, more than the {MAX_JSON_CONTAINERS} accepted"
            ),
        ));
    }
    let root =
        gltf::json::Root::from_slice(json).map_err(|e| invalid(file, format!("JSON: {e}")))?;
    check_trusted_indices(&root).map_err(|reason| invalid(file, reason))?;
    let doc = gltf::Document::from_json(root).map_err(|e| invalid(file, describe(e)))?;
    let mut buffers = Vec::new();
    let mut external_bytes = 0u64;
    for buffer in doc.buffers() {
        let index = buffer.index();
        let err = |reason: String| MotionError::Buffer {
            file: file.to_string(),
            index,
            reason,
        };
        let data = match buffer.source() {
            // Only the first buffer may be the GLB's binary chunk (glTF §4.4.3.3); without this
            // rule a thousand URI-less buffers would copy the chunk a thousand times.
            gltf::buffer::Source::Bin if index > 0 => {
                return Err(err(
                    "has no uri, but only buffer 0 may refer to the GLB binary chunk".into(),
                ));
            }
            gltf::buffer::Source::Bin => bin
                .ok_or_else(|| err("refers to the GLB binary chunk, which is absent".into()))?
                .to_vec(),
            gltf::buffer::Source::Uri(uri) => {
                let left = MAX_BUFFER_BYTES.saturating_sub(external_bytes);
                let data = read_uri(uri, base_dir, left).map_err(err)?;
                external_bytes += data.len() as u64;
                data
            }
        };
        if data.len() < buffer.length() {
            return Err(err(format!(
                "has {} bytes, byteLength says {}",
                data.len(),
                buffer.length()
            )));
        }
        buffers.push(data);
    }
    Ok(Loaded {
        doc,
        base_dir: base_dir.map(Path::to_path_buf),
        buffers,
        decoded_left: std::cell::Cell::new(MAX_DECODED_VALUES),
    })
}

/// Bytes of a buffer URI: `data:...;base64,...` or a relative path next to the file (at most
/// `limit` bytes).
pub(crate) fn read_uri(uri: &str, base_dir: Option<&Path>, limit: u64) -> Result<Vec<u8>, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (meta, payload) = rest
            .split_once(',')
            .ok_or("data: URI without a ',' before its payload")?;
        if !meta.ends_with(";base64") {
            return Err("data: URI is not base64-encoded".to_string());
        }
        return decode_base64(payload);
    }
    if uri.contains(':') || uri.starts_with('/') || uri.starts_with('\\') {
        return Err(format!(
            "URI {uri:?} is neither a data: URI nor a relative file path (not supported)"
        ));
    }
    let dir = base_dir.ok_or_else(|| {
        format!("relative URI {uri:?} needs the file's folder: load the .gltf with Motion::load")
    })?;
    let path = dir.join(percent_decode(uri));
    read_capped(&path, limit, "the buffers of one glTF").map_err(|e| match e {
        ReadError::TooLarge { bytes, .. } if limit < MAX_BUFFER_BYTES => format!(
            "{}: {bytes} bytes would take the buffers of this glTF over {MAX_BUFFER_BYTES} bytes",
            path.display()
        ),
        e => format!("{}: {e}", path.display()),
    })
}

/// Decodes `%XX` escapes of a URI path (other characters pass through).
fn percent_decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        match (
            b[i],
            b.get(i + 1).copied().and_then(hex),
            b.get(i + 2).copied().and_then(hex),
        ) {
            (b'%', Some(h), Some(l)) => {
                out.push((h * 16 + l) as u8);
                i += 3;
            }
            (c, _, _) => {
                out.push(c);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Standard base64 (RFC 4648 §4) with optional `=` padding; whitespace is not allowed.
pub(crate) fn decode_base64(s: &str) -> Result<Vec<u8>, String> {
    let sextet = |c: u8| -> Option<u32> {
        match c {
            b'A'..=b'Z' => Some((c - b'A') as u32),
            b'a'..=b'z' => Some((c - b'a') as u32 + 26),
            b'0'..=b'9' => Some((c - b'0') as u32 + 52),
            b'+' => Some(62),
            b'/' => Some(63),
            _ => None,
        }
    };
    let data = s.trim_end_matches('=').as_bytes();
    let mut out = Vec::with_capacity(data.len() * 3 / 4);
    let (mut acc, mut bits) = (0u32, 0u32);
    for (i, &c) in data.iter().enumerate() {
        let v = sextet(c).ok_or_else(|| format!("invalid base64 character at {i}"))?;
        acc = (acc << 6) | v;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Ok(out)
}

/// An accessor's elements as f32 (integer types converted, normalised ones per glTF §3.11),
/// flattened: `count × components` values. The values are charged to `decoded_left` before
/// anything is allocated (see [`MAX_DECODED_VALUES`]).
pub(crate) fn read_accessor(
    acc: &gltf::Accessor,
    loaded: &Loaded,
) -> Result<(Vec<f32>, usize), String> {
    let buffers = &loaded.buffers;
    let comps = match acc.dimensions() {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 => 4,
        Dimensions::Mat4 => 16,
        d => {
            return Err(format!(
                "accessor {}: type {d:?} not supported",
                acc.index()
            ));
        }
    };
    if acc.sparse().is_some() {
        return Err(format!(
            "accessor {}: sparse accessors not supported",
            acc.index()
        ));
    }
    let count = acc.count();
    let values = count.saturating_mul(comps);
    let left = loaded.decoded_left.get();
    if values > left {
        return Err(format!(
            "accessor {}: {count} elements would take the data decoded from this file over {MAX_DECODED_VALUES} values",
            acc.index()
        ));
    }
    loaded.decoded_left.set(left - values);
    let Some(view) = acc.view() else {
        // No buffer view: all zeros (glTF §3.6.2.1), bounded by the budget above.
        return Ok((vec![0.0; values], comps));
    };
    let csize = acc.data_type().size();
    let elem = comps * csize;
    let stride = view.stride().unwrap_or(elem).max(elem);
    let buf = buffers
        .get(view.buffer().index())
        .ok_or_else(|| format!("accessor {}: missing buffer", acc.index()))?;
    let view_end = view.offset().checked_add(view.length());
    let view_bytes = view_end
        .and_then(|end| buf.get(view.offset()..end))
        .ok_or_else(|| format!("buffer view {} runs past its buffer", view.index()))?;
    let needed = if count == 0 {
        Some(0)
    } else {
        (count - 1)
            .checked_mul(stride)
            .and_then(|n| n.checked_add(elem))
            .and_then(|n| n.checked_add(acc.offset()))
    };
    let data = needed
        .and_then(|n| view_bytes.get(acc.offset()..n.max(acc.offset())))
        .ok_or_else(|| format!("accessor {}: runs past its buffer view", acc.index()))?;
    let mut out = Vec::with_capacity(count * comps);
    let norm = acc.normalized();
    for e in 0..count {
        for c in 0..comps {
            let at = e * stride + c * csize;
            let b = &data[at..at + csize];
            let v = match acc.data_type() {
                DataType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
                DataType::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32,
                DataType::I8 if norm => (b[0] as i8 as f32 / 127.0).max(-1.0),
                DataType::I8 => b[0] as i8 as f32,
                DataType::U8 if norm => b[0] as f32 / 255.0,
                DataType::U8 => b[0] as f32,
                DataType::I16 if norm => {
                    (i16::from_le_bytes([b[0], b[1]]) as f32 / 32767.0).max(-1.0)
                }
                DataType::I16 => i16::from_le_bytes([b[0], b[1]]) as f32,
                DataType::U16 if norm => u16::from_le_bytes([b[0], b[1]]) as f32 / 65535.0,
                DataType::U16 => u16::from_le_bytes([b[0], b[1]]) as f32,
            };
            out.push(v);
        }
    }
    Ok((out, comps))
}
