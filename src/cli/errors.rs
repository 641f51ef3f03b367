//! The error a command returns: what went wrong, with the exit code it ends the process with
//! (2 for bad input, 1 for any other failure). `cli::main` prints it as `wisp: error: …`.

/// An error with its exit code: 2 for bad input, 1 otherwise.
#[derive(Debug)]
pub struct AppError {
    pub code: u8,
    pub error: anyhow::Error,
}

impl AppError {
    /// Bad input (flags, files, output paths, a run over its budget): exit code 2.
    pub fn input(error: impl Into<anyhow::Error>) -> Self {
        Self {
            code: 2,
            error: error.into(),
        }
    }

    /// Any other failure: exit code 1.
    pub fn other(error: impl Into<anyhow::Error>) -> Self {
        Self {
            code: 1,
            error: error.into(),
        }
    }
}
