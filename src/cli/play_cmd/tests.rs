use super::*;

#[test]
fn screenshot_names_never_clobber() {
    let dir = Path::new("shots");
    assert_eq!(
        free_shot_path(dir, |_| false),
        Some(dir.join("wisp-shot-0001.png"))
    );
    // Taken names are skipped, including a gap's later neighbours.
    let taken = |p: &Path| {
        [
            "wisp-shot-0001.png",
            "wisp-shot-0002.png",
            "wisp-shot-0004.png",
        ]
        .iter()
        .any(|n| p.ends_with(n))
    };
    assert_eq!(
        free_shot_path(dir, taken),
        Some(dir.join("wisp-shot-0003.png"))
    );
    assert_eq!(free_shot_path(dir, |_| true), None);
}
