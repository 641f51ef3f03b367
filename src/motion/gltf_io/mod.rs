//! Reading the glTF container and its data: GLB chunks ([`glb`]), the JSON document
//! ([`document`]), buffers (GLB binary chunk, `data:` base64 URIs, relative files,
//! [`buffers`]) and accessors as f32 ([`accessor`]).
//!
//! The GLB container and accessor data are read here rather than through the gltf crate's
//! readers because those index slices after trusting the header lengths (a header whose length
//! is below 12 underflows `length − 12`); every offset is checked, so a truncated or corrupt
//! file is an error, never a panic. The JSON itself is parsed and validated by the gltf crate,
//! and checked further first where the crate's validation has gaps (see [`document`]).
//!
//! Every size is bounded before it is allocated: the file and each external buffer are read
//! through [`crate::input::read_capped`], the JSON may hold at most [`MAX_JSON_CONTAINERS`]
//! objects and arrays (each becomes a struct of up to a few hundred bytes), and all accessor
//! data decoded during one load shares one budget of [`MAX_DECODED_VALUES`] numbers (one
//! accessor read by a thousand channels is charged a thousand times).

mod accessor;
mod buffers;
mod document;
mod glb;

pub(crate) use accessor::read_accessor;
pub(crate) use buffers::read_uri;

use std::path::Path;

use super::error::MotionError;

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

/// Buffer contents and the parsed document.
pub(crate) struct Loaded {
    pub(crate) doc: gltf::Document,
    /// Folder of the file, for relative URIs (images); `None` for bytes given in memory.
    pub(crate) base_dir: Option<std::path::PathBuf>,
    pub(crate) buffers: Vec<Vec<u8>>,
    /// Accessor values that may still be decoded in this load (see [`MAX_DECODED_VALUES`]).
    pub(crate) decoded_left: std::cell::Cell<usize>,
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
    let (json, bin) = glb::container(bytes, file)?;
    let doc = document::document(json, file)?;
    let buffers = buffers::resolve_buffers(&doc, bin, file, base_dir)?;
    Ok(Loaded {
        doc,
        base_dir: base_dir.map(Path::to_path_buf),
        buffers,
        decoded_left: std::cell::Cell::new(MAX_DECODED_VALUES),
    })
}
