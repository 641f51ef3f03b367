//! Atomic PNG writing and the linear -> sRGB transfer function.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// Why an image could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The message carries the cause; it is not also a `source()`, so `{:#}` chains (anyhow)
    /// do not print it twice.
    #[error("{}: {error}", path.display())]
    Io {
        path: PathBuf,
        error: std::io::Error,
    },
    #[error("{}: PNG encoding failed: {message}", path.display())]
    Encode { path: PathBuf, message: String },
    #[error("{}: image buffer has {got} bytes, expected {expected} for {width}x{height} RGB", path.display())]
    Size {
        path: PathBuf,
        got: usize,
        expected: usize,
        width: u32,
        height: u32,
    },
    #[error(
        "{path}: image has {rgb} colours and {alpha} coverage values, expected {width}x{height} of each"
    )]
    PixelCount {
        path: PathBuf,
        rgb: usize,
        alpha: usize,
        width: u32,
        height: u32,
    },
}

/// Writes an 8-bit RGB image (`rgb.len() == 3 * width * height`, rows top to bottom) to
/// `path`, through a temporary file in the same directory renamed into place on success.
pub fn write_png_rgb8(path: &Path, width: u32, height: u32, rgb: &[u8]) -> Result<(), OutputError> {
    let expected = 3 * width as usize * height as usize;
    if rgb.len() != expected || width == 0 || height == 0 {
        return Err(OutputError::Size {
            path: path.into(),
            got: rgb.len(),
            expected,
            width,
            height,
        });
    }
    write_atomically(path, |file| {
        let mut w = BufWriter::new(file);
        {
            let mut enc = png::Encoder::new(&mut w, width, height);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            enc.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
            let enc_err = |e: png::EncodingError| OutputError::Encode {
                path: path.into(),
                message: e.to_string(),
            };
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

/// Writes a file through `<path>.tmp` in the same directory: `write` fills the temporary file
/// and hands it back, which is then synced and renamed over `path` (atomic within a directory
/// on POSIX). On any failure the temporary file is removed and `path` is left as it was.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(File) -> Result<File, OutputError>,
) -> Result<(), OutputError> {
    let mut tmp_name = path.as_os_str().to_owned();
    tmp_name.push(".tmp");
    let tmp = PathBuf::from(tmp_name);
    let io_err = |p: &Path| {
        let p = p.to_path_buf();
        move |error| OutputError::Io { path: p, error }
    };
    let result = (|| {
        let file = File::create(&tmp).map_err(io_err(&tmp))?;
        let file = write(file)?;
        file.sync_all().map_err(io_err(&tmp))?;
        std::fs::rename(&tmp, path).map_err(io_err(path))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Linear [0, 1] -> 8-bit sRGB (IEC 61966-2-1 transfer curve), rounding to nearest.
/// NaN maps to 0 and values outside [0, 1] are clamped, so no invalid value reaches a pixel.
#[inline]
pub fn linear_to_srgb8(v: f32) -> u8 {
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    let s = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_endpoints_and_midpoint() {
        assert_eq!(linear_to_srgb8(0.0), 0);
        assert_eq!(linear_to_srgb8(1.0), 255);
        // sRGB(0.5 linear) = 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5 -> 188
        assert_eq!(linear_to_srgb8(0.5), 188);
        assert_eq!(linear_to_srgb8(f32::NAN), 0);
        assert_eq!(linear_to_srgb8(f32::INFINITY), 255);
        assert_eq!(linear_to_srgb8(-3.0), 0);
    }

    #[test]
    fn writes_atomically_and_rejects_wrong_size() {
        let dir = std::env::temp_dir().join(format!("wisp-png-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("a.png");
        assert!(matches!(
            write_png_rgb8(&p, 2, 2, &[0; 5]),
            Err(OutputError::Size { .. })
        ));
        assert!(!p.exists());
        write_png_rgb8(&p, 2, 1, &[255, 0, 0, 0, 255, 0]).unwrap();
        let bytes = std::fs::read(&p).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        assert!(!dir.join("a.png.tmp").exists());
        let missing = dir.join("no-such-dir").join("b.png");
        let e = write_png_rgb8(&missing, 1, 1, &[0; 3]).unwrap_err();
        assert!(matches!(e, OutputError::Io { .. }));
        // The cause is in the message once, and not repeated as a source.
        assert_eq!(e.to_string().matches("No such file").count(), 1, "{e}");
        assert!(std::error::Error::source(&e).is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
