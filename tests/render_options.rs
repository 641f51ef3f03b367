//! The engine options for comparisons with other renderers (issue 14): camera, solids, ambient,
//! coverage channel, and the guarantee that the pre-issue-14 configuration still renders
//! byte for byte what it rendered before.

use glam::{Affine3A, Vec3};
use wisp::frame::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;
use wisp::raster::LineStyle;
use wisp::scene::{CameraSetup, CameraSpec};

fn engine(config: EngineConfig) -> Engine {
    Engine::new(
        Hairstyle::default_smooth(),
        Motion::still(Affine3A::IDENTITY),
        config,
    )
}

fn small() -> EngineConfig {
    EngineConfig {
        width: 160,
        height: 160,
        ..Default::default()
    }
}

fn decode_png(path: &std::path::Path) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(path).expect("golden image"),
    ));
    let mut reader = decoder.read_info().expect("png header");
    let mut buf = vec![0; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut buf).expect("png data");
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// `tests/golden/default_still_160.png` is `wisp render --still --frames 1 --width 160
/// --height 160` from main at 6039f6e/7d94265, before issue 14. The options added since
/// (camera setup, solids switch, coverage channel, EXR output) must not change a single byte
/// of that configuration, whose lines are 1 px at opacity 0.85 (`LineStyle::pixels`).
/// Tolerance 0. On failure a diff image (|a − b| × 16) is written to the target's temp dir.
/// A deliberate change of the map or the shader changes these bytes: regenerate the golden
/// with `WISP_UPDATE_GOLDEN=1 cargo test --release --test render_options` and say why in the
/// commit.
#[test]
fn pre_issue_14_configuration_renders_byte_identical_png() {
    let golden =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden/default_still_160.png");
    let mut config = small();
    config.line = LineStyle::pixels(1.0, 0.85);
    let mut e = engine(config);
    let rgb = e.frame(0.0).to_srgb8();
    if std::env::var_os("WISP_UPDATE_GOLDEN").is_some() {
        wisp::output::write_png_rgb8(&golden, 160, 160, &rgb).unwrap();
        println!("updated {}", golden.display());
        return;
    }
    let (w, h, want) = decode_png(&golden);
    assert_eq!((w, h), (160, 160));
    if rgb != want {
        let diff: Vec<u8> = rgb
            .iter()
            .zip(&want)
            .map(|(a, b)| a.abs_diff(*b).saturating_mul(16))
            .collect();
        let out =
            std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("default_still_160_diff.png");
        wisp::output::write_png_rgb8(&out, w, h, &diff).unwrap();
        let n = rgb
            .chunks(3)
            .zip(want.chunks(3))
            .filter(|(a, b)| a != b)
            .count();
        panic!(
            "{n} pixels differ from the golden image; diff in {}",
            out.display()
        );
    }
}
