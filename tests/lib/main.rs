//! The library tests: everything that calls `wisp` in process, one module per area, in one
//! binary (one link instead of one per file). Run an area with its module path as the filter:
//! `cargo test --release --test lib -- map_slab::`.
//!
//! The slow accuracy and simulation tests run at a reduced size unless `WISP_FULL_TESTS=1`
//! is set ([`support::full_size`]); each says its full size in its doc comment.
//!
//! The tests that run the `wisp` binary are in `tests/cli/`.

// Helpers.
mod alloc;
mod bounded;
mod common;
mod sim_common;
#[path = "../support/mod.rs"]
mod support;

// Areas.
mod cache;
mod character;
mod dance_clip;
mod export;
mod fiber_chiang;
mod fiber_energy;
mod fiber_hard_cases;
mod fiber_shading;
mod fiber_tables;
mod framing;
mod groom_formats;
mod groom_import;
mod groom_on_bones;
mod groom_partial;
mod groom_sparse;
mod hairstyle;
mod hostile_budget;
mod hostile_cases;
mod hostile_headers;
mod hostile_loaders;
mod hostile_resume;
mod hostile_scene;
mod level_tf;
mod light_path_rate;
mod map_accuracy;
mod map_contact;
mod map_exact;
mod map_hard_cases;
mod map_modulo;
mod map_reference;
mod map_slab;
mod map_surface;
mod motion;
mod quality;
mod raster_bundle;
mod raster_coverage;
mod raster_lines;
mod raster_seen;
mod render;
mod render_options;
mod rigs;
mod scenes;
mod segment_pieces;
mod shade_bend;
mod sim_alloc;
mod sim_dance;
mod sim_rest;
mod sim_still_frames;
mod usd_curves;
