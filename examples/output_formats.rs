//! What each frame format of `wisp render --format` costs on a real frame: conversion from the
//! framebuffer, encoding, and the file's size.
//!
//! ```text
//! cargo run --release --example output_formats -- [--width 800] [--height 800] [--time-s 1]
//!     [--repeat 10] [--png16-levels]
//! ```
//!
//! Renders one frame of the embedded dance with the `smooth` hairstyle (the default scene of
//! `wisp render`, settled and simulated up to `--time-s`), then for each format times the
//! conversion (median of `--repeat`, on the global rayon pool: the render thread's part) and
//! the encoding and writing of the file (median, on this one thread: the writer thread's
//! part, temporary file, fsync and rename included), and prints a Markdown table with the
//! file's size. `--png16-levels` adds the 16-bit PNG encoded into memory at the png crate's
//! compression settings (`Fast` is the one `write_png_rgba16` uses).

use std::time::Instant;
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

fn arg<T: std::str::FromStr>(args: &[String], name: &str, default: T) -> T {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Median wall time of `f` over `n` runs, in ms.
fn median_ms(n: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..n.max(1))
        .map(|_| {
            let t0 = Instant::now();
            f();
            t0.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn png16(rgba: &[u16], width: u32, height: u32, compression: png::Compression) -> Vec<u8> {
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, width, height);
    enc.set_color(png::ColorType::Rgba);
    enc.set_depth(png::BitDepth::Sixteen);
    enc.set_compression(compression);
    let be: Vec<u8> = rgba.iter().flat_map(|v| v.to_be_bytes()).collect();
    let mut w = enc.write_header().expect("header");
    w.write_image_data(&be).expect("data");
    w.finish().expect("finish");
    out
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let config = { EngineConfig::sized(arg(&args, "--width", 800), arg(&args, "--height", 800)) };
    let (w, h) = (config.scene.width, config.scene.height);
    let time_s: f64 = arg(&args, "--time-s", 1.0);
    let repeat: usize = arg(&args, "--repeat", 10);
    let mut engine = Engine::new(Hairstyle::default_smooth(), Motion::default_dance(), config);
    engine.run_up_to(time_s);
    let fb = engine.frame(time_s).clone();
    let bg = engine.scene.background;
    let dir = std::env::temp_dir().join(format!("wisp-output-formats-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");

    println!(
        "{w}×{h}, t = {time_s} s, {} threads, median of {repeat}",
        rayon::current_num_threads()
    );
    println!();
    println!("| format | conversion ms | encoding and writing ms | file KB |");
    println!("|---|---|---|---|");
    let mut rgb8 = Vec::new();
    let convert = median_ms(repeat, || fb.to_srgb8_into(&mut rgb8));
    let p = dir.join("a.png");
    let encode = median_ms(repeat, || {
        wisp::output::write_png_rgb8(&p, w, h, &rgb8).expect("png");
    });
    let kb = std::fs::metadata(&p).map_or(0, |m| m.len()) as f64 / 1e3;
    println!("| png (8-bit RGB) | {convert:.1} | {encode:.1} | {kb:.0} |");
    let mut rgba16 = Vec::new();
    let convert = median_ms(repeat, || fb.to_srgb16_rgba_into(bg, &mut rgba16));
    let p = dir.join("b.png");
    let encode = median_ms(repeat, || {
        wisp::output::write_png_rgba16(&p, w, h, &rgba16).expect("png16");
    });
    let kb = std::fs::metadata(&p).map_or(0, |m| m.len()) as f64 / 1e3;
    println!("| png16 (16-bit RGBA, Fast) | {convert:.1} | {encode:.1} | {kb:.0} |");
    let (mut rgb, mut alpha) = (Vec::new(), Vec::new());
    let convert = median_ms(repeat, || fb.premultiplied_into(bg, &mut rgb, &mut alpha));
    let p = dir.join("c.exr");
    let encode = median_ms(repeat, || {
        wisp::output::write_exr_rgba_f32(&p, w, h, &rgb, &alpha).expect("exr");
    });
    let kb = std::fs::metadata(&p).map_or(0, |m| m.len()) as f64 / 1e3;
    println!("| exr (f32 RGBA) | {convert:.1} | {encode:.1} | {kb:.0} |");
    if args.iter().any(|a| a == "--png16-levels") {
        for (name, c) in [
            ("Fast", png::Compression::Fast),
            ("Balanced", png::Compression::Balanced),
            ("High", png::Compression::High),
        ] {
            let mut bytes = Vec::new();
            let encode = median_ms(repeat.min(5), || bytes = png16(&rgba16, w, h, c));
            println!(
                "| png16 {name}, in memory | | {encode:.1} | {:.0} |",
                bytes.len() as f64 / 1e3
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
