//! Measurements of the pipeline against independent references, shared by `wisp accuracy`,
//! `wisp bench` and the tests, so that ACCURACY.md, the benchmark and the asserted targets are
//! computed the same way. The engine does not import this module.
//!
//! - [`exact`]: the reference itself, ray shooting through explicit fibre cylinders (no grid,
//!   no statistics).
//! - [`exact_reference`], [`ensemble_light`]: the hairstyle's reference under the key light,
//!   and its mean over placements of each bundle's fibres.
//! - [`measure_map`]: the light map at several resolutions against that reference, per vertex
//!   and after shading ([`comparison`] for the figures, [`markdown()`] for the tables).
//! - [`placement_floor`]: the reference against itself with the fibres placed otherwise in
//!   each bundle: the error no estimate from the render strands can go below.
//! - [`skin::measure_skin`]: the hair's shadow on the skin against the same reference, per
//!   pixel.
//! - [`LevelTfReference`]: a quality level's map against the reference of the full hair.
//! - [`image::image_error`], [`image::flip_mean`]: one frame against a more accurate one
//!   (quality levels), over the hair's pixels and as ꟻLIP over the whole picture.

pub mod comparison;
pub mod exact;
pub mod image;
mod level_tf;
mod map_vs_reference;
mod markdown;
mod placement_floor;
mod reference;
pub mod skin;

pub use level_tf::LevelTfReference;
pub use map_vs_reference::{MapMeasurement, Row, measure_map, sweep_geometries};
pub use markdown::{bias_per_bin, markdown};
pub use placement_floor::placement_floor;
pub use reference::{
    DEFAULT_PLACEMENTS, default_rays, ensemble_light, exact_reference, exact_reference_placed,
    key_light, placements_used, single_fiber_variant,
};
