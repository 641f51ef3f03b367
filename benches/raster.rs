//! Raster benchmarks: `cargo bench --bench raster`.
//!
//! - `draw_polylines/100k_segments/threads=N`: 2,000 curly strands x 51 points (100,000
//!   segments), 1-px lines at opacity 0.8, around and behind an opaque head ellipsoid framed at
//!   1280x720, in a rayon pool of N threads. The framebuffer is not cleared between iterations
//!   (the work does not depend on the colours already there), so only the line drawing is timed.
//! - `draw_ellipsoid/head_1280x720/threads=N`: the shaded head alone (includes a frame clear,
//!   timed alone as `draw_ellipsoid/clear_1280x720`).
//! - `framebuffer/to_argb_u32_1280x720`: linear -> sRGB conversion of a rendered frame.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use glam::{Affine3A, Vec3};
use wisp::raster::{
    Camera, Framebuffer, LineScratch, LineStyle, LineWidth, Polylines, draw_ellipsoid,
    draw_polylines,
};

const W: u32 = 1280;
const H: u32 = 720;
const STRANDS: usize = 2000;
const POINTS: usize = 51;

struct Rng(u64);
impl Rng {
    fn next_f32(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        ((self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 40) as f32) / (1u64 << 24) as f32
    }
}

/// Curly strands, 30 cm long, falling from the upper half of a 10 cm head.
fn hair(strands: usize, n: usize) -> (Vec<Vec3>, Vec<Vec3>) {
    let r = 0.1;
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    let (mut pts, mut cols) = (
        Vec::with_capacity(strands * n),
        Vec::with_capacity(strands * n),
    );
    for _ in 0..strands {
        let phi = rng.next_f32() * std::f32::consts::TAU;
        let cos_t = rng.next_f32();
        let sin_t = (1.0 - cos_t * cos_t).sqrt();
        let normal = Vec3::new(sin_t * phi.cos(), cos_t, sin_t * phi.sin());
        let (mut p, mut dir) = (normal * r, normal);
        let seg = 0.3 / n as f32;
        let tint = Vec3::new(
            0.3 + 0.5 * rng.next_f32(),
            0.15 + 0.2 * rng.next_f32(),
            0.05,
        );
        let phase = rng.next_f32() * std::f32::consts::TAU;
        for i in 0..n {
            pts.push(p);
            let u = i as f32 / (n - 1) as f32;
            cols.push(tint * (0.3 + 0.7 * u));
            dir = (dir + Vec3::new(0.0, -0.25, 0.0)).normalize();
            let curl = Vec3::new((phase + u * 25.0).sin(), 0.0, (phase + u * 25.0).cos()) * 0.6;
            p += (dir + curl).normalize() * seg;
            if p.length() < r * 1.03 {
                p = p.normalize() * r * 1.03;
            }
        }
    }
    (pts, cols)
}

fn head() -> Affine3A {
    Affine3A::from_scale(Vec3::new(0.09, 0.11, 0.1))
}

fn shade(_p: Vec3, n: Vec3) -> Vec3 {
    let light = Vec3::new(0.5, 0.8, 0.6).normalize();
    Vec3::new(0.85, 0.62, 0.5) * (0.15 + 0.85 * n.dot(light).max(0.0))
}

fn camera() -> Camera {
    Camera::framing(
        Vec3::new(0.0, -0.1, 0.0),
        0.25,
        Vec3::new(0.3, 0.1, 1.0),
        0.6,
        W,
        H,
    )
}

fn bench_raster(c: &mut Criterion) {
    let (pts, cols) = hair(STRANDS, POINTS);
    let lines = Polylines {
        points: &pts,
        colors: &cols,
        widths_m: &[],
        points_per_line: POINTS,
        bundle: None,
    };
    assert_eq!(lines.segment_count(), 100_000);
    let cam = camera();
    let style = LineStyle {
        width: LineWidth::Pixels(1.0),
        opacity: 0.8,
    };

    let mut group = c.benchmark_group("draw_polylines");
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool");
        let mut fb = Framebuffer::new(W, H, Vec3::splat(0.02));
        draw_ellipsoid(&mut fb, &cam, head(), shade);
        let mut scratch = LineScratch::default();
        group.bench_function(format!("100k_segments/threads={threads}"), |b| {
            b.iter(|| {
                pool.install(|| {
                    draw_polylines(&mut fb, &cam, black_box(&lines), &style, &mut scratch)
                })
            })
        });
    }
    group.finish();

    let mut group = c.benchmark_group("draw_ellipsoid");
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool");
        let mut fb = Framebuffer::new(W, H, Vec3::splat(0.02));
        group.bench_function(format!("head_1280x720/threads={threads}"), |b| {
            b.iter(|| {
                // Reset depth only inside the head's box would be cheaper; a full clear is
                // timed separately below so it can be subtracted.
                fb.clear(Vec3::splat(0.02));
                pool.install(|| draw_ellipsoid(&mut fb, &cam, black_box(head()), shade))
            })
        });
    }
    let mut fb = Framebuffer::new(W, H, Vec3::splat(0.02));
    group.bench_function("clear_1280x720", |b| {
        b.iter(|| fb.clear(black_box(Vec3::splat(0.02))))
    });
    group.finish();

    // Conversion for the window / PNG, on the rendered scene (hair, head and background).
    let mut fb = Framebuffer::new(W, H, Vec3::splat(0.02));
    draw_ellipsoid(&mut fb, &cam, head(), shade);
    draw_polylines(&mut fb, &cam, &lines, &style, &mut LineScratch::default());
    let mut group = c.benchmark_group("framebuffer");
    let mut argb = Vec::new();
    group.bench_function("to_argb_u32_1280x720", |b| {
        b.iter(|| black_box(&fb).to_argb_u32_into(&mut argb))
    });
    group.finish();
}

criterion_group!(benches, bench_raster);
criterion_main!(benches);
