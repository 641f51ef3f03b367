//! Rest-pose generation (in progress).
use super::{GuideSet, Hairstyle, StrandLayout};

/// Builds guides in their rest pose and the render-strand layout of a validated hairstyle.
pub fn generate(_style: &Hairstyle) -> (GuideSet, StrandLayout) {
    unimplemented!("in progress")
}
