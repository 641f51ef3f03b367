use super::*;

#[test]
fn frame_names_are_recognised_exactly() {
    let name = |index, extension, temporary| {
        Some(FrameName {
            index,
            extension,
            temporary,
        })
    };
    assert_eq!(frame_name("frame_00012.png"), name(12, "png", false));
    assert_eq!(frame_name("frame_00012.png.tmp"), name(12, "png", true));
    assert_eq!(frame_name("frame_00012.exr"), name(12, "exr", false));
    assert_eq!(frame_name("frame_00012.exr.tmp"), name(12, "exr", true));
    assert_eq!(frame_name("frame_123456.png"), name(123_456, "png", false));
    assert_eq!(frame_name("frame_0012.png"), None);
    assert_eq!(frame_name("frame_00012.PNG"), None);
    assert_eq!(frame_name("frame_00012.jpg"), None);
    assert_eq!(frame_name("frame_00012.png.bak"), None);
    assert_eq!(frame_name("frame_00012.tmp"), None);
    assert_eq!(frame_name("my_frame_00012.png"), None);
    assert_eq!(frame_name("frame_000a2.png"), None);
}

/// A whole run removes stale frames of its own format and every temporary file, and
/// leaves the other format's frames and other files alone.
#[test]
fn tidying_keeps_other_formats() {
    let dir = std::env::temp_dir().join(format!("wisp-tidy-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let names = [
        "frame_00000.exr",
        "frame_00003.exr",
        "frame_00000.png",
        "frame_00003.png",
        "frame_00001.png.tmp",
        "frame_00007.exr.tmp",
        "notes.txt",
    ];
    for n in names {
        std::fs::write(dir.join(n), b"x").unwrap();
    }
    prepare_output_dir(&dir, &Tidy::whole_run(2), FrameFormat::Exr, true).unwrap();
    let mut left: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    left.sort();
    assert_eq!(
        left,
        [
            "frame_00000.exr",
            "frame_00000.png",
            "frame_00003.png",
            "notes.txt"
        ]
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
