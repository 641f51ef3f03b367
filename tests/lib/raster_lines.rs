//! Integration tests of `wisp::raster`: coverage integrals, occlusion by the head, hair order,
//! determinism across thread counts, degenerate input, and a look-at-it scene PNG.

use crate::common::{axis_camera, unproject};
use glam::{Affine3A, Vec3};
use wisp::raster::{
    Camera, Framebuffer, LineScratch, LineStyle, LineWidth, Polylines, draw_ellipsoid,
    draw_polylines,
};

fn draw(
    fb: &mut Framebuffer,
    cam: &Camera,
    pts: &[Vec3],
    cols: &[Vec3],
    n: usize,
    style: LineStyle,
) {
    let lines = Polylines {
        points: pts,
        colors: cols,
        widths_m: &[],
        points_per_line: n,
        bundle: None,
    };
    draw_polylines(fb, cam, &lines, &style, &mut LineScratch::default());
}

fn coverage_sum(fb: &Framebuffer) -> f64 {
    fb.color.iter().map(|c| f64::from(c.x)).sum()
}

/// Coverage of a horizontal 7-point polyline from x = 20.3 to 171.9 at height `y`.
fn horizontal_coverage(cam: &Camera, width: f32, y: f32, opacity: f32) -> f64 {
    let (xa, xb) = (20.3_f32, 171.9_f32);
    let n = 7;
    let pts: Vec<Vec3> = (0..n)
        .map(|i| {
            let x = xa + (xb - xa) * i as f32 / (n - 1) as f32;
            unproject(cam, x, y, 1.5)
        })
        .collect();
    let cols = vec![Vec3::ONE; n];
    let mut fb = Framebuffer::new(200, 100, Vec3::ZERO);
    let style = LineStyle {
        width: LineWidth::Pixels(width),
        opacity,
    };
    draw(&mut fb, cam, &pts, &cols, n, style);
    coverage_sum(&fb)
}

/// A line covers length × width, as the pixels' 16 sub-samples count it. A horizontal strip
/// w px wide holds ⌊16w⌋ or ⌈16w⌉ of the 16 sub-sample heights of each pixel column it
/// crosses (they are the sixteenths, n-rooks), so one line is within (length + 2)/16 of
/// length × width (one sixteenth per column, plus the ends). Averaged over 64 heights one
/// sixteenth apart / 64 (the sub-sample lattice's period in 64 steps) the count is exact to
/// 2/64 sub-samples per column: within (length + 2)/512. The polyline has joints, which
/// the half-open partition along the line must not double count. Opacity scales the
/// coverage linearly on black.
#[test]
fn horizontal_line_coverage_is_length_times_width() {
    let cam = axis_camera(200, 100);
    let length = 171.9 - 20.3;
    for (width, y) in [
        (1.0_f32, 40.3_f32),
        (1.0, 40.5),
        (2.0, 61.77),
        (0.5, 20.1),
        (3.3, 50.0),
        (0.13, 30.2),
    ] {
        let expected = f64::from(length * width);
        let steps = 64;
        let mut mean = 0.0;
        for k in 0..steps {
            let yk = y + k as f32 / (16.0 * steps as f32);
            let got = horizontal_coverage(&cam, width, yk, 1.0);
            assert!(
                (got - expected).abs() <= f64::from(length + 2.0) / 16.0,
                "w {width} at y {yk}: {got} vs {expected}"
            );
            if k % 16 == 0 {
                let quarter = horizontal_coverage(&cam, width, yk, 0.25);
                assert!(
                    (quarter - 0.25 * got).abs() < 1e-4 * got,
                    "{quarter} vs {got}"
                );
            }
            mean += got / f64::from(steps);
        }
        assert!(
            (mean - expected).abs() <= f64::from(length + 2.0) / 512.0 + 1e-4 * expected,
            "w {width}: mean {mean} vs {expected}"
        );
    }
}

