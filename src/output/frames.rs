//! Frame files of an export: their formats, names, and the check that a frame on disk is
//! complete (`render --resume`).
//!
//! A frame counts as complete only when it decodes in full and ends where its format says:
//! a PNG with every checksum (each chunk's CRC, ancillary chunks such as `sRGB` included, and
//! the zlib Adler-32, which the png crate skips by default) through its `IEND` chunk, and not
//! one byte after it; an OpenEXR file whose header has every attribute OpenEXR requires, with
//! its type, whose chunks lie end to end from the offset table to the file's last byte
//! (`exr_layout`), and which decodes through every pixel. Its size must be the run's, and its
//! kind the format's: an 8-bit PNG left by `--format png` is no `png16` frame although the
//! name is the same. Names are not trusted: a frame renamed into place is whole, but a file
//! copied in, cut off by a full disk, grown, or damaged since is not.
//!
//! Nothing is read past what the header accounts for: a PNG is read in a stream that stops at
//! `IEND`, an OpenEXR file's chunk extents are read from its offset table, and either is then
//! compared with the file's length, so a frame grown to 4 GB is refused after a few KB.
//! OpenEXR has no checksum, so a flipped bit inside an EXR's pixel data can pass.

mod exr_layout;

use std::fs::File;
use std::io::{BufReader, Seek};
use std::path::Path;

/// The file format of exported frames.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameFormat {
    /// 8-bit sRGB RGB PNG: the picture over the background, nothing else.
    Png8,
    /// 16-bit RGBA PNG: sRGB colour with straight alpha = coverage (transparent where nothing
    /// was drawn), for compositing over another background.
    Png16,
    /// OpenEXR, linear RGBA in 32-bit float, colour premultiplied by alpha = coverage.
    Exr,
}

impl FrameFormat {
    /// The file extension, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            FrameFormat::Png8 | FrameFormat::Png16 => "png",
            FrameFormat::Exr => "exr",
        }
    }

    /// `frame_00012.png`: the name of frame `index`, at least five digits.
    pub fn file_name(self, index: u32) -> String {
        format!("frame_{index:05}.{}", self.extension())
    }

    /// What a frame of this format is, in words ("16-bit RGBA PNG").
    pub fn describe(self) -> &'static str {
        match self {
            FrameFormat::Png8 => "8-bit RGB PNG",
            FrameFormat::Png16 => "16-bit RGBA PNG",
            FrameFormat::Exr => "RGBA OpenEXR",
        }
    }
}

/// Why a frame on disk is not a complete frame of the run.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum FrameDefect {
    /// No file of that name.
    #[error("missing")]
    Missing,
    /// It does not open or decode to its end: truncated, corrupt, or not an image.
    #[error("does not decode ({0})")]
    Undecodable(String),
    /// It decodes, at another size.
    #[error("is {got_width}x{got_height} px, this run makes {width}x{height}")]
    WrongSize {
        got_width: u32,
        got_height: u32,
        width: u32,
        height: u32,
    },
    /// It decodes, in another layout (bit depth, colour type).
    #[error("is {got}; this run writes {want} frames")]
    WrongKind { got: String, want: &'static str },
    /// Its image ends before the file does: bytes appended, or the file grown.
    #[error("has {} bytes after the end of its image (which ends at byte {end} of {len})", len.saturating_sub(*end))]
    Trailing {
        /// Where the image ends (its last chunk's last byte + 1).
        end: u64,
        /// The file's length in bytes.
        len: u64,
    },
}

/// Checks that `path` holds a complete `width` x `height` frame of `format` (see the module
/// doc), decoding all of it. The size and kind are checked from the header before any pixel
/// buffer is allocated, and an OpenEXR file's layout before its pixels are read.
pub fn check_frame(
    path: &Path,
    format: FrameFormat,
    width: u32,
    height: u32,
) -> Result<(), FrameDefect> {
    let len = match std::fs::metadata(path) {
        Ok(m) if m.is_file() => m.len(),
        Ok(_) => return Err(FrameDefect::Undecodable("not a file".into())),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Err(FrameDefect::Missing),
        Err(e) => return Err(FrameDefect::Undecodable(e.to_string())),
    };
    let size = |got_width, got_height| {
        if (got_width, got_height) == (width, height) {
            Ok(())
        } else {
            Err(FrameDefect::WrongSize {
                got_width,
                got_height,
                width,
                height,
            })
        }
    };
    match format {
        FrameFormat::Png8 | FrameFormat::Png16 => {
            let want = match format {
                FrameFormat::Png8 => (png::BitDepth::Eight, png::ColorType::Rgb),
                _ => (png::BitDepth::Sixteen, png::ColorType::Rgba),
            };
            check_png(path, len, want, format.describe(), size)
        }
        FrameFormat::Exr => check_exr(path, len, format.describe(), size),
    }
}

