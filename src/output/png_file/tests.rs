use super::*;
use std::fs::File;

#[test]
fn rgba16_round_trips_big_endian_samples() {
    let dir = std::env::temp_dir().join(format!("wisp-png16-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("a.png");
    let rgba: Vec<u16> = vec![0, 1, 256, 65535, 0x1234, 0xFEDC, 300, 7];
    assert!(matches!(
        write_png_rgba16(&p, 2, 2, &rgba),
        Err(OutputError::Size { .. })
    ));
    write_png_rgba16(&p, 1, 2, &rgba).unwrap();
    assert!(!dir.join("a.png.tmp").exists());
    let decoder = png::Decoder::new(std::io::BufReader::new(File::open(&p).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (1, 2));
    assert_eq!(info.bit_depth, png::BitDepth::Sixteen);
    assert_eq!(info.color_type, png::ColorType::Rgba);
    let back: Vec<u16> = buf
        .chunks_exact(2)
        .map(|b| u16::from_be_bytes([b[0], b[1]]))
        .collect();
    assert_eq!(back, rgba);
    std::fs::remove_dir_all(&dir).unwrap();
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