/// Diagonal lines: the grid sum approximates the integral; 2% covers the sampling error.
#[test]
fn diagonal_line_coverage_is_close_to_length_times_width() {
    let cam = axis_camera(160, 160);
    for (a, b) in [
        ((10.2, 15.7), (140.1, 120.3)),
        ((80.0, 5.5), (70.3, 150.9)),
        ((5.0, 100.0), (150.0, 99.0)),
    ] {
        let pts = [
            unproject(&cam, a.0, a.1, 2.0),
            unproject(&cam, b.0, b.1, 2.0),
        ];
        let mut fb = Framebuffer::new(160, 160, Vec3::ZERO);
        draw(
            &mut fb,
            &cam,
            &pts,
            &[Vec3::ONE; 2],
            2,
            LineStyle::default(),
        );
        let len = f64::from((b.0 - a.0).hypot(b.1 - a.1));
        let got = coverage_sum(&fb);
        assert!((got - len).abs() < 0.02 * len, "{got} vs {len}");
        assert!(fb.color.iter().all(|c| c.x <= 1.0 + 1e-6));
    }
}

#[test]
fn color_is_interpolated_along_the_segment() {
    let cam = axis_camera(101, 11);
    let pts = [
        unproject(&cam, 0.5, 5.5, 1.0),
        unproject(&cam, 100.5, 5.5, 1.0),
    ];
    let cols = [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0)];
    let mut fb = Framebuffer::new(101, 11, Vec3::ZERO);
    draw(&mut fb, &cam, &pts, &cols, 2, LineStyle::default());
    let mid = fb.pixel(50, 5).unwrap();
    assert!((mid - Vec3::new(0.5, 0.0, 0.5)).length() < 1e-3, "{mid}");
    let q = fb.pixel(25, 5).unwrap();
    assert!((q - Vec3::new(0.75, 0.0, 0.25)).length() < 1e-3, "{q}");
}

/// Head of radius 0.3 m at 2 m. A line through the image centre at 3 m is hidden where the
/// head is and visible beside it; the same line at 1 m is visible across the head.
#[test]
fn head_hides_lines_behind_it() {
    let (w, h) = (120, 80);
    let cam = axis_camera(w, h);
    let head = Affine3A::from_scale_rotation_translation(
        Vec3::splat(0.3),
        glam::Quat::IDENTITY,
        Vec3::new(0.0, 0.0, -2.0),
    );
    let skin = Vec3::new(0.8, 0.6, 0.5);
    let mut head_only = Framebuffer::new(w, h, Vec3::ZERO);
    draw_ellipsoid(&mut head_only, &cam, head, |_, _| skin);
    let red = Vec3::new(1.0, 0.0, 0.0);
    for (depth, in_front) in [(3.0, false), (1.0, true)] {
        let pts = [
            unproject(&cam, 0.0, 40.5, depth),
            unproject(&cam, 120.0, 40.5, depth),
        ];
        let mut fb = head_only.clone();
        draw(&mut fb, &cam, &pts, &[red; 2], 2, LineStyle::default());
        let centre = fb.pixel(60, 40).unwrap();
        if in_front {
            assert_eq!(centre, red);
        } else {
            assert_eq!(centre, skin);
        }
        // Beside the head (silhouette radius ≈ 6.3 px around x = 60) the line always shows.
        assert_eq!(fb.pixel(5, 40).unwrap(), red);
        // Depth is not written by lines.
        assert_eq!(fb.depth, head_only.depth);
    }
}

/// Draws one red and one blue opaque 1 px segment on a 64² `axis_camera`, in both input orders
/// (red first, then blue first); returns the two frames.
fn red_and_blue_in_both_orders(cam: &Camera, red: [Vec3; 2], blue: [Vec3; 2]) -> [Framebuffer; 2] {
    let (r, b) = (Vec3::X, Vec3::Z);
    let orders = [
        ([red[0], red[1], blue[0], blue[1]], [r, r, b, b]),
        ([blue[0], blue[1], red[0], red[1]], [b, b, r, r]),
    ];
    orders.map(|(pts, cols)| {
        let mut fb = Framebuffer::new(64, 64, Vec3::ZERO);
        draw(&mut fb, cam, &pts, &cols, 2, LineStyle::default());
        fb
    })
}

