//! Hair hidden behind the solids or behind nearer hair is neither drawn nor shaded
//! (`raster::seen_points`, `src/raster/cull.rs`, `src/raster/hiding.rs`): the colour of a
//! point left unmarked never reaches a pixel, compositing the fragments the seen pass kept
//! with the marked points' colours (`draw_seen_polylines`) gives the same bits, so the
//! engine's frame, which shades only the marked points, is the frame of shading them all,
//! byte for byte; and it does leave out the hair behind the character and under the hair's
//! surface.

use glam::{Vec2, Vec3};
use proptest::prelude::*;
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;
use wisp::raster::{
    Bundle, Camera, Framebuffer, LineScratch, LineStyle, Polylines, draw_polylines,
    draw_seen_polylines, seen_points,
};

const W: u32 = 120;
const H: u32 = 80;

/// Eye on +Z looking at the origin, 0.9 rad vertical fov.
fn camera() -> Camera {
    Camera::look_at(Vec3::new(0.0, 0.0, 2.0), Vec3::ZERO, Vec3::Y, 0.9, W, H)
}

/// A framebuffer whose opaque depth is `blocks` per 5 × 5 block (24 × 16 of them, row-major;
/// `None`: background), as if solids had been drawn.
fn with_solids(blocks: &[Option<f32>]) -> Framebuffer {
    let mut fb = Framebuffer::new(W, H, Vec3::splat(0.1));
    for (i, d) in fb.depth.iter_mut().enumerate() {
        let (x, y) = (i % W as usize, i / W as usize);
        *d = blocks[(y / 5) * 24 + x / 5].unwrap_or(f32::INFINITY);
    }
    fb
}

/// Draws `lines` over a copy of `fb`; the colour and coverage bits.
fn draw(fb: &Framebuffer, lines: &Polylines, style: &LineStyle) -> (Vec<u32>, Vec<u32>) {
    let mut fb = fb.clone();
    draw_polylines(
        &mut fb,
        &camera(),
        lines,
        style,
        &mut LineScratch::default(),
    );
    let color = fb.color.iter().flat_map(|c| c.to_array().map(f32::to_bits));
    (
        color.collect(),
        fb.coverage.iter().map(|c| c.to_bits()).collect(),
    )
}

/// The engine's two passes over a copy of `fb`: the seen points of `lines` (kept fragments),
/// then the kept fragments drawn with the colours of `shaded` (the same geometry); the
/// colour and coverage bits.
fn draw_seen(
    fb: &Framebuffer,
    lines: &Polylines,
    shaded: &Polylines,
    style: &LineStyle,
) -> (Vec<u32>, Vec<u32>) {
    let mut fb = fb.clone();
    let mut scratch = LineScratch::default();
    seen_points(&fb, &camera(), lines, style, &mut scratch, &mut Vec::new());
    draw_seen_polylines(&mut fb, &camera(), shaded, style, &mut scratch);
    let color = fb.color.iter().flat_map(|c| c.to_array().map(f32::to_bits));
    (
        color.collect(),
        fb.coverage.iter().map(|c| c.to_bits()).collect(),
    )
}

