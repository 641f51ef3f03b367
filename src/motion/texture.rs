//! Base colour textures of a character's materials: PNG and JPEG images (embedded in a buffer
//! view, a `data:` URI or a file next to a `.gltf`), decoded once at load into linear RGB.
//!
//! glTF stores base colour textures sRGB-encoded (§3.9.2); they are decoded to linear values
//! here, so the renderer multiplies linear albedos. PNG (the `png` crate, also the output's)
//! and baseline or progressive JPEG in grey or RGB (`jpeg-decoder`) are read; any other image
//! (WebP, KTX2, CMYK JPEG) leaves the material with its colour factor and is counted
//! (`Character::unread_textures`) so that the command line can say so. Images are bounded: at
//! most [`MAX_TEXTURE_SIDE`] pixels a side and [`MAX_TEXTURE_BYTES`] decoded bytes per file.

use glam::Vec3;

use super::error::{MotionError, invalid};
use super::gltf_io::{Loaded, read_uri};

/// Longest texture side in pixels.
pub const MAX_TEXTURE_SIDE: u32 = 8192;
/// Most bytes the PNG decoder may allocate for the textures of one file.
pub const MAX_TEXTURE_BYTES: usize = 256 << 20;

/// A decoded texture: linear RGB, rows top to bottom (glTF's UV origin is the top-left corner).
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<Vec3>,
}

impl Texture {
    /// Heap bytes held.
    pub fn held_bytes(&self) -> u64 {
        (self.texels.len() * size_of::<Vec3>()) as u64
    }
}

/// Textures of one load, each decoded once.
pub(crate) struct Cache {
    /// Per glTF texture: not yet looked at, or its index in `textures` (None: unsupported).
    slots: Vec<Option<Option<usize>>>,
    textures: Vec<Texture>,
    tex_coord: Vec<u32>,
    bytes_left: usize,
    /// Textures in a format this module does not read.
    pub(crate) unsupported: usize,
}

impl Cache {
    pub(crate) fn new(textures: usize) -> Self {
        Self {
            slots: vec![None; textures],
            textures: Vec::new(),
            tex_coord: Vec::new(),
            bytes_left: MAX_TEXTURE_BYTES,
            unsupported: 0,
        }
    }

    /// Which TEXCOORD set texture `t` (an index into the decoded textures) is read with.
    pub(crate) fn tex_coord(&self, t: usize) -> Option<u32> {
        self.tex_coord.get(t).copied()
    }

    pub(crate) fn into_textures(self) -> Vec<Texture> {
        self.textures
    }

