//! What the commands write to the terminal: `print!` and `println!` that stop quietly when the
//! reader of standard output has gone, and `eprint!` and `eprintln!` that print control
//! characters as `?`.
//!
//! The standard `print!` panics when standard output is a pipe its reader has closed (`wisp …
//! | head`: the reader had what it wanted); these end the process with exit code 141, as a
//! program killed by SIGPIPE. Every message on stderr (errors, warnings, progress) echoes
//! paths and names from outside, so each line goes through [`printable`] there: a file named
//! with an escape sequence cannot clear the screen. Declared with `#[macro_use]` first in
//! `cli`, these macros shadow the standard ones in every command.

/// `print!` that ends the process quietly (exit code 141) on a closed pipe.
macro_rules! print {
    ($($arg:tt)*) => {
        $crate::cli::terminal::write_stdout(format_args!($($arg)*))
    };
}

/// `println!` that ends the process quietly (exit code 141) on a closed pipe.
macro_rules! println {
    () => {
        print!("\n")
    };
    ($($arg:tt)*) => {
        $crate::cli::terminal::write_stdout(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// `eprint!` with control characters printed as `?` (newlines kept).
macro_rules! eprint {
    ($($arg:tt)*) => {
        $crate::cli::terminal::write_stderr(format_args!($($arg)*))
    };
}

/// `eprintln!` with control characters printed as `?`.
macro_rules! eprintln {
    () => {
        eprint!("\n")
    };
    ($($arg:tt)*) => {
        $crate::cli::terminal::write_stderr(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// Writes to standard output; a closed pipe ends the process with code 141, any other write
/// error with code 1 and a message.
pub fn write_stdout(args: std::fmt::Arguments) {
    use std::io::Write;
    if let Err(e) = std::io::stdout().lock().write_fmt(args) {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(141);
        }
        eprintln!("wisp: error: cannot write to standard output: {e}");
        std::process::exit(1);
    }
}

/// Writes to standard error, each line through [`printable`]. A failed write is ignored (there
/// is nowhere left to report it).
pub fn write_stderr(args: std::fmt::Arguments) {
    use std::io::Write;
    let _ = std::io::stderr()
        .lock()
        .write_all(terminal_lines(&args.to_string()).as_bytes());
}

/// `text` with its lines kept and every other control character as `?`.
fn terminal_lines(text: &str) -> String {
    text.split('\n')
        .map(printable)
        .collect::<Vec<_>>()
        .join("\n")
}

pub use wisp::input::printable;

#[cfg(test)]
mod tests;