/// Marks the points of `points` (lines of `per_line`) and checks that the colours of the
/// unmarked ones do not change a bit of the frame, drawn whole or only where marked; returns
/// (marked, unmarked).
fn check(
    points: &[Vec3],
    per_line: usize,
    width_m: f32,
    bundle: bool,
    fb: &Framebuffer,
) -> (usize, usize) {
    let disc: Vec<Vec2> = (0..20)
        .map(|k| {
            let (r, a) = (((k as f32 + 0.5) / 20.0).sqrt(), k as f32 * 2.4);
            Vec2::new(r * a.cos(), r * a.sin())
        })
        .collect();
    let colors: Vec<Vec3> = (0..points.len())
        .map(|i| Vec3::new(0.2 + 0.1 * (i % 7) as f32, 0.5, 0.3))
        .collect();
    let widths = vec![width_m; points.len()];
    let lines = Polylines {
        points,
        colors: &colors,
        widths_m: &widths,
        points_per_line: per_line,
        bundle: bundle.then_some(Bundle {
            radius_m: width_m,
            fiber_radius_m: width_m / 50.0,
            points: &disc,
        }),
    };
    let style = LineStyle::projected(1.0);
    let mut seen = Vec::new();
    seen_points(
        fb,
        &camera(),
        &lines,
        &style,
        &mut LineScratch::default(),
        &mut seen,
    );
    assert_eq!(seen.len(), points.len());
    // The unmarked points get other colours (as the engine leaves them black).
    let other: Vec<Vec3> = colors
        .iter()
        .zip(&seen)
        .map(|(c, &s)| if s { *c } else { Vec3::new(5.0, 0.0, 9.0) })
        .collect();
    let changed = Polylines {
        colors: &other,
        ..lines
    };
    let whole = draw(fb, &lines, &style);
    assert!(
        whole == draw(fb, &changed, &style),
        "an unmarked point's colour reached a pixel"
    );
    assert!(
        whole == draw_seen(fb, &lines, &changed, &style),
        "drawing the kept fragments with the marked points' colours changed the frame"
    );
    let marked = seen.iter().filter(|&&s| s).count();
    (marked, points.len() - marked)
}

/// Lines across the frame at depth 2 m over a wall at 1.5 m with a hole: the hair behind the
/// wall is unmarked, the hair over the hole is marked, and neither changes the frame.
#[test]
fn hair_behind_a_wall_is_unmarked_and_over_a_hole_marked() {
    let points: Vec<Vec3> = (0..6)
        .flat_map(|l| {
            (0..10).map(move |i| Vec3::new(-0.9 + i as f32 * 0.2, -0.4 + l as f32 * 0.15, 0.0))
        })
        .collect();
    let wall = with_solids(&[Some(1.5); 384]);
    assert_eq!(check(&points, 10, 0.004, false, &wall), (0, 60));
    let behind = with_solids(&[Some(2.5); 384]);
    assert_eq!(check(&points, 10, 0.004, false, &behind), (60, 0));
    let mut holed = vec![Some(1.5); 384];
    for b in [7 * 24 + 10, 7 * 24 + 11, 8 * 24 + 10, 8 * 24 + 11] {
        holed[b] = None;
    }
    let (marked, unmarked) = check(&points, 10, 0.004, false, &with_solids(&holed));
    assert!(marked > 0 && unmarked > 0, "{marked} {unmarked}");
    let (marked, unmarked) = check(&points, 10, 0.06, true, &with_solids(&holed));
    assert!(marked > 0 && unmarked > 0, "{marked} {unmarked}");
}

/// A curtain of wide opaque lines at 0.8 m in front of lines at 0 m over the left half: the
/// lines behind the curtain are unmarked, those beside it marked, and the frame is unchanged.
#[test]
fn hair_behind_nearer_hair_is_unmarked() {
    let line =
        |x0: f32, dx: f32, y: f32, z: f32| (0..8).map(move |i| Vec3::new(x0 + i as f32 * dx, y, z));
    let mut points: Vec<Vec3> = (0..40)
        .flat_map(|l| line(-1.2, 0.17, -0.8 + l as f32 * 0.04, 0.8))
        .collect();
    let under = points.len();
    points.extend((0..6).flat_map(|l| line(-0.7, 0.05, -0.4 + l as f32 * 0.15, 0.0)));
    let beside = points.len();
    points.extend((0..6).flat_map(|l| line(0.3, 0.05, -0.4 + l as f32 * 0.15, 0.0)));
    let open = with_solids(&[None; 384]);
    check(&points, 8, 0.06, false, &open);
    let widths = vec![0.06; points.len()];
    let colors = vec![Vec3::ONE; points.len()];
    let lines = Polylines {
        points: &points,
        colors: &colors,
        widths_m: &widths,
        points_per_line: 8,
        bundle: None,
    };
    let mut seen = Vec::new();
    seen_points(
        &open,
        &camera(),
        &lines,
        &LineStyle::projected(1.0),
        &mut LineScratch::default(),
        &mut seen,
    );
    assert!(
        seen[under..beside].iter().all(|&s| !s),
        "hair under the curtain marked"
    );
    assert!(
        seen[beside..].iter().all(|&s| s),
        "hair beside the curtain unmarked"
    );
    assert!(seen[..under].iter().any(|&s| s), "the curtain unmarked");
}

