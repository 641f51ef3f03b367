//! Output: the export's pass ([`FrameWriter`]) and its files: 8-bit sRGB PNG, 16-bit sRGB
//! RGBA PNG and linear RGBA OpenEXR frames, written so that nothing half-written ever carries a
//! file's name, and checked whole before a resumed export keeps them ([`check_frame`]).
//!
//! A file is encoded to `<name>.tmp` in the same directory, flushed and synced, then renamed
//! over `<name>` (rename is atomic within a directory on POSIX), so an interrupted export
//! leaves complete files only (`atomic.rs`, [`write_atomically`]).

mod atomic;
mod exr_file;
mod frames;
mod png_file;
mod writer;

pub use atomic::{OutputError, write_atomically};
pub use exr_file::{read_exr_rgba_f32, write_exr_rgba_f32};
pub use frames::{FrameDefect, FrameFormat, check_frame};
pub use png_file::{write_png_rgb8, write_png_rgba16};
pub use writer::{FinishError, FrameWriter, OutputTimings, WriterStopped};

/// The sRGB encodings the frame writers expect, offered beside them.
pub use crate::color::{linear_to_srgb8, linear_to_srgb16};
