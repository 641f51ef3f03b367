//! Output: 8-bit sRGB PNG files written so that nothing half-written ever carries a frame's name.
//!
//! A frame is encoded to `<name>.png.tmp` in the same directory, flushed, then renamed over
//! `<name>.png` (rename is atomic within a directory on POSIX), so an interrupted export leaves
//! complete frames only.

mod png_file;

pub use png_file::{OutputError, linear_to_srgb8, write_png_rgb8};
