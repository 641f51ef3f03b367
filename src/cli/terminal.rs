//! What the commands write to the terminal: `print!` and `println!` that stop quietly when the
//! reader of standard output has gone, and names from input files made safe to print.
//!
//! The standard `print!` panics when standard output is a pipe its reader has closed (`wisp …
//! | head`: the reader had what it wanted); these end the process with exit code 141, as a
//! program killed by SIGPIPE. Declared with `#[macro_use]` first in `cli`, they shadow the
//! standard macros in every command.

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

/// A name from an input file (hairstyle, clip, joint) safe to print on a terminal: control
/// characters (an escape sequence could clear the screen) become `?`.
pub fn printable(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect()
}

#[cfg(test)]
mod tests;
