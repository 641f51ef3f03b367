//! Opaque triangle meshes (a character's body): depth-tested, anti-aliased, shaded once per
//! pixel by a caller's closure.
//!
//! What: [`draw_mesh`] draws every triangle nearer than what the depth buffer holds, shades
//! each covered pixel once (`shade(world position, unit normal, albedo)`) and anti-aliases the
//! silhouette; it writes depth where the mesh covers at least half of a pixel, so hair behind
//! the body is hidden and hair in front is drawn over it.
//!
//! How, per frame:
//! 1. **Set-up** (`setup`, serial, in input order): triangles to view space, clipped to the
//!    near plane, projected, back faces of single-sided surfaces culled, and binned into
//!    16-row bands.
//! 2. **Visibility** (`visibility`, parallel over bands): four samples per pixel keep the
//!    nearest triangle and its depth. Samples start at the framebuffer's depth, so solids
//!    drawn before (the head ellipsoid) hide what is behind them.
//! 3. **Shading** (`shading`, the same band task): a covered pixel is shaded once per layer
//!    its samples see (one surface at one depth: once inside a surface, once for each side of
//!    an edge where one part of the body passes in front of another or two materials meet),
//!    the layers averaged by their samples, and blended by its covered fraction.
//!
//! Deterministic for any thread count: a band is drawn by one task, its triangles in input
//! order, with strict depth tests (the first triangle wins a tie).
//!
//! Why this design: shading dominates (each pixel of skin reads the light map, about 100 ns),
//! so visibility first and one shade per pixel and layer costs the least; multisampling only
//! the visibility buys anti-aliased silhouettes, inner edges included, for four depth tests
//! per pixel and a second shade on the few pixels along those edges. Rejected: shading
//! in the raster loop (overdraw shades hidden pixels: a body has 2–3 layers where arms cross
//! it) and per-vertex (Gouraud) lighting, which blurs hair shadows over the 2–5 cm between a
//! low-poly mesh's vertices.

mod model;
mod screen_tri;
mod setup;
mod shading;
mod texture;
mod visibility;

pub use model::{Mesh, Surface};
pub use texture::Texture;

use glam::Vec3;
use rayon::prelude::*;

use crate::raster::camera::Camera;
use crate::raster::framebuffer::Framebuffer;
use screen_tri::{ScreenTri, screen_box};
use setup::{BAND_ROWS, set_up};
use shading::{Pixels, Samples, shade_band};
use visibility::{Band, NONE, SAMPLES};

/// Buffers reused across frames (allocation-free once sized).
#[derive(Debug, Default)]
pub struct MeshScratch {
    tris: Vec<ScreenTri>,
    bins: Vec<Vec<u32>>,
    sample_depth: Vec<f32>,
    sample_tri: Vec<u32>,
}

impl MeshScratch {
    /// Bytes held for an image of `width` × `height` and `triangles` triangles (each may be
    /// clipped into two and binned into a few bands).
    pub fn estimated_bytes(width: u32, height: u32, triangles: u64) -> u64 {
        let samples = width as u64 * height as u64 * SAMPLES as u64;
        samples * (size_of::<f32>() + size_of::<u32>()) as u64
            + triangles * (2 * size_of::<ScreenTri>() as u64 + 4 * size_of::<u32>() as u64)
    }
}

/// Draws `mesh` (see the module doc). `shade(position, normal, albedo)` gives a pixel's linear
/// RGB colour; it is called once per covered pixel, from several threads. Inconsistent input
/// (index out of range, lists of different lengths, non-finite vertices) draws the triangles
/// it concerns as nothing, never panics. As for lines, the framebuffer's size overrides the
/// camera's.
pub fn draw_mesh(
    fb: &mut Framebuffer,
    cam: &Camera,
    mesh: &Mesh,
    shade: impl Fn(Vec3, Vec3, Vec3) -> Vec3 + Sync,
    scratch: &mut MeshScratch,
) {
    let (w, h) = (fb.width as usize, fb.height as usize);
    if w == 0 || h == 0 || !fb.is_consistent() {
        return;
    }
    let Some(view) = cam.view_for(fb.width, fb.height) else {
        return;
    };
    set_up(&view, mesh, &mut scratch.tris, &mut scratch.bins);
    let bands = h.div_ceil(BAND_ROWS);
    let n = w * h * SAMPLES;
    scratch.sample_depth.resize(n, f32::INFINITY);
    scratch.sample_tri.resize(n, NONE);
    let tris = &scratch.tris;
    let bins = &scratch.bins;
    let rows = BAND_ROWS * w;
    let inv_focal_px = 1.0 / view.focal_px;
    fb.color
        .par_chunks_mut(rows)
        .zip(fb.depth.par_chunks_mut(rows))
        .zip(fb.coverage.par_chunks_mut(rows))
        .zip(scratch.sample_depth.par_chunks_mut(rows * SAMPLES))
        .zip(scratch.sample_tri.par_chunks_mut(rows * SAMPLES))
        .enumerate()
        .take(bands)
        // One job per band: the character's bands cost unevenly, and rayon splits a range
        // only about log2(threads) deep unless a part is stolen.
        .with_max_len(1)
        .for_each(|(b, ((((color, depth), coverage), s_depth), s_tri))| {
            let band = Band {
                y0: b * BAND_ROWS,
                rows: depth.len() / w,
                w,
                span: (0, w),
            };
            if bins[b].is_empty() {
                return;
            }
            // Only the columns the band's triangles can touch (the union of their boxes) are
            // set up and shaded: the rest of the band keeps what is there, as it would with
            // every sample missed (the character fills about a third of a frame's width).
            let span = bins[b]
                .iter()
                .map(|&t| band.columns(screen_box(&tris[t as usize])))
                .fold((w, 0), |(lo, hi), (x0, x1)| (lo.min(x0), hi.max(x1)));
            let band = Band { span, ..band };
            // Samples start at the opaque depth already there.
            for row in 0..band.rows {
                for px in row * w + span.0..row * w + span.1 {
                    s_depth[px * SAMPLES..(px + 1) * SAMPLES].fill(depth[px]);
                    s_tri[px * SAMPLES..(px + 1) * SAMPLES].fill(NONE);
                }
            }
            for &t in &bins[b] {
                band.rasterise(&tris[t as usize], t, s_depth, s_tri);
            }
            let samples = Samples {
                depth: s_depth,
                tri: s_tri,
            };
            let px = Pixels {
                color,
                depth,
                coverage,
            };
            shade_band(&band, tris, mesh, &shade, samples, (px, inv_focal_px));
        });
}

#[cfg(test)]
mod tests;
