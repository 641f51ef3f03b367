//! The window's on-screen readout: lines of text on a dark translucent box, drawn into the 0RGB
//! buffer that goes to the window (after the engine's image was converted, so a screenshot of
//! the engine's framebuffer never contains it). Its figures ([`Readout`]) are means over the
//! frames of the last half second ([`ReadoutMeter`]), so they can be read while they change.
//!
//! Glyphs come from `font8x8` (the public-domain 8×8 VGA-style font, ASCII part), drawn at an
//! integer scale. Every write is clipped to the buffer: a window of any size, down to 1×1 or a
//! buffer shorter than width × height, draws what fits and nothing else.

use font8x8::legacy::BASIC_LEGACY;
use std::fmt::Write;
use std::time::Instant;
use wisp::engine::{Engine, StageTimings};
use wisp::fiber::ShadingMode;
use wisp::quality::Quality;

/// How often the readout's figures are renewed (means over the frames since), seconds.
const READOUT_INTERVAL_S: f64 = 0.5;

/// Glyph cell size in font pixels (the font is 8×8; lines are 2 pixels apart).
const GLYPH_PX: usize = 8;
const LINE_PX: usize = GLYPH_PX + 2;
/// Padding between the box edge and the text, and between the box and the window edge, in
/// font pixels.
const PAD_PX: usize = 4;
/// The box darkens what is behind it to (256 − 176)/256 ≈ 31% of its brightness.
const BOX_ALPHA_256: u32 = 176;
/// Text colour, 0RGB (light grey: bright on the box, not glaring).
const TEXT_RGB: u32 = 0x00E8_E8E0;

/// The pixel rectangle a panel covers, clipped to the buffer (`x0..x1`, `y0..y1`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rect {
    pub x0: usize,
    pub y0: usize,
    pub x1: usize,
    pub y1: usize,
}

/// What the readout says: the frame rate, the mean time of each stage and the switches.
#[derive(Clone, Debug, Default)]
pub struct Readout {
    /// Frames shown per second of wall clock.
    pub fps: f64,
    /// Mean per-frame time of the engine's stages, seconds.
    pub stages: StageTimings,
    /// Mean per-frame time of the window's own work (image conversion, the readout, the
    /// upload to the window), seconds.
    pub window_s: f64,
    pub mode: ShadingMode,
    pub self_collision: bool,
    pub paused: bool,
    pub level: Quality,
    /// Simulation steps each frame moves the motion by.
    pub steps_per_frame: u32,
}

impl Readout {
    /// The readout as lines of at most 28 characters (so it fits a 240-pixel window), written
    /// into `out` (cleared first; reused from frame to frame).
    pub fn write_into(&self, out: &mut String) {
        let ms = |s: f64| 1e3 * s;
        let t = &self.stages;
        out.clear();
        // Writing to a String cannot fail.
        let _ = write!(
            out,
            "{:.1} fps{}\n\
             anim {:.1}  sim {:.1} ms\n\
             sim steps/frame: {}\n\
             interp {:.1}  map {:.1} ms\n\
             shade {:.1}  raster {:.1} ms\n\
             window {:.1} ms\n\
             shader: {}\n\
             self-collision: {}\n\
             quality: {}",
            self.fps,
            if self.paused { "  paused" } else { "" },
            ms(t.animation_s),
            ms(t.simulation_s),
            self.steps_per_frame,
            ms(t.interpolation_s),
            ms(t.map_s),
            ms(t.shading_s),
            ms(t.raster_s),
            ms(self.window_s),
            match self.mode {
                ShadingMode::DualScattering => "dual",
                ShadingMode::SingleScattering => "single",
                ShadingMode::KajiyaKay => "kajiya-kay",
                ShadingMode::Visibility => "visibility",
                ShadingMode::Volume => "volume",
            },
            if self.self_collision { "on" } else { "off" },
            self.level.name(),
        );
    }
}

/// The readout's figures ([`Readout`]): means over the frames since they were last renewed,
/// renewed every [`READOUT_INTERVAL_S`]; the switches as of the last frame.
pub struct ReadoutMeter {
    readout: Option<Readout>,
    /// The readout's text, reused from frame to frame.
    text: String,
    /// When the figures were last renewed, and the sums since: stage timings, window
    /// seconds, frames.
    since: Instant,
    stages: StageTimings,
    window_s: f64,
    frames: u32,
}

impl ReadoutMeter {
    pub fn new() -> Self {
        Self {
            readout: None,
            text: String::new(),
            since: Instant::now(),
            stages: StageTimings::default(),
            window_s: 0.0,
            frames: 0,
        }
    }

