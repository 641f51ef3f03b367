//! PNG frames, written atomically (`atomic.rs`): 8-bit sRGB RGB, and 16-bit sRGB RGBA with
//! straight alpha, both tagged sRGB. The samples come already encoded (`crate::color`).
//!
//! Both use the png crate's `Fast` deflate: an order of magnitude faster than its default for
//! files 20–30% larger, so encoding does not compete with rendering for the cores (the
//! measurements are with each writer).

use super::atomic::{OutputError, write_atomically};
use std::io::{BufWriter, Write};
use std::path::Path;

/// Writes an 8-bit RGB image (`rgb.len() == 3 * width * height`, rows top to bottom) to
/// `path`, through a temporary file in the same directory renamed into place on success.
///
/// Compressed with the png crate's `Fast` setting: on the writer thread the default `Balanced`
/// took about 40 ms a frame at 800×800 and competed with the renderer for the two cores; `Fast`
/// takes 4 ms, and a 20-frame export of the dance runs 5–9% faster (whole-process medians) for
/// files about 20% larger (158 against 132 KB). The pixels are the same (decoded).
pub fn write_png_rgb8(path: &Path, width: u32, height: u32, rgb: &[u8]) -> Result<(), OutputError> {
    let expected = 3 * width as usize * height as usize;
    if rgb.len() != expected || width == 0 || height == 0 {
        return Err(OutputError::Size {
            path: path.into(),
            got: rgb.len(),
            expected,
            width,
            height,
            channels: "RGB",
        });
    }
    write_atomically(path, |file| {
        let mut w = BufWriter::new(file);
        {
            let mut enc = png::Encoder::new(&mut w, width, height);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            enc.set_compression(png::Compression::Fast);
            enc.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
            let enc_err = |e| encode_error(path, e);
            let mut writer = enc.write_header().map_err(enc_err)?;
            writer.write_image_data(rgb).map_err(enc_err)?;
            writer.finish().map_err(enc_err)?;
        }
        w.into_inner().map_err(|e| OutputError::Io {
            path: path.into(),
            error: e.into_error(),
        })
    })
}

/// Writes a 16-bit RGBA image (`rgba.len() == 4 * width * height`, rows top to bottom, each
/// sample 0..=65535) to `path` as a PNG of bit depth 16, colour type RGBA, tagged sRGB,
/// through a temporary file renamed into place on success. The samples are taken as they are:
/// sRGB-encoded colour with straight (not premultiplied) alpha, as PNG defines it; see
/// `Framebuffer::to_srgb16_rgba_into`. PNG stores 16-bit samples big-endian; they are
/// converted a row at a time while streaming into the encoder.
///
/// Compressed with the png crate's `Fast` setting (fdeflate): on an 800×800 frame of the dance
/// 9 ms and 1.01 MB, against 161 ms and 0.79 MB with the default `Balanced` and 390 ms and
/// 0.78 MB with `High` (`examples/output_formats.rs`). 16-bit frames are intermediates for
/// compositing, and the encoder would otherwise cost as much as rendering.
pub fn write_png_rgba16(
    path: &Path,
    width: u32,
    height: u32,
    rgba: &[u16],
) -> Result<(), OutputError> {
    let expected = 4 * width as usize * height as usize;
    if rgba.len() != expected || width == 0 || height == 0 {
        return Err(OutputError::Size {
            path: path.into(),
            got: rgba.len(),
            expected,
            width,
            height,
            channels: "RGBA",
        });
    }
    write_atomically(path, |file| {
        let mut w = BufWriter::new(file);
        {
            let mut enc = png::Encoder::new(&mut w, width, height);
            enc.set_color(png::ColorType::Rgba);
            enc.set_depth(png::BitDepth::Sixteen);
            enc.set_compression(png::Compression::Fast);
            enc.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
            let enc_err = |e| encode_error(path, e);
            let io_err = |error| OutputError::Io {
                path: path.into(),
                error,
            };
            let mut writer = enc.write_header().map_err(enc_err)?;
            let mut stream = writer.stream_writer().map_err(enc_err)?;
            let mut row_be = vec![0u8; 2 * 4 * width as usize];
            for row in rgba.chunks_exact(4 * width as usize) {
                for (o, v) in row_be.chunks_exact_mut(2).zip(row) {
                    o.copy_from_slice(&v.to_be_bytes());
                }
                stream.write_all(&row_be).map_err(io_err)?;
            }
            stream.finish().map_err(enc_err)?;
        }
        w.into_inner().map_err(|e| OutputError::Io {
            path: path.into(),
            error: e.into_error(),
        })
    })
}

/// The encoder's error: a failed write (a full disk, the file-size limit) as
/// [`OutputError::Io`], anything else as [`OutputError::Encode`].
fn encode_error(path: &Path, e: png::EncodingError) -> OutputError {
    match e {
        png::EncodingError::IoError(error) => OutputError::Io {
            path: path.into(),
            error,
        },
        e => OutputError::Encode {
            path: path.into(),
            message: format!("PNG encoding failed: {e}"),
        },
    }
}

#[cfg(test)]
mod tests;
