//! `wisp fiber ...` (in progress, issue #3).
use super::AppError;

#[derive(clap::Args, Debug)]
pub struct FiberArgs {}

pub fn run(_args: FiberArgs) -> Result<(), AppError> {
    Err(AppError::other(anyhow::anyhow!(
        "wisp fiber: not built yet"
    )))
}