proptest! {
    /// For random lines (thin, wide, bundles drawn as their fibres, behind the eye, off
    /// screen) over random blocks of opaque depth, the colours of unmarked points never reach
    /// a pixel.
    #[test]
    fn unmarked_colors_never_reach_a_pixel(
        pts in prop::collection::vec((-1.2f32..1.2, -0.8f32..0.8, -1.5f32..2.5), 12),
        width_m in 0.0005f32..0.1,
        bundle in any::<bool>(),
        blocks in prop::collection::vec(prop::option::weighted(0.9, 0.5f32..4.0), 384),
    ) {
        let points: Vec<Vec3> = pts.into_iter().map(|(x, y, z)| Vec3::new(x, y, z)).collect();
        check(&points, 4, width_m, bundle, &with_solids(&blocks));
    }
}

/// The engine's frame shades only the points the raster can draw, and is the frame of shading
/// every point, bit for bit: on the dance at 1280 × 720, where four fifths of the points
/// (83,736 of 103,850 at t = 2 s; 28,241 behind the character alone) cannot reach a pixel.
#[test]
fn engine_frame_is_the_frame_of_shading_every_point() {
    let config = EngineConfig::sized(1280, 720);
    let mut e = Engine::new(Hairstyle::default_smooth(), Motion::default_dance(), config);
    e.run_up_to(2.0);
    e.frame(2.0);
    let bits = |fb: &Framebuffer| -> Vec<u32> {
        fb.color
            .iter()
            .flat_map(|c| c.to_array().map(f32::to_bits))
            .chain(fb.coverage.iter().map(|c| c.to_bits()))
            .collect()
    };
    let only_seen = bits(e.framebuffer());
    let unshaded = e.colors().iter().filter(|c| **c == Vec3::ZERO).count();
    e.shade();
    let shaded_all = e.colors().iter().filter(|c| **c == Vec3::ZERO).count();
    let every = bits(e.draw());
    assert!(only_seen == every, "the frames differ");
    let n = e.colors().len();
    assert_eq!(shaded_all, 0, "a shaded point is black");
    assert!(
        unshaded * 2 > n,
        "only {unshaded} of {n} points left unshaded: nothing hidden was skipped"
    );
}

