//! Compares the PNG frames of a `wisp render` export: how many pixels change between
//! consecutive frames, by how much, and (optionally) a difference image of two frames.
//!
//! ```text
//! cargo run --release --example frame_diff -- DIR [--from N] [--diff A B OUT.png]
//! cargo run --release --example frame_diff -- DIR --against OTHER_DIR --frames 15,45,89
//! ```
//!
//! For every pair of consecutive frames `frame_{k-1}`, `frame_k` with k > N (default 0) it
//! prints the fraction of pixels whose RGB differ, the largest and the mean absolute difference
//! over all channels (grey levels), and a summary over all pairs. `--diff A B OUT.png` writes
//! |frame_A − frame_B| per channel, amplified 16× (clamped to 255), so a one-level change is
//! visible as a dark grey pixel and an unchanged image is pure black.
//!
//! `--against OTHER_DIR --frames LIST` instead compares the same frames of two exports (mean
//! absolute difference over all channels, grey levels), e.g. a run at a coarse simulation step
//! against one at a fine step; it also prints the mean difference between each listed frame
//! and the next one of OTHER_DIR (one frame of motion) for scale.
//!
//! Used to check that hair at rest stays at rest (issue 11): after the settle, a still-head
//! export must show no changed pixel.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

fn read_rgb(path: &Path) -> Result<(u32, u32, Vec<u8>), String> {
    let file = File::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let decoder = png::Decoder::new(std::io::BufReader::new(file));
    let mut reader = decoder
        .read_info()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| format!("{}: image too large", path.display()))?;
    let mut buf = vec![0u8; size];
    let info = reader
        .next_frame(&mut buf)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    if info.color_type != png::ColorType::Rgb || info.bit_depth != png::BitDepth::Eight {
        return Err(format!("{}: not 8-bit RGB", path.display()));
    }
    buf.truncate(info.buffer_size());
    Ok((info.width, info.height, buf))
}

fn frame_path(dir: &Path, k: usize) -> PathBuf {
    dir.join(format!("frame_{k:05}.png"))
}

struct PairDiff {
    changed_fraction: f64,
    max_level: u8,
    mean_level: f64,
}

fn compare(a: &[u8], b: &[u8]) -> PairDiff {
    let pixels = a.len() / 3;
    let mut changed = 0usize;
    let mut max_level = 0u8;
    let mut sum = 0u64;
    for (pa, pb) in a.chunks_exact(3).zip(b.chunks_exact(3)) {
        let mut any = false;
        for (x, y) in pa.iter().zip(pb) {
            let d = x.abs_diff(*y);
            any |= d > 0;
            max_level = max_level.max(d);
            sum += u64::from(d);
        }
        changed += usize::from(any);
    }
    PairDiff {
        changed_fraction: changed as f64 / pixels.max(1) as f64,
        max_level,
        mean_level: sum as f64 / a.len().max(1) as f64,
    }
}

