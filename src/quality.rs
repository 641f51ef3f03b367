//! Quality levels: how much work a frame gets, from a live window's to the most accurate the
//! engine does. What each level chooses for each pass is `crate::engine`'s (`quality.rs`);
//! their time and error are in BENCHMARKS.md.

use serde::{Deserialize, Serialize};

/// How much work a frame gets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quality {
    /// For a live window: fewer, thicker strands, a coarser simulation step and skin texture.
    Preview,
    /// For exported frames: the engine's defaults, shaded with light paths (a tenth of
    /// `Reference`'s) instead of dual scattering.
    #[default]
    Final,
    /// The most accurate the engine does: the light paths' shader with all its paths, finer
    /// steps and pieces.
    Reference,
}

impl Quality {
    /// Every level, fastest first.
    pub const ALL: [Quality; 3] = [Quality::Preview, Quality::Final, Quality::Reference];

    /// The level's name, as `--quality` and scene files spell it.
    pub fn name(self) -> &'static str {
        match self {
            Quality::Preview => "preview",
            Quality::Final => "final",
            Quality::Reference => "reference",
        }
    }

    /// The level named `name`, if there is one.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|q| q.name() == name)
    }

    /// The next level, slower and more accurate; after the last, the first (a key that
    /// cycles them).
    pub fn next(self) -> Self {
        match self {
            Quality::Preview => Quality::Final,
            Quality::Final => Quality::Reference,
            Quality::Reference => Quality::Preview,
        }
    }
}

impl std::fmt::Display for Quality {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::Quality;

    /// `Quality::ALL` lists the levels in declaration order, so `level as usize` indexes an
    /// array built from it (`wisp bench`'s level configurations).
    #[test]
    fn all_is_in_declaration_order() {
        for (i, q) in Quality::ALL.iter().enumerate() {
            assert_eq!(*q as usize, i, "{q}");
        }
    }
}
