//! Text from outside (a name in a file, a path a user typed) made safe to print on a terminal.

/// `text` with every control character as `?`: an escape sequence in a file's name or in a
/// name inside a file could otherwise clear the screen or rewrite what was printed, and a
/// newline could forge a line of output.
pub fn printable(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::printable;

    /// ESC (U+001B), a newline and a C1 control (U+009B, CSI) each become one `?`; other
    /// characters, accented ones included, stay.
    #[test]
    fn control_characters_become_question_marks() {
        assert_eq!(printable("a\u{1b}[2Jb\n"), "a?[2Jb?");
        assert_eq!(printable("x\u{9b}31m"), "x?31m");
        assert_eq!(printable("Tête"), "Tête");
    }
}
