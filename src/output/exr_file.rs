//! Atomic OpenEXR writing: linear RGBA in 32-bit float, for measurements against other
//! renderers (no transfer curve, no clamping, coverage as alpha).
//!
//! Lossless RLE in 64 × 64 tiles, compressed in parallel but written in increasing order, so
//! the same image gives the same bytes on every run and for any thread count.

use std::io::BufWriter;
use std::path::{Path, PathBuf};

use exr::meta::attribute::LineOrder;
use exr::prelude::{Encoding, Image, SpecificChannels, Vec2, WritableImage};
use glam::Vec3;

use super::OutputError;

/// Writes a `width` x `height` image to `path` as OpenEXR, channels R, G, B, A in 32-bit float
/// (rows top to bottom, `rgb` linear radiance and `alpha` coverage, one entry per pixel each),
/// lossless compression. Written to `<path>.tmp`, synced, then renamed into place.
///
/// The colour is written as given: OpenEXR readers take RGB as premultiplied by A, which holds
/// when the image was composited over a black background (see `raster::framebuffer`).
/// Non-finite values are written as they are (a pixel's NaN stays visible to the reader).
///
/// The tiles are compressed in parallel and written in increasing order ([`ENCODING`]), so the
/// same image gives the same bytes on every run and for any thread count.
pub fn write_exr_rgba_f32(
    path: &Path,
    width: u32,
    height: u32,
    rgb: &[Vec3],
    alpha: &[f32],
) -> Result<(), OutputError> {
    let expected = width as usize * height as usize;
    if rgb.len() != expected || alpha.len() != expected || width == 0 || height == 0 {
        return Err(OutputError::PixelCount {
            path: path.into(),
            rgb: rgb.len(),
            alpha: alpha.len(),
            width,
            height,
        });
    }
    let w = width as usize;
    let channels = SpecificChannels::rgba(|Vec2(x, y): Vec2<usize>| {
        let i = y * w + x;
        let c = rgb[i];
        (c.x, c.y, c.z, alpha[i])
    });
    let image = Image::from_encoded_channels((w, height as usize), ENCODING, channels);
    super::write_atomically(path, |file| {
        let mut writer = BufWriter::new(file);
        image
            .write()
            .to_buffered(&mut writer)
            .map_err(|e| match e {
                exr::error::Error::Io(error) => OutputError::Io {
                    path: path.into(),
                    error,
                },
                e => OutputError::Encode {
                    path: path.into(),
                    message: format!("OpenEXR encoding failed: {e}"),
                },
            })?;
        writer.into_inner().map_err(|e| OutputError::Io {
            path: path.into(),
            error: e.into_error(),
        })
    })
}

/// Reads an RGBA OpenEXR file written by [`write_exr_rgba_f32`] (any RGBA file with f32, f16
/// or u32 samples): `(width, height, rgb, alpha)`, rows top to bottom.
pub fn read_exr_rgba_f32(path: &Path) -> Result<(u32, u32, Vec<Vec3>, Vec<f32>), OutputError> {
    use exr::prelude::{ReadChannels, ReadLayers, read};
    type Pixels = (usize, Vec<[f32; 4]>);
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |size, _| -> Pixels { (size.width(), vec![[0.0; 4]; size.area()]) },
            |(w, px): &mut Pixels, pos, (r, g, b, a): (f32, f32, f32, f32)| {
                px[pos.y() * *w + pos.x()] = [r, g, b, a];
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .map_err(|e| OutputError::Encode {
            path: PathBuf::from(path),
            message: format!("OpenEXR: {e}"),
        })?;
    let size = image.layer_data.size;
    let (_, px) = image.layer_data.channel_data.pixels;
    let rgb = px.iter().map(|p| Vec3::new(p[0], p[1], p[2])).collect();
    let alpha = px.iter().map(|p| p[3]).collect();
    Ok((size.width() as u32, size.height() as u32, rgb, alpha))
}

/// The crate's fast lossless encoding (RLE, 64 × 64 tiles) with the tiles in increasing order.
/// Its default order, "unspecified", lets the parallel writer put each tile in the file when
/// its compression finishes: the same pixels, but bytes that differ from run to run (two
/// exports of one scene compared).
const ENCODING: Encoding = Encoding {
    line_order: LineOrder::Increasing,
    ..Encoding::FAST_LOSSLESS
};

#[cfg(test)]
mod tests;
