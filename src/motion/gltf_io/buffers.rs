//! The bytes of the glTF's buffers (and of images given by URI): the GLB binary chunk, a
//! `data:` base64 URI, or a file next to the `.gltf` (relative path, `%XX` escapes decoded).
//!
//! Only buffer 0 may be the GLB's binary chunk (glTF §4.4.3.3): without this rule a thousand
//! URI-less buffers would copy the chunk a thousand times. External files are read through
//! [`read_capped`] and share one budget of [`MAX_BUFFER_BYTES`] per load; absolute paths and
//! other URI schemes are refused, so a file only ever reads beside itself.

use std::path::Path;

use super::MAX_BUFFER_BYTES;
use crate::input::{ReadError, read_capped};
use crate::motion::error::MotionError;

/// Every buffer of `doc`, each at least its `byteLength` long. `bin` is the GLB binary chunk;
/// relative URIs are resolved in `base_dir`.
pub(super) fn resolve_buffers(
    doc: &gltf::Document,
    bin: Option<&[u8]>,
    file: &str,
    base_dir: Option<&Path>,
) -> Result<Vec<Vec<u8>>, MotionError> {
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
            // Only the first buffer may be the GLB's binary chunk (see the module doc).
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
    Ok(buffers)
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
fn decode_base64(s: &str) -> Result<Vec<u8>, String> {
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