fn write_diff(a: &Path, b: &Path, out: &Path) -> Result<(), String> {
    let (w, h, pa) = read_rgb(a)?;
    let (w2, h2, pb) = read_rgb(b)?;
    if (w, h) != (w2, h2) {
        return Err("frames differ in size".into());
    }
    let diff: Vec<u8> = pa
        .iter()
        .zip(&pb)
        .map(|(x, y)| (u32::from(x.abs_diff(*y)) * 16).min(255) as u8)
        .collect();
    let file = File::create(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut enc = png::Encoder::new(BufWriter::new(file), w, h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut writer = enc.write_header().map_err(|e| e.to_string())?;
    writer.write_image_data(&diff).map_err(|e| e.to_string())?;
    let d = compare(&pa, &pb);
    println!(
        "diff {} vs {}: {:.3}% pixels changed, max {} levels, mean {:.4}; wrote {}",
        a.display(),
        b.display(),
        d.changed_fraction * 100.0,
        d.max_level,
        d.mean_level,
        out.display()
    );
    Ok(())
}

fn main() {
    if let Err(e) = run() {
        eprintln!("frame_diff: {e}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let dir = PathBuf::from(
        args.first()
            .ok_or("usage: frame_diff DIR [--from N] [--diff A B OUT.png]")?,
    );
    let mut from = 0usize;
    let mut against: Option<PathBuf> = None;
    let mut frames: Vec<usize> = Vec::new();
    let mut i = 1;
    while i < args.len() {
        match args[i].as_str() {
            "--from" => {
                from = args
                    .get(i + 1)
                    .and_then(|s| s.parse().ok())
                    .ok_or("--from needs a frame number")?;
                i += 2;
            }
            "--diff" => {
                let a: usize = args
                    .get(i + 1)
                    .and_then(|s| s.parse().ok())
                    .ok_or("--diff A B OUT")?;
                let b: usize = args
                    .get(i + 2)
                    .and_then(|s| s.parse().ok())
                    .ok_or("--diff A B OUT")?;
                let out = PathBuf::from(args.get(i + 3).ok_or("--diff A B OUT")?);
                write_diff(&frame_path(&dir, a), &frame_path(&dir, b), &out)?;
                i += 4;
            }
            "--against" => {
                against = Some(PathBuf::from(
                    args.get(i + 1).ok_or("--against needs a folder")?,
                ));
                i += 2;
            }
            "--frames" => {
                frames = args
                    .get(i + 1)
                    .ok_or("--frames needs a list")?
                    .split(',')
                    .map(|f| f.parse().map_err(|_| format!("bad frame {f}")))
                    .collect::<Result<_, _>>()?;
                i += 2;
            }
            other => return Err(format!("unknown argument {other}")),
        }
    }
    if let Some(other) = against {
        for f in frames {
            let a = read_rgb(&frame_path(&dir, f))?.2;
            let b = read_rgb(&frame_path(&other, f))?.2;
            let next = read_rgb(&frame_path(&other, f + 1)).map(|n| compare(&b, &n.2).mean_level);
            let d = compare(&a, &b);
            println!(
                "frame {f}: mean abs difference {:.3} levels ({:.2}% pixels changed); frame {f} to {} of {}: {}",
                d.mean_level,
                d.changed_fraction * 100.0,
                f + 1,
                other.display(),
                next.map_or("—".to_string(), |m| format!("{m:.3}"))
            );
        }
        return Ok(());
    }
    let mut prev = read_rgb(&frame_path(&dir, from))?.2;
    let (mut pairs, mut changed_pairs) = (0usize, 0usize);
    let (mut worst_fraction, mut worst_level, mut mean_fraction, mut mean_level) =
        (0.0f64, 0u8, 0.0f64, 0.0f64);
    let mut last_changed = None;
    let mut k = from + 1;
    while frame_path(&dir, k).exists() {
        let cur = read_rgb(&frame_path(&dir, k))?.2;
        if cur.len() != prev.len() {
            return Err(format!("frame {k} differs in size"));
        }
        let d = compare(&prev, &cur);
        pairs += 1;
        if d.changed_fraction > 0.0 {
            changed_pairs += 1;
            last_changed = Some(k);
        }
        worst_fraction = worst_fraction.max(d.changed_fraction);
        worst_level = worst_level.max(d.max_level);
        mean_fraction += d.changed_fraction;
        mean_level += d.mean_level;
        println!(
            "{k:5}: {:7.3}% changed, max {:3}, mean {:.4}",
            d.changed_fraction * 100.0,
            d.max_level,
            d.mean_level
        );
        prev = cur;
        k += 1;
    }
    let n = pairs.max(1) as f64;
    println!(
        "summary over {pairs} pairs from frame {from}: {changed_pairs} pairs differ; changed pixels \
         mean {:.3}% (worst {:.3}%), max {worst_level} levels, mean abs {:.4}; last changed frame {}",
        mean_fraction / n * 100.0,
        worst_fraction * 100.0,
        mean_level / n,
        last_changed.map_or("none".to_string(), |k| k.to_string())
    );
    Ok(())
}
