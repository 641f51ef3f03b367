//! Frame files of an export: their formats, names, and the check that a frame on disk is
//! complete (`render --resume`).
//!
//! A frame counts as complete only when it decodes in full: a PNG with its checksums (chunk
//! CRCs and the zlib Adler-32, which the png crate skips by default) through to its end chunk,
//! an OpenEXR file through every pixel. Its size must be the run's, and its kind the format's:
//! an 8-bit PNG left by `--format png` is no `png16` frame although the name is the same.
//! Names are not trusted: a frame renamed into place is whole, but a file copied in, cut off
//! by a full disk or damaged since is not. OpenEXR has no checksum, so a flipped bit inside an
//! EXR's pixel data can pass (a cut file cannot: its chunk table points past the end).

use std::fs::File;
use std::io::BufReader;
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
}

/// Checks that `path` holds a complete `width` x `height` frame of `format` (see the module
/// doc), decoding all of it. The size and kind are checked from the header before any pixel
/// buffer is allocated.
pub fn check_frame(
    path: &Path,
    format: FrameFormat,
    width: u32,
    height: u32,
) -> Result<(), FrameDefect> {
    match std::fs::metadata(path) {
        Ok(m) if m.is_file() => {}
        Ok(_) => return Err(FrameDefect::Undecodable("not a file".into())),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Err(FrameDefect::Missing),
        Err(e) => return Err(FrameDefect::Undecodable(e.to_string())),
    }
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
            check_png(path, want, format.describe(), size)
        }
        FrameFormat::Exr => {
            // The header first: the reader allocates the pixels its header announces.
            let meta = exr::meta::MetaData::read_from_file(path, false)
                .map_err(|e| FrameDefect::Undecodable(format!("OpenEXR: {e}")))?;
            let Some(header) = meta.headers.first() else {
                return Err(FrameDefect::Undecodable("OpenEXR: no layer".into()));
            };
            let announced = header.layer_size;
            size(announced.width() as u32, announced.height() as u32)?;
            if meta.headers.len() != 1 {
                return Err(FrameDefect::WrongKind {
                    got: format!("an OpenEXR file of {} layers", meta.headers.len()),
                    want: format.describe(),
                });
            }
            let (w, h, _, _) = super::read_exr_rgba_f32(path).map_err(|e| match e {
                super::OutputError::Encode { message, .. } => FrameDefect::Undecodable(message),
                e => FrameDefect::Undecodable(e.to_string()),
            })?;
            size(w, h)
        }
    }
}

/// Decodes a PNG to its end chunk with every checksum verified; `want` is its bit depth and
/// colour type, `size` checks its dimensions.
fn check_png(
    path: &Path,
    want: (png::BitDepth, png::ColorType),
    want_words: &'static str,
    size: impl Fn(u32, u32) -> Result<(), FrameDefect>,
) -> Result<(), FrameDefect> {
    let bad = |e: png::DecodingError| FrameDefect::Undecodable(format!("PNG: {e}"));
    let file = File::open(path).map_err(|e| FrameDefect::Undecodable(e.to_string()))?;
    let mut options = png::DecodeOptions::default();
    options.set_ignore_adler32(false);
    options.set_ignore_crc(false);
    let mut decoder = png::Decoder::new_with_options(BufReader::new(file), options);
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
    reader.finish().map_err(bad)
}

#[cfg(test)]
mod tests;
