//! Output: 8-bit sRGB PNG frames and linear RGBA OpenEXR images, written so that nothing
//! half-written ever carries a file's name.
//!
//! A file is encoded to `<name>.tmp` in the same directory, flushed and synced, then renamed
//! over `<name>` (rename is atomic within a directory on POSIX), so an interrupted export
//! leaves complete files only ([`write_atomically`]).

mod exr_file;
mod png_file;

pub use exr_file::{read_exr_rgba_f32, write_exr_rgba_f32};
pub use png_file::{OutputError, linear_to_srgb8, write_atomically, write_png_rgb8};
