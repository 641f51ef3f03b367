use super::*;

#[test]
fn round_trips_linear_floats_and_coverage_exactly() {
    let dir = std::env::temp_dir().join(format!("wisp-exr-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("a.exr");
    // Values an 8-bit PNG cannot hold: above 1, tiny, and many distinct levels.
    let rgb: Vec<Vec3> = (0..12)
        .map(|i| Vec3::new(i as f32 * 0.37, 1e-6 * i as f32, 7.5))
        .collect();
    let alpha: Vec<f32> = (0..12).map(|i| i as f32 / 11.0).collect();
    assert!(matches!(
        write_exr_rgba_f32(&p, 4, 4, &rgb, &alpha),
        Err(OutputError::PixelCount { .. })
    ));
    assert!(!p.exists());
    write_exr_rgba_f32(&p, 4, 3, &rgb, &alpha).unwrap();
    assert!(!dir.join("a.exr.tmp").exists());
    let (w, h, rgb2, alpha2) = read_exr_rgba_f32(&p).unwrap();
    assert_eq!((w, h), (4, 3));
    assert_eq!(rgb2, rgb);
    assert_eq!(alpha2, alpha);
    let missing = dir.join("no-such-dir").join("b.exr");
    assert!(matches!(
        write_exr_rgba_f32(&missing, 4, 3, &rgb, &alpha),
        Err(OutputError::Io { .. })
    ));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_same_image_gives_the_same_bytes() {
    // 300 × 200 is 5 × 4 tiles, compressed in parallel. In increasing line order the writer
    // sorts them before writing, so every write is the same file; the order is in the
    // header for any reader to see.
    let dir = std::env::temp_dir().join(format!("wisp-exr-bytes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (w, h) = (300u32, 200u32);
    let rgb: Vec<Vec3> = (0..w * h)
        .map(|i| {
            Vec3::new(
                (i % 97) as f32 * 0.01,
                (i % 13) as f32,
                (i / w) as f32 * 1e-3,
            )
        })
        .collect();
    let alpha: Vec<f32> = (0..w * h).map(|i| (i % 7) as f32 / 6.0).collect();
    let mut files = Vec::new();
    for k in 0..4 {
        let p = dir.join(format!("{k}.exr"));
        write_exr_rgba_f32(&p, w, h, &rgb, &alpha).unwrap();
        files.push(std::fs::read(&p).unwrap());
    }
    assert!(
        files.windows(2).all(|f| f[0] == f[1]),
        "EXR bytes differ between writes"
    );
    let meta = exr::meta::MetaData::read_from_file(dir.join("0.exr"), false).unwrap();
    assert_eq!(meta.headers[0].line_order, LineOrder::Increasing);
    let (_, _, rgb2, alpha2) = read_exr_rgba_f32(&dir.join("0.exr")).unwrap();
    assert_eq!((rgb2, alpha2), (rgb, alpha));
    std::fs::remove_dir_all(&dir).unwrap();
}