/// Checks an OpenEXR frame, `len` bytes: its header (values read strictly, every required
/// attribute present with its type), its size and layer count, its layout (the chunks end to
/// end through the file's last byte) and then every pixel; `size` checks its dimensions.
fn check_exr(
    path: &Path,
    len: u64,
    want_words: &'static str,
    size: impl Fn(u32, u32) -> Result<(), FrameDefect>,
) -> Result<(), FrameDefect> {
    use exr::meta::MetaData;
    let bad = |e: exr::error::Error| FrameDefect::Undecodable(format!("OpenEXR: {e}"));
    // The size first, read leniently (a header announcing another size is WrongSize even when
    // its other attributes disagree with it): the reader allocates the pixels it announces.
    let lenient = MetaData::read_from_file(path, false).map_err(bad)?;
    let Some(header) = lenient.headers.first() else {
        return Err(FrameDefect::Undecodable("OpenEXR: no layer".into()));
    };
    size(
        header.layer_size.width() as u32,
        header.layer_size.height() as u32,
    )?;
    if lenient.headers.len() != 1 {
        return Err(FrameDefect::WrongKind {
            got: format!("an OpenEXR file of {} layers", lenient.headers.len()),
            want: want_words,
        });
    }
    // Then strictly: an attribute value that does not parse is an error, not skipped.
    let meta = MetaData::read_from_file(path, true).map_err(bad)?;
    MetaData::validate(&meta.headers, true).map_err(bad)?;
    let layout = exr_layout::Layout {
        tiled: meta.requirements.is_single_layer_and_tiled,
        long_names: meta.requirements.has_long_names,
        chunks: meta.headers[0].chunk_count,
    };
    let file = File::open(path).map_err(|e| FrameDefect::Undecodable(e.to_string()))?;
    exr_layout::check(&mut BufReader::new(file), len, &layout)?;
    let (w, h, _, _) = super::read_exr_rgba_f32(path).map_err(|e| match e {
        super::OutputError::Encode { message, .. } => FrameDefect::Undecodable(message),
        e => FrameDefect::Undecodable(e.to_string()),
    })?;
    size(w, h)
}

/// Decodes a PNG to its end chunk with every checksum verified (ancillary chunks' CRCs too:
/// the png crate skips a failing one by default) and checks that the file, `len` bytes, ends
/// there; `want` is its bit depth and colour type, `size` checks its dimensions.
fn check_png(
    path: &Path,
    len: u64,
    want: (png::BitDepth, png::ColorType),
    want_words: &'static str,
    size: impl Fn(u32, u32) -> Result<(), FrameDefect>,
) -> Result<(), FrameDefect> {
    let bad = |e: png::DecodingError| FrameDefect::Undecodable(format!("PNG: {e}"));
    let file = File::open(path).map_err(|e| FrameDefect::Undecodable(e.to_string()))?;
    let mut options = png::DecodeOptions::default();
    options.set_ignore_adler32(false);
    options.set_ignore_crc(false);
    options.set_skip_ancillary_crc_failures(false);
    let mut read = BufReader::new(file);
    let mut decoder = png::Decoder::new_with_options(&mut read, options);
    decoder.set_transformations(png::Transformations::IDENTITY);
    let mut reader = decoder.read_info().map_err(bad)?;
    let info = reader.info();
    let (got_width, got_height) = (info.width, info.height);
    let got = (info.bit_depth, info.color_type);
    size(got_width, got_height)?;
    if got != want {
        let color = match got.1 {
            png::ColorType::Grayscale => "grey",
            png::ColorType::Rgb => "RGB",
            png::ColorType::Indexed => "palette",
            png::ColorType::GrayscaleAlpha => "grey and alpha",
            png::ColorType::Rgba => "RGBA",
        };
        return Err(FrameDefect::WrongKind {
            got: format!("a PNG of {}-bit {color}", got.0 as u8),
            want: want_words,
        });
    }
    let bytes = reader
        .output_buffer_size()
        .ok_or_else(|| FrameDefect::Undecodable("PNG: image too large".into()))?;
    let mut buf = vec![0; bytes];
    reader.next_frame(&mut buf).map_err(bad)?;
    reader.finish().map_err(bad)?;
    drop(reader);
    // The decoder consumed exactly through IEND's CRC: where the file must end.
    let end = read
        .stream_position()
        .map_err(|e| FrameDefect::Undecodable(e.to_string()))?;
    if end == len {
        Ok(())
    } else {
        Err(FrameDefect::Trailing { end, len })
    }
}

#[cfg(test)]
mod tests;