    /// The decoded texture of a material's `baseColorTexture`, or `None` when its image is in
    /// a format this module does not read.
    pub(crate) fn load(
        &mut self,
        info: &gltf::texture::Info,
        loaded: &Loaded,
        file: &str,
    ) -> Result<Option<usize>, MotionError> {
        let tex = info.texture();
        let slot = tex.index();
        if let Some(done) = self.slots.get(slot).copied().flatten() {
            return Ok(done);
        }
        let root = loaded.doc.as_json();
        let Some(image_index) = root.textures.get(slot).map(|t| t.source.value()) else {
            return Ok(None);
        };
        let at = format!("images[{image_index}]");
        let Some(image) = root.images.get(image_index) else {
            return Err(invalid(
                file,
                format!("textures[{slot}].source: {at} does not exist"),
            ));
        };
        let bytes = image_bytes(image, loaded, file, &at)?;
        let decoded = if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
            Some(
                self.decode_png(&bytes)
                    .map_err(|e| invalid(file, format!("{at}: PNG: {e}")))?,
            )
        } else if bytes.starts_with(&[0xFF, 0xD8, 0xFF]) {
            self.decode_jpeg(&bytes)
                .map_err(|e| invalid(file, format!("{at}: JPEG: {e}")))?
        } else {
            None
        };
        if decoded.is_none() {
            self.unsupported += 1;
        }
        let out = decoded.map(|t| {
            self.textures.push(t);
            self.tex_coord.push(info.tex_coord());
            self.textures.len() - 1
        });
        if let Some(s) = self.slots.get_mut(slot) {
            *s = Some(out);
        }
        Ok(out)
    }

    /// Decodes a JPEG into linear RGB texels, charging its decoded bytes (and the texels') to
    /// the file's texture budget; `None` for a pixel format without RGB (CMYK).
    fn decode_jpeg(&mut self, bytes: &[u8]) -> Result<Option<Texture>, String> {
        let mut decoder = jpeg_decoder::Decoder::new(std::io::Cursor::new(bytes));
        decoder.set_max_decoding_buffer_size(self.bytes_left);
        decoder.read_info().map_err(|e| e.to_string())?;
        let info = decoder.info().ok_or("no image header")?;
        let (w, h) = (u32::from(info.width), u32::from(info.height));
        check_side(w, h)?;
        let channels = match info.pixel_format {
            jpeg_decoder::PixelFormat::L8 => 1,
            jpeg_decoder::PixelFormat::L16 => 2,
            jpeg_decoder::PixelFormat::RGB24 => 3,
            jpeg_decoder::PixelFormat::CMYK32 => return Ok(None),
        };
        let pixels = decoder.decode().map_err(|e| e.to_string())?;
        let texel_bytes = w as usize * h as usize * size_of::<Vec3>();
        self.bytes_left = self.bytes_left.saturating_sub(pixels.len() + texel_bytes);
        let lut = srgb_to_linear_table();
        // L16 is big-endian: its high byte first.
        let texels: Vec<Vec3> = pixels
            .chunks_exact(channels)
            .map(|px| match channels {
                3 => Vec3::new(
                    lut[px[0] as usize],
                    lut[px[1] as usize],
                    lut[px[2] as usize],
                ),
                _ => Vec3::splat(lut[px[0] as usize]),
            })
            .collect();
        if texels.len() != w as usize * h as usize {
            return Err("the decoded image is shorter than its size".into());
        }
        Ok(Some(Texture {
            width: w,
            height: h,
            texels,
        }))
    }

    /// Decodes a PNG into linear RGB texels, charging its decoded bytes (and the texels') to the
    /// file's texture budget.
    fn decode_png(&mut self, bytes: &[u8]) -> Result<Texture, String> {
        let mut decoder = png::Decoder::new_with_limits(
            std::io::Cursor::new(bytes),
            png::Limits {
                bytes: self.bytes_left,
            },
        );
        decoder.set_transformations(png::Transformations::normalize_to_color8());
        let mut reader = decoder.read_info().map_err(|e| e.to_string())?;
        let (w, h) = (reader.info().width, reader.info().height);
        check_side(w, h)?;
        let size = reader
            .output_buffer_size()
            .ok_or("the image is too large")?;
        if size > self.bytes_left {
            return Err(format!(
                "{w}x{h} pixels take the textures of this file over {MAX_TEXTURE_BYTES} bytes"
            ));
        }
        let mut buf = vec![0u8; size];
        let info = reader.next_frame(&mut buf).map_err(|e| e.to_string())?;
        let channels = info.color_type.samples();
        let texel_bytes = w as usize * h as usize * size_of::<Vec3>();
        self.bytes_left = self.bytes_left.saturating_sub(size + texel_bytes);
        let lut = srgb_to_linear_table();
        let texels = buf[..info.buffer_size()]
            .chunks_exact(info.line_size)
            .flat_map(|row| row.chunks_exact(channels).take(w as usize))
            .map(|px| match channels {
                1 | 2 => Vec3::splat(lut[px[0] as usize]),
                _ => Vec3::new(
                    lut[px[0] as usize],
                    lut[px[1] as usize],
                    lut[px[2] as usize],
                ),
            })
            .collect::<Vec<_>>();
        if texels.len() != w as usize * h as usize {
            return Err("the decoded image is shorter than its size".into());
        }
        Ok(Texture {
            width: w,
            height: h,
            texels,
        })
    }
}

/// Refuses a texture without pixels or wider or taller than [`MAX_TEXTURE_SIDE`].
fn check_side(w: u32, h: u32) -> Result<(), String> {
    if w == 0 || h == 0 || w > MAX_TEXTURE_SIDE || h > MAX_TEXTURE_SIDE {
        return Err(format!(
            "{w}x{h} pixels: each side must be in [1, {MAX_TEXTURE_SIDE}]"
        ));
    }
    Ok(())
}

/// The encoded bytes of glTF image `image` (named `at` in messages): its buffer view's bytes,
/// or those of its URI (`data:` or a file next to the `.gltf`). Checked here: the crate's
/// `Image::source` unwraps a missing mimeType or uri.
fn image_bytes(
    image: &gltf::json::Image,
    loaded: &Loaded,
    file: &str,
    at: &str,
) -> Result<Vec<u8>, MotionError> {
    Ok(match (&image.buffer_view, &image.uri) {
        (Some(view), _) => {
            if image.mime_type.is_none() {
                return Err(invalid(
                    file,
                    format!("{at}: a bufferView image needs a mimeType"),
                ));
            }
            let view = loaded
                .doc
                .views()
                .nth(view.value())
                .ok_or_else(|| invalid(file, format!("{at}: bufferView out of range")))?;
            let buf = loaded
                .buffers
                .get(view.buffer().index())
                .ok_or_else(|| invalid(file, format!("{at}: missing buffer")))?;
            view.offset()
                .checked_add(view.length())
                .and_then(|end| buf.get(view.offset()..end))
                .ok_or_else(|| invalid(file, format!("{at}: its bufferView runs past its buffer")))?
                .to_vec()
        }
        (None, Some(uri)) => read_uri(uri, loaded.base_dir.as_deref(), MAX_TEXTURE_BYTES as u64)
            .map_err(|e| invalid(file, format!("{at}: {e}")))?,
        (None, None) => {
            return Err(invalid(
                file,
                format!("{at}: neither a uri nor a bufferView"),
            ));
        }
    })
}

/// 8-bit sRGB to linear (IEC 61966-2-1).
fn srgb_to_linear_table() -> [f32; 256] {
    let mut t = [0.0f32; 256];
    for (i, v) in t.iter_mut().enumerate() {
        let c = i as f32 / 255.0;
        *v = if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        };
    }
    t
}
