use super::*;

#[test]
fn names_from_files_print_without_control_characters() {
    assert_eq!(printable("a\u{1b}[2Jb\n"), "a?[2Jb?");
    assert_eq!(printable("Tête"), "Tête");
}
