//! The output pass: each rendered frame converted from the framebuffer into its format's
//! pixels (8-bit sRGB, 16-bit sRGB RGBA with straight alpha, or linear RGBA premultiplied) and
//! written by a thread of its own, beside the next frame's render, under a temporary name that
//! is then renamed ([`write_atomically`](super::write_atomically)).
//!
//! Three pixel buffers circulate between the renderer and the writer through bounded
//! crossbeam channels, so after the first frames nothing is allocated and the renderer runs at
//! most two frames ahead of the disk.

use super::{FrameFormat, OutputError, write_exr_rgba_f32, write_png_rgb8, write_png_rgba16};
use crate::budget::MemoryPart;
use crate::raster::Framebuffer;
use crossbeam_channel::{Receiver, Sender};
use glam::Vec3;
use std::path::{Path, PathBuf};
use std::thread::JoinHandle;
use std::time::Instant;

/// Pixel buffers that circulate between the renderer and the writer.
const BUFFERS: usize = 3;

/// A converted frame, in the layout its format's writer takes.
enum Pixels {
    /// 8-bit sRGB RGB.
    Rgb8(Vec<u8>),
    /// 16-bit sRGB RGBA, straight alpha.
    Rgba16(Vec<u16>),
    /// Linear RGB premultiplied by alpha, and alpha.
    Premultiplied(Vec<Vec3>, Vec<f32>),
}

impl Pixels {
    fn empty(format: FrameFormat) -> Self {
        match format {
            FrameFormat::Png8 => Pixels::Rgb8(Vec::new()),
            FrameFormat::Png16 => Pixels::Rgba16(Vec::new()),
            FrameFormat::Exr => Pixels::Premultiplied(Vec::new(), Vec::new()),
        }
    }

    /// Fills the buffers from `fb`, drawn over `background`.
    fn convert(&mut self, fb: &Framebuffer, background: Vec3) {
        match self {
            Pixels::Rgb8(rgb) => fb.to_srgb8_into(rgb),
            Pixels::Rgba16(rgba) => fb.to_srgb16_rgba_into(background, rgba),
            Pixels::Premultiplied(rgb, alpha) => fb.premultiplied_into(background, rgb, alpha),
        }
    }

    fn write(&self, path: &Path, width: u32, height: u32) -> Result<(), OutputError> {
        match self {
            Pixels::Rgb8(rgb) => write_png_rgb8(path, width, height, rgb),
            Pixels::Rgba16(rgba) => write_png_rgba16(path, width, height, rgba),
            Pixels::Premultiplied(rgb, alpha) => {
                write_exr_rgba_f32(path, width, height, rgb, alpha)
            }
        }
    }
}

/// A rendered frame on its way to the writer thread.
struct Job {
    index: u32,
    width: u32,
    height: u32,
    pixels: Pixels,
}

/// The writer thread stopped (its error is returned by [`FrameWriter::finish`]).
#[derive(Debug, thiserror::Error)]
#[error("the frame writer stopped")]
pub struct WriterStopped;

/// Why an export's frames were not all written.
#[derive(Debug, thiserror::Error)]
pub enum FinishError {
    #[error(transparent)]
    Output(#[from] OutputError),
    #[error("the frame writer thread panicked")]
    Panicked,
}

/// Seconds the output took over a whole export.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OutputTimings {
    /// Converting framebuffers to the format's pixels, on the renderer's thread.
    pub convert_s: f64,
    /// Encoding and writing, on the writer thread (beside the next frame's render).
    pub write_s: f64,
}

/// Frames of one format written into one folder as `frame_NNNNN.EXT`.
pub struct FrameWriter {
    format: FrameFormat,
    jobs: Option<Sender<Job>>,
    spare: Receiver<Pixels>,
    thread: Option<JoinHandle<Result<f64, OutputError>>>,
    convert_s: f64,
}

impl FrameWriter {
    /// Starts the writer thread for frames of `format` in `dir` (which must exist).
    pub fn start(dir: PathBuf, format: FrameFormat) -> Self {
        let (to_writer, jobs) = crossbeam_channel::bounded::<Job>(BUFFERS - 1);
        let (to_renderer, spare) = crossbeam_channel::bounded::<Pixels>(BUFFERS);
        for _ in 0..BUFFERS {
            let _ = to_renderer.send(Pixels::empty(format));
        }
        let thread = std::thread::spawn(move || -> Result<f64, OutputError> {
            let mut write_s = 0.0;
            for job in jobs {
                let path = dir.join(format.file_name(job.index));
                let t0 = Instant::now();
                job.pixels.write(&path, job.width, job.height)?;
                write_s += t0.elapsed().as_secs_f64();
                let _ = to_renderer.send(job.pixels);
            }
            Ok(write_s)
        });
        Self {
            format,
            jobs: Some(to_writer),
            spare,
            thread: Some(thread),
            convert_s: 0.0,
        }
    }

    /// Converts `fb` (drawn over `background`) and hands it to the writer as frame `index`.
    pub fn write(
        &mut self,
        fb: &Framebuffer,
        background: Vec3,
        index: u32,
    ) -> Result<(), WriterStopped> {
        let t0 = Instant::now();
        let mut pixels = self
            .spare
            .recv()
            .unwrap_or_else(|_| Pixels::empty(self.format));
        pixels.convert(fb, background);
        self.convert_s += t0.elapsed().as_secs_f64();
        let job = Job {
            index,
            width: fb.width,
            height: fb.height,
            pixels,
        };
        match &self.jobs {
            Some(jobs) => jobs.send(job).map_err(|_| WriterStopped),
            None => Err(WriterStopped),
        }
    }

    /// Waits for the frames handed over to be written; the first write error, if any.
    pub fn finish(mut self) -> Result<OutputTimings, FinishError> {
        drop(self.jobs.take());
        let write_s = match self.thread.take().map(JoinHandle::join) {
            Some(Ok(result)) => result?,
            Some(Err(_)) => return Err(FinishError::Panicked),
            None => 0.0,
        };
        Ok(OutputTimings {
            convert_s: self.convert_s,
            write_s,
        })
    }

    /// The pixel buffers in flight and the encoder's copy of the one being written, counted at
    /// the widest format's 16 B a pixel (linear RGBA f32 for EXR; 8-bit PNG needs 3, 16-bit
    /// PNG 8).
    pub fn estimate(width: u32, height: u32) -> MemoryPart {
        let pixels = width as u64 * height as u64;
        MemoryPart {
            what: "frame export",
            product: format!("{} × {width}×{height} pixels × 16 B", BUFFERS + 1),
            bytes: (BUFFERS as u64 + 1) * 16 * pixels,
            set_by: "--width × --height",
        }
    }
}