/// Two opaque lines crossing at the image centre: the nearer one is on top whatever the
/// input order.
#[test]
fn nearer_hair_is_on_top_in_any_order() {
    let cam = axis_camera(64, 64);
    let near = [
        unproject(&cam, 0.0, 32.5, 1.0),
        unproject(&cam, 64.0, 32.5, 1.0),
    ];
    let far = [
        unproject(&cam, 32.5, 0.0, 2.0),
        unproject(&cam, 32.5, 64.0, 2.0),
    ];
    for (k, fb) in red_and_blue_in_both_orders(&cam, near, far)
        .iter()
        .enumerate()
    {
        assert_eq!(fb.pixel(32, 32).unwrap(), Vec3::X, "order {k}");
    }
}

/// Fibres side by side hide what is behind them as their summed width does. Sixteen white
/// lines a quarter pixel wide, a quarter pixel apart, tile the rows 40..44 in front of a red
/// line 8 px wide: every sub-sample of those rows lies in a white strip (neighbouring strips
/// share their edges), so no red shows there. Composited as independent layers, each pixel
/// would let (3/4)⁴ ≈ 0.32 of the red through its four quarter-pixel lines.
#[test]
fn fibers_side_by_side_hide_what_is_behind_them() {
    let cam = axis_camera(64, 64);
    let (xa, xb) = (4.0, 60.0);
    let mut pts = Vec::new();
    let mut cols = Vec::new();
    for i in 0..16 {
        let y = 40.0 + 0.25 * (i as f32 + 0.5);
        pts.extend([unproject(&cam, xa, y, 1.0), unproject(&cam, xb, y, 1.0)]);
        cols.extend([Vec3::ONE; 2]);
    }
    // The red line behind, 8 px wide, drawn first in a call of its own.
    let red = [
        unproject(&cam, xa, 42.0, 2.0),
        unproject(&cam, xb, 42.0, 2.0),
    ];
    let mut fb = Framebuffer::new(64, 64, Vec3::ZERO);
    draw(
        &mut fb,
        &cam,
        &red,
        &[Vec3::X; 2],
        2,
        LineStyle::pixels(8.0, 1.0),
    );
    assert_eq!(fb.pixel(32, 42).unwrap(), Vec3::X);
    draw(&mut fb, &cam, &pts, &cols, 2, LineStyle::pixels(0.25, 1.0));
    for x in 8..56 {
        for y in 40..44 {
            let px = fb.pixel(x, y).unwrap();
            // White: green and blue as high as red (independent layers: green 0.68).
            assert!(
                (px - Vec3::ONE).abs().max_element() < 1e-5,
                "pixel ({x}, {y}): {px}"
            );
        }
    }
    // Rows just outside the tiled band still show the red.
    assert!(fb.pixel(32, 39).unwrap().y < 0.5 && fb.pixel(32, 39).unwrap().x > 0.99);
}

/// Two opaque lines on the same pixels whose depths cross halfway (one runs near to far, the
/// other far to near, so their mid-points are equally deep): each pixel shows the one nearer
/// *there*, in either input order. Sorting whole segments by mid-point depth, as the raster
/// did before per-pixel order, put one line on top along its whole length.
#[test]
fn lines_crossing_in_depth_are_ordered_per_pixel() {
    let cam = axis_camera(64, 64);
    let a = [
        unproject(&cam, 2.0, 32.5, 1.0),
        unproject(&cam, 62.0, 32.5, 3.0),
    ];
    let b = [
        unproject(&cam, 2.0, 32.5, 3.0),
        unproject(&cam, 62.0, 32.5, 1.0),
    ];
    for (k, fb) in red_and_blue_in_both_orders(&cam, a, b).iter().enumerate() {
        // a's depth along the row: 1/z is linear on screen, from 1 to 1/3; b's from 1/3 to 1.
        // They are equally deep at x = 32; a (red) is nearer left of it, b (blue) right of it.
        for x in [4, 16, 28] {
            assert_eq!(fb.pixel(x, 32).unwrap(), Vec3::X, "order {k}, x {x}");
        }
        for x in [36, 48, 60] {
            assert_eq!(fb.pixel(x, 32).unwrap(), Vec3::Z, "order {k}, x {x}");
        }
    }
}

