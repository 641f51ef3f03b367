use super::*;
use crate::output::{write_exr_rgba_f32, write_png_rgb8, write_png_rgba16};
use glam::Vec3;

#[test]
fn names_and_extensions() {
    assert_eq!(FrameFormat::Png8.file_name(12), "frame_00012.png");
    assert_eq!(FrameFormat::Png16.file_name(12), "frame_00012.png");
    assert_eq!(FrameFormat::Exr.file_name(123_456), "frame_123456.exr");
}

/// Every way a frame can be incomplete is caught: missing, cut at any of a spread of
/// lengths (including inside the last chunk and inside the end chunk), one byte flipped
/// inside the image data, wrong size, wrong kind; and the complete frames pass.
#[test]
fn only_complete_frames_pass() {
    let dir = std::env::temp_dir().join(format!("wisp-frames-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // Large enough for several EXR chunks (16 rows each for ZIP) and several PNG rows.
    let (w, h) = (40u32, 37u32);
    let n = (w * h) as usize;
    let rgb8: Vec<u8> = (0..3 * n).map(|i| (i * 37 % 251) as u8).collect();
    let rgba16: Vec<u16> = (0..4 * n).map(|i| (i * 7919 % 65_521) as u16).collect();
    let rgb: Vec<Vec3> = (0..n).map(|i| Vec3::splat(i as f32 * 0.1)).collect();
    let alpha: Vec<f32> = (0..n).map(|i| i as f32 / n as f32).collect();
    let p8 = dir.join("a.png");
    let p16 = dir.join("b.png");
    let pexr = dir.join("c.exr");
    write_png_rgb8(&p8, w, h, &rgb8).unwrap();
    write_png_rgba16(&p16, w, h, &rgba16).unwrap();
    write_exr_rgba_f32(&pexr, w, h, &rgb, &alpha).unwrap();
    use FrameFormat::*;
    assert_eq!(check_frame(&p8, Png8, w, h), Ok(()));
    assert_eq!(check_frame(&p16, Png16, w, h), Ok(()));
    assert_eq!(check_frame(&pexr, Exr, w, h), Ok(()));
    assert_eq!(
        check_frame(&dir.join("none.png"), Png8, w, h),
        Err(FrameDefect::Missing)
    );
    assert!(matches!(
        check_frame(&p8, Png16, w, h),
        Err(FrameDefect::WrongKind { .. })
    ));
    assert!(matches!(
        check_frame(&p16, Png8, w, h),
        Err(FrameDefect::WrongKind { .. })
    ));
    assert!(matches!(
        check_frame(&p8, Png8, w, h + 1),
        Err(FrameDefect::WrongSize { .. })
    ));
    assert!(matches!(
        check_frame(&pexr, Exr, w + 1, h),
        Err(FrameDefect::WrongSize { .. })
    ));
    assert!(matches!(
        check_frame(&p8, Exr, w, h),
        Err(FrameDefect::Undecodable(_))
    ));
    assert!(matches!(
        check_frame(&dir, Png8, w, h),
        Err(FrameDefect::Undecodable(_))
    ));
    // A header announcing 100,000 x 100,000 pixels (40 GB as f32 RGBA) is refused from the
    // header, before the reader allocates them.
    let huge = dir.join("huge.exr");
    let mut bytes = std::fs::read(&pexr).unwrap();
    let window = b"dataWindow\0box2i\0";
    let at = bytes
        .windows(window.len())
        .position(|x| x == window)
        .unwrap()
        + window.len()
        + 4;
    bytes[at + 8..at + 16].copy_from_slice(&[0x9f, 0x86, 1, 0, 0x9f, 0x86, 1, 0]);
    std::fs::write(&huge, &bytes).unwrap();
    assert!(matches!(
        check_frame(&huge, Exr, w, h),
        Err(FrameDefect::WrongSize {
            got_width: 100_000,
            got_height: 100_000,
            ..
        })
    ));
    let cut = dir.join("cut");
    for (src, format) in [(&p8, Png8), (&p16, Png16), (&pexr, Exr)] {
        let bytes = std::fs::read(src).unwrap();
        let len = bytes.len();
        let mut lengths: Vec<usize> = (0..len).step_by(len / 23 + 1).collect();
        lengths.extend([len - 1, len - 4, len - 12, len - 13]);
        for keep in lengths {
            std::fs::write(&cut, &bytes[..keep]).unwrap();
            assert!(
                matches!(
                    check_frame(&cut, format, w, h),
                    Err(FrameDefect::Undecodable(_))
                ),
                "{format:?} cut to {keep} of {len} bytes passed"
            );
        }
    }
    // A flipped bit in the compressed image data of each PNG (the IDAT chunk's payload).
    for (src, format) in [(&p8, Png8), (&p16, Png16)] {
        let mut bytes = std::fs::read(src).unwrap();
        let idat = bytes.windows(4).position(|x| x == b"IDAT").unwrap();
        bytes[idat + 8] ^= 0x10;
        std::fs::write(&cut, &bytes).unwrap();
        assert!(
            matches!(
                check_frame(&cut, format, w, h),
                Err(FrameDefect::Undecodable(_))
            ),
            "{format:?} with a flipped bit passed"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
