use super::*;

/// A path with ESC (U+001B) and a carriage return prints them as `?`; the line breaks between
/// messages stay.
#[test]
fn stderr_lines_keep_their_breaks_and_lose_control_characters() {
    assert_eq!(
        terminal_lines("wisp: error: a\u{1b}[2Jb\rc.json: bad\nnext\n"),
        "wisp: error: a?[2Jb?c.json: bad\nnext\n"
    );
    assert_eq!(terminal_lines("Tête"), "Tête");
}