/// Small deterministic generator (xorshift64*), so the tests need no extra crate.
struct Rng(u64);
impl Rng {
    fn next_f32(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        ((self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 40) as f32) / (1u64 << 24) as f32
    }
}

/// Curly strands falling from the upper half of a sphere of radius `r` at the origin.
fn hair_scene(strands: usize, n: usize, r: f32) -> (Vec<Vec3>, Vec<Vec3>) {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let (mut pts, mut cols) = (Vec::new(), Vec::new());
    for _ in 0..strands {
        let phi = rng.next_f32() * std::f32::consts::TAU;
        let cos_t = rng.next_f32();
        let sin_t = (1.0 - cos_t * cos_t).sqrt();
        let normal = Vec3::new(sin_t * phi.cos(), cos_t, sin_t * phi.sin());
        let mut p = normal * r;
        let mut dir = normal;
        let seg = 2.5 * r / n as f32;
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

fn render_scene(threads: usize, w: u32, h: u32) -> Framebuffer {
    let (pts, cols) = hair_scene(600, 40, 0.1);
    let cam = Camera::framing(
        Vec3::new(0.0, -0.06, 0.0),
        0.19,
        Vec3::new(0.3, 0.1, 1.0),
        0.6,
        w,
        h,
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut fb = Framebuffer::new(w, h, Vec3::new(0.02, 0.02, 0.03));
        let light = Vec3::new(0.5, 0.8, 0.6).normalize();
        draw_ellipsoid(
            &mut fb,
            &cam,
            Affine3A::from_scale(Vec3::new(0.09, 0.11, 0.1)),
            |_, n| Vec3::new(0.85, 0.62, 0.5) * (0.15 + 0.85 * n.dot(light).max(0.0)),
        );
        let lines = Polylines {
            points: &pts,
            colors: &cols,
            widths_m: &[],
            points_per_line: 40,
            bundle: None,
        };
        let style = LineStyle {
            width: LineWidth::Pixels(1.0),
            opacity: 0.8,
        };
        draw_polylines(&mut fb, &cam, &lines, &style, &mut LineScratch::default());
        fb
    })
}

#[test]
fn identical_bits_for_one_and_two_threads() {
    let a = render_scene(1, 320, 240);
    let b = render_scene(2, 320, 240);
    let c = render_scene(3, 320, 240);
    let bits = |fb: &Framebuffer| -> Vec<u32> {
        fb.color
            .iter()
            .flat_map(|c| c.to_array().map(f32::to_bits))
            .chain(fb.depth.iter().map(|d| d.to_bits()))
            .collect()
    };
    assert!(bits(&a) == bits(&b), "1 vs 2 threads differ");
    assert!(bits(&a) == bits(&c), "1 vs 3 threads differ");
    // The scene is not trivially empty.
    let background = Vec3::new(0.02, 0.02, 0.03);
    let touched = a.color.iter().filter(|c| **c != background).count();
    assert!(touched > 5_000, "{touched}");
}

/// Renders the scene to `<target tmp>/raster_scene.png` to look at, and checks the head
/// occludes hair behind it while hair in front of it shows.
#[test]
fn scene_png() {
    let fb = render_scene(2, 640, 480);
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("raster_scene.png");
    wisp::output::write_png_rgb8(&path, fb.width, fb.height, &fb.to_srgb8()).unwrap();
    // A 4x nearest-neighbour zoom of the head's upper-left edge, to judge anti-aliasing.
    let (x0, y0, cw, ch, zoom) = (200, 100, 120, 90, 4);
    let rgb = fb.to_srgb8();
    let mut crop = Vec::with_capacity(cw * ch * zoom * zoom * 3);
    for y in 0..ch * zoom {
        for x in 0..cw * zoom {
            let i = 3 * ((y0 + y / zoom) * fb.width as usize + x0 + x / zoom);
            crop.extend_from_slice(&rgb[i..i + 3]);
        }
    }
    let crop_path = path.with_file_name("raster_scene_zoom.png");
    let (zw, zh) = ((cw * zoom) as u32, (ch * zoom) as u32);
    wisp::output::write_png_rgb8(&crop_path, zw, zh, &crop).unwrap();
    assert!(fb.color.iter().all(|c| c.is_finite()));
    let head_pixels = fb.depth.iter().filter(|d| d.is_finite()).count();
    assert!(head_pixels > 10_000, "{head_pixels}");
}

#[test]
fn degenerate_input_never_panics_and_draws_nothing_wrong() {
    let cam = axis_camera(50, 40);
    let good = unproject(&cam, 25.0, 20.0, 1.0);
    let nasty = [
        Vec3::NAN,
        Vec3::new(f32::INFINITY, 0.0, -1.0),
        Vec3::new(0.0, f32::NEG_INFINITY, -1.0),
        Vec3::new(1e30, 1e30, -1.0),
        Vec3::new(-1e38, 3e38, -1e-30),
        Vec3::new(0.0, 0.0, 5.0),   // behind the eye
        Vec3::new(0.0, 0.0, -1e-4), // nearer than the near plane
        Vec3::new(0.0, 0.0, -1e30), // very far
        good,                       // zero-length with `good`
        Vec3::new(1e-3, 0.0, 0.0),  // beside the eye
    ];
    let mut scratch = LineScratch::default();
    for a in nasty {
        for b in nasty {
            for (w, h) in [(50, 40), (1, 1), (0, 0), (1, 40), (50, 1), (0, 7)] {
                let cam = axis_camera(w, h);
                let mut fb = Framebuffer::new(w, h, Vec3::ZERO);
                let pts = [a, b, good];
                let lines = Polylines {
                    points: &pts,
                    colors: &[Vec3::ONE; 3],
                    widths_m: &[],
                    points_per_line: 3,
                    bundle: None,
                };
                for width_px in [1.0, 0.0, -1.0, f32::NAN, 1e9, f32::INFINITY] {
                    let style = LineStyle {
                        width: LineWidth::Pixels(width_px),
                        opacity: 1.0,
                    };
                    draw_polylines(&mut fb, &cam, &lines, &style, &mut scratch);
                }
                assert!(
                    fb.color
                        .iter()
                        .all(|c| c.is_finite() && c.max_element() <= 1.0 + 1e-6)
                );
                assert!(fb.color.iter().all(|c| c.min_element() >= 0.0));
            }
        }
    }
    // Bad colours, odd counts, mismatched lengths, inconsistent buffers.
    let mut fb = Framebuffer::new(50, 40, Vec3::ZERO);
    let far = unproject(&cam, 40.0, 30.0, 1.0);
    let pts = [good, far, good, far, good];
    let cols = [
        Vec3::NAN,
        Vec3::ONE,
        Vec3::splat(f32::INFINITY),
        Vec3::ONE,
        Vec3::ONE,
    ];
    for n in [0, 1, 2, 3, 5, 6, usize::MAX] {
        for ncol in [0, 1, 3, 5] {
            let lines = Polylines {
                points: &pts,
                colors: &cols[..ncol],
                widths_m: &[],
                points_per_line: n,
                bundle: None,
            };
            draw_polylines(&mut fb, &cam, &lines, &LineStyle::default(), &mut scratch);
            assert!(fb.color.iter().all(|c| c.is_finite()));
        }
    }
    for opacity in [f32::NAN, 0.0, -1.0, 7.0] {
        let lines = Polylines {
            points: &pts[2..],
            colors: &cols[2..],
            widths_m: &[],
            points_per_line: 2,
            bundle: None,
        };
        draw_polylines(
            &mut fb,
            &cam,
            &lines,
            &LineStyle {
                width: LineWidth::Pixels(1.0),
                opacity,
            },
            &mut scratch,
        );
        assert!(
            fb.color
                .iter()
                .all(|c| c.is_finite() && c.max_element() <= 1.0 + 1e-6)
        );
    }
    fb.depth.pop();
    let lines = Polylines {
        points: &pts[3..],
        colors: &cols[3..],
        widths_m: &[],
        points_per_line: 2,
        bundle: None,
    };
    draw_polylines(&mut fb, &cam, &lines, &LineStyle::default(), &mut scratch);
}

/// A segment from beside the camera to far away crosses the near plane: the visible part is
/// drawn, ending (in the image) where the clip put it, not mirrored.
#[test]
fn near_plane_clipping_keeps_the_visible_part() {
    let cam = axis_camera(100, 100);
    // From behind the eye (z = +1) to in front (z = −1), offset to the right and down.
    let pts = [Vec3::new(0.2, -0.2, 1.0), Vec3::new(0.2, -0.2, -1.0)];
    let mut fb = Framebuffer::new(100, 100, Vec3::ZERO);
    draw(
        &mut fb,
        &cam,
        &pts,
        &[Vec3::ONE; 2],
        2,
        LineStyle::default(),
    );
    // (0.2, −0.2, −1) projects to (60, 60); nearer points go off toward the bottom right.
    assert!(fb.pixel(60, 60).unwrap().x > 0.2);
    assert!(fb.pixel(80, 80).unwrap().x > 0.2);
    // Nothing up and left of the vanishing point (a mirrored projection would put it there).
    for y in 0..55 {
        for x in 0..55 {
            assert_eq!(fb.pixel(x, y).unwrap(), Vec3::ZERO, "{x},{y}");
        }
    }
}

/// A line piercing a sphere obliquely, with strong perspective (depth 1.5 m to 4.5 m): on
/// every pixel of its row, the line shows exactly where its true depth on that pixel's ray is
/// less than the sphere's. Screen-linear depth interpolation would move the crossing points
/// by several pixels.
#[test]
fn depth_is_perspective_correct_against_the_head() {
    let (w, h) = (200, 101); // odd height: y = 0 projects onto the centre of row 50
    let cam = axis_camera(w, h);
    let (centre, radius) = (Vec3::new(0.0, 0.0, -3.0), 0.5_f32);
    let skin = Vec3::new(0.2, 0.8, 0.2);
    let mut fb = Framebuffer::new(w, h, Vec3::ZERO);
    draw_ellipsoid(
        &mut fb,
        &cam,
        Affine3A::from_scale_rotation_translation(
            Vec3::splat(radius),
            glam::Quat::IDENTITY,
            centre,
        ),
        |_, _| skin,
    );
    let head_only = fb.clone();
    let (a, b) = (Vec3::new(-1.0, 0.0, -1.5), Vec3::new(1.0, 0.0, -4.5));
    let red = Vec3::X;
    draw(&mut fb, &cam, &[a, b], &[red; 2], 2, LineStyle::default());
    let f = cam.focal_px();
    let (mut shown, mut hidden) = (0, 0);
    for i in 0..w {
        let xs = (i as f32 + 0.5 - 0.5 * w as f32) / f;
        // Ray (xs, 0, −1)·s meets the line A + t (B − A) where A.x + t dx = xs · (−A.z − t dz).
        let d = b - a;
        let t = (-xs * a.z - a.x) / (d.x + xs * d.z);
        if !(0.02..=0.98).contains(&t) {
            continue; // near the end caps
        }
        let line_depth = -(a.z + t * d.z);
        // Sphere along the ray p = s·(xs, 0, −1): |p − c|² = r², depth = s.
        let dir = Vec3::new(xs, 0.0, -1.0);
        let (qa, qb, qc) = (
            dir.dot(dir),
            dir.dot(centre),
            centre.dot(centre) - radius * radius,
        );
        let disc = qb * qb - qa * qc;
        let sphere_depth = if disc > 0.0 {
            (qb - disc.sqrt()) / qa
        } else {
            f32::INFINITY
        };
        let px = fb.pixel(i, 50).unwrap();
        if sphere_depth.is_finite() && (line_depth - sphere_depth).abs() < 0.02 {
            continue; // the crossing pixel itself
        }
        if line_depth < sphere_depth {
            assert_eq!(
                px, red,
                "pixel {i}: line at {line_depth} in front of {sphere_depth}"
            );
            shown += 1;
        } else {
            let head = head_only.pixel(i, 50).unwrap();
            assert_eq!(
                px, head,
                "pixel {i}: line at {line_depth} behind {sphere_depth}"
            );
            hidden += 1;
        }
    }
    assert!(shown > 20 && hidden > 5, "shown {shown}, hidden {hidden}");
}
