//! Tests of the line raster's working buffers.

use glam::Vec3;

use super::*;
use crate::raster::camera::Camera;
use crate::raster::lines::draw::draw_polylines;
use crate::raster::lines::polyline::LineStyle;
use crate::raster::lines::seen::{draw_seen_polylines, seen_points};

/// After a warm-up frame (a whole draw, the seen points, the draw of the kept fragments),
/// drawing the same scene again allocates nothing, whichever thread draws which band.
#[test]
fn warmed_up_scratch_does_not_grow() {
    // Two threads, so bands move between the per-thread buffers from frame to frame.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    pool.install(|| {
        let cam = Camera::look_at(Vec3::new(0.0, 0.0, 2.0), Vec3::ZERO, Vec3::Y, 0.9, 160, 120);
        let pts: Vec<Vec3> = (0..400)
            .map(|i| {
                let a = i as f32 * 0.37;
                Vec3::new(a.sin(), (i % 20) as f32 * 0.05 - 0.5, a.cos()) * 0.5
            })
            .collect();
        let cols = vec![Vec3::ONE; pts.len()];
        let lines = Polylines {
            points: &pts,
            colors: &cols,
            widths_m: &[],
            points_per_line: 20,
            bundle: None,
        };
        let mut fb = Framebuffer::new(160, 120, Vec3::ZERO);
        let mut scratch = LineScratch::default();
        let style = LineStyle::default();
        // A frame as the engine draws it: the seen points, then the kept fragments.
        let mut seen = Vec::new();
        let mut frame = |scratch: &mut LineScratch| {
            draw_polylines(&mut fb, &cam, &lines, &style, scratch);
            seen_points(&fb, &cam, &lines, &style, scratch, &mut seen);
            draw_seen_polylines(&mut fb, &cam, &lines, &style, scratch);
        };
        frame(&mut scratch);
        let warm = scratch.capacity_bytes();
        assert!(warm > 0);
        // Many frames: the per-thread buffers must not outgrow each other frame after frame.
        for _ in 0..40 {
            frame(&mut scratch);
            assert_eq!(scratch.capacity_bytes(), warm);
        }
    });
}
