//! Golden images: a frame compared with a PNG in `tests/golden/`, per channel within a stated
//! tolerance, writing a diff image (|a − b| × 16) to the target's temp dir on failure.
//! `WISP_UPDATE_GOLDEN=1 cargo test --release --test lib -- MODULE::` rewrites the goldens (say why in the
//! commit).

use std::path::{Path, PathBuf};

/// The path of golden image `name` in `tests/golden/`.
pub fn golden_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(name)
}

/// Decodes an 8-bit RGB PNG: (width, height, bytes).
pub fn decode_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let file = std::fs::File::open(path)
        .unwrap_or_else(|e| panic!("golden image {}: {e}", path.display()));
    let decoder = png::Decoder::new(std::io::BufReader::new(file));
    let mut reader = decoder.read_info().expect("png header");
    let mut buf = vec![0; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut buf).expect("png data");
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Compares `rgb` (8-bit sRGB, `width` × `height`) with golden image `name`: every channel
/// within `tolerance` levels. Panics naming the count of pixels over it and the diff image.
pub fn assert_golden(name: &str, width: u32, height: u32, rgb: &[u8], tolerance: u8) {
    let golden = golden_path(name);
    if std::env::var_os("WISP_UPDATE_GOLDEN").is_some() {
        wisp::output::write_png_rgb8(&golden, width, height, rgb).unwrap();
        println!("updated {}", golden.display());
        return;
    }
    let (w, h, want) = decode_png(&golden);
    assert_eq!((w, h), (width, height), "{name}: size");
    let over = rgb
        .chunks(3)
        .zip(want.chunks(3))
        .filter(|(a, b)| a.iter().zip(*b).any(|(x, y)| x.abs_diff(*y) > tolerance))
        .count();
    if over > 0 {
        let diff: Vec<u8> = rgb
            .iter()
            .zip(&want)
            .map(|(a, b)| a.abs_diff(*b).saturating_mul(16))
            .collect();
        let stem = name.trim_end_matches(".png");
        let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{stem}_diff.png"));
        wisp::output::write_png_rgb8(&out, w, h, &diff).unwrap();
        panic!(
            "{name}: {over} pixels differ by more than {tolerance} levels from the golden image; diff in {}",
            out.display()
        );
    }
}