/// Without fragments kept for lines of this shape on a framebuffer of this size, the second
/// pass draws every segment itself: with no seen pass at all, after a seen pass of other
/// lines, and a second time after the kept fragments were spent. A marked point whose shaded
/// colour is not finite draws black, never NaN.
#[test]
fn second_pass_without_its_kept_fragments_draws_everything() {
    let points: Vec<Vec3> = (0..8)
        .flat_map(|l| {
            (0..6).map(move |i| {
                Vec3::new(
                    -0.8 + i as f32 * 0.3,
                    -0.5 + l as f32 * 0.12,
                    0.1 * l as f32,
                )
            })
        })
        .collect();
    let colors: Vec<Vec3> = (0..points.len())
        .map(|i| Vec3::new(0.1 * (i % 9) as f32, 0.4, 0.7))
        .collect();
    let widths = vec![0.01; points.len()];
    let lines = Polylines {
        points: &points,
        colors: &colors,
        widths_m: &widths,
        points_per_line: 6,
        bundle: None,
    };
    let style = LineStyle::projected(1.0);
    let fb = with_solids(&[None; 384]);
    let whole = draw(&fb, &lines, &style);
    let second = |scratch: &mut LineScratch| {
        let mut out = fb.clone();
        draw_seen_polylines(&mut out, &camera(), &lines, &style, scratch);
        let color = out
            .color
            .iter()
            .flat_map(|c| c.to_array().map(f32::to_bits));
        (
            color.collect::<Vec<_>>(),
            out.coverage.iter().map(|c| c.to_bits()).collect::<Vec<_>>(),
        )
    };
    let mut scratch = LineScratch::default();
    assert!(second(&mut scratch) == whole, "no seen pass");
    let other = Polylines {
        points: &points[..points.len() / 2],
        colors: &colors[..points.len() / 2],
        widths_m: &widths[..points.len() / 2],
        ..lines
    };
    seen_points(
        &fb,
        &camera(),
        &other,
        &style,
        &mut scratch,
        &mut Vec::new(),
    );
    assert!(
        second(&mut scratch) == whole,
        "after a seen pass of other lines"
    );
    seen_points(
        &fb,
        &camera(),
        &lines,
        &style,
        &mut scratch,
        &mut Vec::new(),
    );
    assert!(second(&mut scratch) == whole, "with the kept fragments");
    assert!(second(&mut scratch) == whole, "once they are spent");

    // A non-finite shaded colour: the kept fragments of its segments draw black.
    let mut seen = Vec::new();
    seen_points(&fb, &camera(), &lines, &style, &mut scratch, &mut seen);
    let bad: Vec<Vec3> = colors
        .iter()
        .zip(&seen)
        .enumerate()
        .map(|(i, (c, &s))| if s && i % 3 == 0 { Vec3::NAN } else { *c })
        .collect();
    assert!(bad.iter().any(|c| c.is_nan()), "no marked point to spoil");
    let mut out = fb.clone();
    let spoiled = Polylines {
        colors: &bad,
        ..lines
    };
    draw_seen_polylines(&mut out, &camera(), &spoiled, &style, &mut scratch);
    assert!(
        out.color.iter().all(|c| c.is_finite()),
        "a NaN reached a pixel"
    );
    assert!(out.coverage.iter().all(|c| c.is_finite()));
}

/// A band that would keep more fragments than the seen pass holds for it (64 a pixel of the
/// band) is emitted again by the second pass: 90 faint wide lines stacked over the same rows
/// (nothing hides anything), each covering its band's every pixel, give the one-pass draw's
/// bits, whatever the colours of the points the pass left unmarked.
#[test]
fn bands_over_the_kept_bound_are_emitted_again() {
    // 20 px wide lines (41.5 px a metre at 2 m) across the whole width, at rows 8 to 28.
    let points: Vec<Vec3> = (0..90)
        .flat_map(|l| {
            let z = -0.001 * l as f32;
            [
                Vec3::new(-2.0, 0.0, z),
                Vec3::new(0.0, 0.0, z),
                Vec3::new(2.0, 0.0, z),
            ]
        })
        .collect();
    let colors: Vec<Vec3> = (0..points.len())
        .map(|i| Vec3::new(0.01 * (i % 97) as f32, 0.3, 0.9 - 0.005 * (i % 61) as f32))
        .collect();
    let widths = vec![0.48; points.len()];
    let lines = Polylines {
        points: &points,
        colors: &colors,
        widths_m: &widths,
        points_per_line: 3,
        bundle: None,
    };
    let style = LineStyle {
        opacity: 0.02,
        ..LineStyle::projected(1.0)
    };
    let fb = with_solids(&[None; 384]);
    let whole = draw(&fb, &lines, &style);
    let mut seen = Vec::new();
    seen_points(
        &fb,
        &camera(),
        &lines,
        &style,
        &mut LineScratch::default(),
        &mut seen,
    );
    assert!(seen.iter().all(|&s| s), "a faint line was hidden");
    assert!(
        whole == draw_seen(&fb, &lines, &lines, &style),
        "the frames differ"
    );
    // The stack covers its rows with 90 layers at 0.02 (1 − 0.98⁹⁰ = 0.84).
    let mut out = fb.clone();
    draw_polylines(
        &mut out,
        &camera(),
        &lines,
        &style,
        &mut LineScratch::default(),
    );
    let covered = out.coverage.iter().filter(|&&c| c > 0.8).count();
    assert!(covered >= 16 * W as usize, "only {covered} pixels covered");
}
