use super::*;

const GREY: u32 = 0x0080_8080;

fn inside(r: &Rect, x: usize, y: usize) -> bool {
    (r.x0..r.x1).contains(&x) && (r.y0..r.y1).contains(&y)
}

/// Every pixel outside the returned rectangle is untouched; every pixel inside is either
/// darkened or text. Returns the number of text pixels.
fn check_panel(buf: &[u32], width: usize, r: &Rect) -> usize {
    let mut text = 0;
    for (i, &p) in buf.iter().enumerate() {
        let (x, y) = (i % width.max(1), i / width.max(1));
        if width > 0 && inside(r, x, y) {
            assert!(p == darken(GREY) || p == TEXT_RGB, "({x}, {y}) = {p:06x}");
            text += usize::from(p == TEXT_RGB);
        } else {
            assert_eq!(p, GREY, "({x}, {y}) outside {r:?} changed");
        }
    }
    text
}

#[test]
fn draws_text_on_a_box_in_the_top_left_corner() {
    let (w, h) = (240, 240);
    let mut buf = vec![GREY; w * h];
    let r = draw_panel(&mut buf, w, h, "12.3 fps\nshader: dual", 1);
    // 12 columns of 8 px and 2 lines (8 + 2 + 8 px), padded by 4 px on each side, 4 px in.
    assert_eq!(
        r,
        Rect {
            x0: 4,
            y0: 4,
            x1: 4 + 8 + 12 * 8,
            y1: 4 + 8 + 18
        }
    );
    let text = check_panel(&buf, w, &r);
    assert!(text > 100, "{text} text pixels");
    // The box darkens: 0x80 · 80 / 256 = 40.
    assert_eq!(darken(GREY), 0x0028_2828);
    assert_eq!(darken(0x00FF_FFFF), 0x004F_4F4F);
    // Scale 2 covers twice the size.
    let mut buf = vec![GREY; w * h];
    let r2 = draw_panel(&mut buf, w, h, "12.3 fps\nshader: dual", 2);
    assert_eq!(
        (r2.x1 - r2.x0, r2.y1 - r2.y0),
        (2 * (r.x1 - r.x0), 2 * (r.y1 - r.y0))
    );
    assert_eq!(check_panel(&buf, w, &r2), 4 * text);
}

/// The glyphs are the right way round: an 'L' has its upright on the left and its foot as
/// its widest row at the bottom (not mirrored, not upside down).
#[test]
fn glyphs_are_upright_and_not_mirrored() {
    let (w, h) = (32, 32);
    let mut buf = vec![GREY; w * h];
    draw_panel(&mut buf, w, h, "L", 1);
    // The glyph cell starts at 4 (margin) + 4 (padding) = 8.
    let lit = |x: usize, y: usize| buf[(8 + y) * w + 8 + x] == TEXT_RGB;
    let row_count = |y: usize| (0..8).filter(|&x| lit(x, y)).count();
    let col_count = |x: usize| (0..8).filter(|&y| lit(x, y)).count();
    let widest = (0..8).max_by_key(|&y| row_count(y)).unwrap();
    assert!(widest >= 5, "the foot is at the bottom (row {widest})");
    let left: usize = (0..4).map(col_count).sum();
    let right: usize = (4..8).map(col_count).sum();
    assert!(left > 2 * right, "upright on the left: {left} vs {right}");
    // A character outside ASCII draws as '?', not nothing.
    let mut buf = vec![GREY; w * h];
    let r = draw_panel(&mut buf, w, h, "é", 1);
    assert!(check_panel(&buf, w, &r) > 5);
}

/// Tiny windows, a short buffer, empty text, huge scales: no panic, nothing out of bounds,
/// nothing outside the returned rectangle changed.
#[test]
fn never_draws_out_of_bounds() {
    let text = "12.3 fps  paused\nanim 0.1  sim 20.1 ms\nself-collision: on";
    for (w, h, len) in [
        (16, 16, 256),
        (16, 16, 100),
        (1, 1, 1),
        (0, 0, 0),
        (0, 10, 5),
        (10, 0, 10),
        (9, 9, 81),
        (3, 500, 1500),
        (500, 3, 1500),
    ] {
        for scale in [0, 1, 2, 1000] {
            let mut buf = vec![GREY; len];
            let r = draw_panel(&mut buf, w, h, text, scale);
            assert!(
                r.x0 <= r.x1 && r.x1 <= w && r.y0 <= r.y1 && r.y1 <= h,
                "{r:?}"
            );
            if w > 0 {
                assert!(r.y1 * w <= len, "{r:?} within the buffer");
            }
            check_panel(&buf, w, &r);
        }
    }
    let mut buf = vec![GREY; 64 * 64];
    let r = draw_panel(&mut buf, 64, 64, "", 1);
    assert_eq!((r.x0, r.y0), (r.x1, r.y1), "empty text draws nothing");
    assert!(buf.iter().all(|&p| p == GREY));
}

#[test]
fn readout_says_what_is_on() {
    let mut r = Readout {
        fps: 12.34,
        stages: StageTimings {
            simulation_s: 0.0201,
            raster_s: 0.025,
            ..StageTimings::default()
        },
        window_s: 0.0021,
        mode: ShadingMode::KajiyaKay,
        self_collision: false,
        paused: true,
        level: Quality::Preview,
        steps_per_frame: 4,
    };
    let mut s = String::new();
    r.write_into(&mut s);
    for want in [
        "12.3 fps  paused",
        "sim 20.1 ms",
        "raster 25.0 ms",
        "window 2.1 ms",
        "shader: kajiya-kay",
        "self-collision: off",
        "quality: preview",
        "sim steps/frame: 4",
    ] {
        assert!(s.contains(want), "{want:?} in {s:?}");
    }
    assert!(s.lines().all(|l| l.len() <= 28), "{s}");
    (r.paused, r.self_collision, r.mode) = (false, true, ShadingMode::DualScattering);
    r.write_into(&mut s);
    assert!(!s.contains("paused") && s.contains("self-collision: on") && s.contains("dual"));
    assert_eq!(s.lines().count(), 9, "cleared before writing");
}
