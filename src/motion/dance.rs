//! The project's own dance (placeholder until `animations/dance.glb` is generated).

use super::Motion;

pub(crate) fn default_dance() -> Motion {
    Motion::still(glam::Affine3A::IDENTITY)
}