    /// Counts a frame shown: the engine's stage timings and `window_s` of the window's own
    /// work; renews the figures when they are due (at once the first time), and takes the
    /// shader, self-collision, `paused` and the simulation steps per frame as they are now.
    pub fn record(&mut self, engine: &Engine, window_s: f64, paused: bool, steps: u32) {
        self.stages.add(&engine.timings);
        self.window_s += window_s;
        self.frames += 1;
        let since_s = self.since.elapsed().as_secs_f64();
        if self.readout.is_none() || since_s >= READOUT_INTERVAL_S {
            let n = self.frames as f64;
            self.readout = Some(Readout {
                fps: n / since_s.max(1e-9),
                stages: self.stages.scaled(1.0 / n),
                window_s: self.window_s / n,
                ..Readout::default()
            });
            (self.stages, self.window_s, self.frames) = (StageTimings::default(), 0.0, 0);
            self.since = Instant::now();
        }
        if let Some(r) = &mut self.readout {
            r.mode = engine.shading.config.mode;
            r.self_collision = engine.simulation.config.self_collision;
            r.level = engine.level;
            r.paused = paused;
            r.steps_per_frame = steps;
        }
    }

    /// Draws the readout, once there is one, over the `w` × `h` image `argb`.
    pub fn draw(&mut self, argb: &mut [u32], w: usize, h: usize) {
        if let Some(r) = &self.readout {
            r.write_into(&mut self.text);
            draw_panel(argb, w, h, &self.text, scale_for(w));
        }
    }
}

/// Font scale for a window: 1 below 900 pixels wide, then 2 (8-pixel glyphs are hard to read
/// on a large, high-density screen).
pub fn scale_for(width: usize) -> usize {
    if width >= 900 { 2 } else { 1 }
}

/// Draws `text` (lines split at '\n'; characters outside ASCII as '?') at the top left of a
/// `width` × `height` 0RGB buffer, `scale` screen pixels per font pixel (1 to 8), on a dark translucent
/// box. Returns the rectangle drawn (empty when nothing fits); nothing outside it changes.
pub fn draw_panel(buf: &mut [u32], width: usize, height: usize, text: &str, scale: usize) -> Rect {
    let scale = scale.clamp(1, 8);
    // Only whole rows of the buffer are drawn on.
    let height = height.min(buf.len().checked_div(width).unwrap_or(0));
    let cols = text.lines().map(|l| l.chars().count()).max().unwrap_or(0);
    let rows = text.lines().count();
    let box_w = (2 * PAD_PX + cols * GLYPH_PX) * scale;
    // The last line needs no gap below it.
    let text_h = (rows * LINE_PX).saturating_sub(LINE_PX - GLYPH_PX);
    let box_h = (2 * PAD_PX + text_h) * scale;
    let r = Rect {
        x0: (PAD_PX * scale).min(width),
        y0: (PAD_PX * scale).min(height),
        x1: (PAD_PX * scale + box_w).min(width),
        y1: (PAD_PX * scale + box_h).min(height),
    };
    if rows == 0 || r.x0 >= r.x1 || r.y0 >= r.y1 {
        return Rect {
            x1: r.x0,
            y1: r.y0,
            ..r
        };
    }
    for y in r.y0..r.y1 {
        for p in &mut buf[y * width + r.x0..y * width + r.x1] {
            *p = darken(*p);
        }
    }
    let left = r.x0 + PAD_PX * scale;
    for (row, line) in text.lines().enumerate() {
        let top = r.y0 + (PAD_PX + row * LINE_PX) * scale;
        for (col, ch) in line.chars().enumerate() {
            let glyph = BASIC_LEGACY[if ch.is_ascii() {
                ch as usize
            } else {
                b'?' as usize
            }];
            let x = left + col * GLYPH_PX * scale;
            draw_glyph(buf, width, &r, x, top, &glyph, scale);
        }
    }
    r
}

/// Blends a 0RGB pixel toward black by [`BOX_ALPHA_256`].
fn darken(p: u32) -> u32 {
    let keep = 256 - BOX_ALPHA_256;
    let ch = |shift: u32| (((p >> shift) & 0xFF) * keep / 256) << shift;
    ch(16) | ch(8) | ch(0)
}

/// One glyph with its top-left corner at (`x`, `y`), clipped to `clip`. In font8x8 each byte
/// is a row, top first, and bit i is column i from the left.
fn draw_glyph(
    buf: &mut [u32],
    width: usize,
    clip: &Rect,
    x: usize,
    y: usize,
    glyph: &[u8; 8],
    scale: usize,
) {
    for (gy, bits) in glyph.iter().enumerate() {
        for gx in 0..GLYPH_PX {
            if bits & (1 << gx) == 0 {
                continue;
            }
            for sy in 0..scale {
                let py = y + gy * scale + sy;
                if py >= clip.y1 {
                    break;
                }
                for sx in 0..scale {
                    let px = x + gx * scale + sx;
                    if px >= clip.x1 {
                        break;
                    }
                    buf[py * width + px] = TEXT_RGB;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests;
