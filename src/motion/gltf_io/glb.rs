//! The GLB container (glTF 2.0 §4.4): a 12-byte header (`"glTF"`, version 2, total length),
//! a JSON chunk and an optional BIN chunk, each an 8-byte header (length, type) and its bytes.
//! Every length is checked against the bytes there are, so a truncated or corrupt container
//! is an error naming what is missing, never a slice out of range.

use crate::motion::error::{MotionError, invalid};

/// The JSON text and the GLB binary chunk (if any) of a file's bytes: a GLB is split into its
/// chunks, JSON (after any whitespace) is taken whole, anything else is refused.
pub(super) fn container<'a>(
    bytes: &'a [u8],
    file: &str,
) -> Result<(&'a [u8], Option<&'a [u8]>), MotionError> {
    if bytes.starts_with(b"glTF") {
        return split_glb(bytes, file);
    }
    if bytes.iter().find(|b| !b.is_ascii_whitespace()) == Some(&b'{') {
        return Ok((bytes, None));
    }
    let head: Vec<String> = bytes.iter().take(8).map(|b| format!("{b:02x}")).collect();
    Err(MotionError::NotGltf {
        file: file.to_string(),
        reason: if bytes.is_empty() {
            "the file is empty".to_string()
        } else {
            format!(
                "starts with bytes [{}], neither the GLB magic \"glTF\" nor a JSON object",
                head.join(" ")
            )
        },
    })
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
