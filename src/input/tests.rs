use super::*;

#[test]
fn human_bytes_rounds_to_one_decimal() {
    assert_eq!(human_bytes(0), "0 B");
    assert_eq!(human_bytes(999), "999 B");
    assert_eq!(human_bytes(1_500), "1.5 KB");
    assert_eq!(human_bytes(17_920_000_000), "17.9 GB");
}

#[test]
fn refuses_directories_and_devices_before_reading() {
    let e = read_capped(Path::new("/"), 10, "a test file").unwrap_err();
    assert!(e.to_string().contains("a directory"), "{e}");
    #[cfg(unix)]
    {
        let e = read_capped(Path::new("/dev/zero"), 10, "a test file").unwrap_err();
        assert!(e.to_string().contains("character device"), "{e}");
    }
}

#[test]
fn refuses_a_file_over_the_cap_and_reads_one_at_the_cap() {
    let dir = std::env::temp_dir().join(format!("wisp-input-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("ten.bin");
    std::fs::write(&p, [7u8; 10]).unwrap();
    assert_eq!(read_capped(&p, 10, "a test file").unwrap(), vec![7u8; 10]);
    let e = read_capped(&p, 9, "a test file").unwrap_err();
    assert_eq!(e.to_string(), "is 10 B, over the 9 B limit for a test file");
    std::fs::remove_dir_all(&dir).unwrap();
}
