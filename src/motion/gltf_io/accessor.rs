//! Accessor data as f32 (glTF 2.0 §3.6.2): `count` elements of 1–16 components, each read at
//! `offset + e·stride + c·size` of its buffer view, integers converted and normalised ones
//! scaled to [0, 1] or [−1, 1] (`max(i / (2ⁿ⁻¹ − 1), −1)` for signed types, §3.11).
//!
//! Every range is checked before it is sliced (the view inside its buffer, the last element
//! inside the view, with overflow-checked arithmetic), and the values are charged to the
//! load's decode budget ([`MAX_DECODED_VALUES`]) before anything is allocated, so an accessor
//! claiming billions of elements is refused, not decoded.

use gltf::accessor::{DataType, Dimensions};

use super::{Loaded, MAX_DECODED_VALUES};

/// An accessor's elements as f32 (integer types converted, normalised ones per glTF §3.11),
/// flattened: `count × components` values, and the component count. The values are charged
/// to `decoded_left` before anything is allocated (see [`MAX_DECODED_VALUES`]).
pub(crate) fn read_accessor(
    acc: &gltf::Accessor,
    loaded: &Loaded,
) -> Result<(Vec<f32>, usize), String> {
    let comps = components(acc)?;
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
    let data = element_bytes(acc, &view, loaded, stride, elem)?;
    let mut out = Vec::with_capacity(count * comps);
    let norm = acc.normalized();
    for e in 0..count {
        for c in 0..comps {
            let at = e * stride + c * csize;
            out.push(component(&data[at..at + csize], acc.data_type(), norm));
        }
    }
    Ok((out, comps))
}

/// Components per element of the accessor's type (MAT2 and MAT3 are not supported).
fn components(acc: &gltf::Accessor) -> Result<usize, String> {
    Ok(match acc.dimensions() {
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
    })
}

/// The bytes of the accessor's elements in its view: from its offset to the end of its last
/// element (`stride` apart, `elem` bytes each), checked to lie inside the view and the view
/// inside its buffer.
fn element_bytes<'a>(
    acc: &gltf::Accessor,
    view: &gltf::buffer::View,
    loaded: &'a Loaded,
    stride: usize,
    elem: usize,
) -> Result<&'a [u8], String> {
    let count = acc.count();
    let buf = loaded
        .buffers
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
    needed
        .and_then(|n| view_bytes.get(acc.offset()..n.max(acc.offset())))
        .ok_or_else(|| format!("accessor {}: runs past its buffer view", acc.index()))
}

/// One component from its little-endian bytes `b`, normalised when `norm` (glTF §3.11).
#[inline]
fn component(b: &[u8], data_type: DataType, norm: bool) -> f32 {
    match data_type {
        DataType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        DataType::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32,
        DataType::I8 if norm => (b[0] as i8 as f32 / 127.0).max(-1.0),
        DataType::I8 => b[0] as i8 as f32,
        DataType::U8 if norm => b[0] as f32 / 255.0,
        DataType::U8 => b[0] as f32,
        DataType::I16 if norm => (i16::from_le_bytes([b[0], b[1]]) as f32 / 32767.0).max(-1.0),
        DataType::I16 => i16::from_le_bytes([b[0], b[1]]) as f32,
        DataType::U16 if norm => u16::from_le_bytes([b[0], b[1]]) as f32 / 65535.0,
        DataType::U16 => u16::from_le_bytes([b[0], b[1]]) as f32,
    }
}
