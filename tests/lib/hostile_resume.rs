//! Damaged frames in a `--resume` folder (issue 60, item 1): every case of
//! `support::hostile::frames` is refused by `wisp::output::check_frame`, so `render --resume`
//! renders the frame again instead of keeping it. Each case runs bounded (`bounded.rs`): a
//! frame grown to 4 GiB is refused from its header and its length, with a small heap.

use crate::bounded::run_bounded;
use crate::support::hostile::Rng;
use crate::support::hostile::frames::{self, Damage, Expect, Kind};
use crate::support::scratch_dir;
use glam::Vec3;
use std::path::{Path, PathBuf};
use std::time::Duration;
use wisp::output::{FrameDefect, FrameFormat, check_frame};

/// A hang bound (not a speed assertion).
const HANG: Duration = Duration::from_secs(60);

/// 70 × 70 px: two 64-px tiles a side in the EXR (4 chunks), 70 rows in the PNGs.
const SIDE: u32 = 70;

/// Heap a check may use, in bytes: the decoded frame (70 × 70 × 4 channels × 4 bytes =
/// 78,400 for the EXR, 29,400 and 39,200 for the PNGs) plus the readers' buffers (8 KiB each)
/// and the zlib state (about 40 KB), with room to spare; a file read into memory would be its
/// length, 4 GiB for the grown ones.
const HEAP_BYTES: usize = 1 << 20;

/// Writes one complete frame of each format into `dir`: (format, kind, path).
fn complete_frames(dir: &Path) -> Vec<(FrameFormat, Kind, PathBuf)> {
    let n = (SIDE * SIDE) as usize;
    let rgb8: Vec<u8> = (0..3 * n).map(|i| (i * 37 % 251) as u8).collect();
    let rgba16: Vec<u16> = (0..4 * n).map(|i| (i * 7919 % 65_521) as u16).collect();
    let rgb: Vec<Vec3> = (0..n).map(|i| Vec3::splat(i as f32 * 0.01)).collect();
    let alpha: Vec<f32> = (0..n).map(|i| i as f32 / n as f32).collect();
    let frames = vec![
        (FrameFormat::Png8, Kind::Png, dir.join("png8.png")),
        (FrameFormat::Png16, Kind::Png, dir.join("png16.png")),
        (FrameFormat::Exr, Kind::Exr, dir.join("exr.exr")),
    ];
    wisp::output::write_png_rgb8(&frames[0].2, SIDE, SIDE, &rgb8).unwrap();
    wisp::output::write_png_rgba16(&frames[1].2, SIDE, SIDE, &rgba16).unwrap();
    wisp::output::write_exr_rgba_f32(&frames[2].2, SIDE, SIDE, &rgb, &alpha).unwrap();
    for (format, _, path) in &frames {
        assert_eq!(check_frame(path, *format, SIDE, SIDE), Ok(()), "{format:?}");
    }
    frames
}

/// Copies `original` to `damaged`, applies `damage` and checks the copy, bounded; the defect
/// and the peak heap.
fn check_damaged(
    original: &Path,
    damaged: &Path,
    format: FrameFormat,
    damage: &Damage,
) -> (Result<(), FrameDefect>, usize) {
    std::fs::copy(original, damaged).unwrap();
    damage.apply(damaged);
    let path = damaged.to_path_buf();
    let report = run_bounded(move || check_frame(&path, format, SIDE, SIDE), HANG)
        .unwrap_or_else(|e| panic!("{format:?} {damage:?}: {e}"));
    (report.value, report.peak_bytes)
}

/// The cases (a flipped bit in the `sRGB` chunk, junk appended, the file grown to
/// 4 GiB, an EXR attribute renamed) and their kin, in each format: each refused, saying why.
/// Appended and grown files are refused as `Trailing` at the exact original length.
#[test]
fn named_damages_are_refused() {
    let dir = scratch_dir("hostile-resume-named");
    let damaged = dir.join("damaged");
    let mut count = 0;
    for (format, kind, path) in complete_frames(&dir) {
        let bytes = std::fs::read(&path).unwrap();
        let cases = frames::named(kind, &bytes);
        if kind == Kind::Png {
            assert!(
                cases.iter().any(|c| c.0.contains("sRGB")),
                "wisp's PNGs carry an sRGB chunk"
            );
        }
        for (name, damage, expect) in cases {
            let (got, peak) = check_damaged(&path, &damaged, format, &damage);
            match (&expect, &got) {
                (Expect::Trailing { len }, Err(FrameDefect::Trailing { end, len: got_len })) => {
                    assert_eq!(
                        (*end, *got_len),
                        (bytes.len() as u64, *len),
                        "{format:?} {name}"
                    )
                }
                (Expect::Undecodable(text), Err(FrameDefect::Undecodable(message))) => {
                    assert!(message.contains(text), "{format:?} {name}: {message}")
                }
                _ => panic!("{format:?} {name}: {got:?}, expected {expect:?}"),
            }
            assert!(peak < HEAP_BYTES, "{format:?} {name}: {peak} bytes of heap");
            count += 1;
        }
    }
    println!("{count} named damages refused");
    // At least: 4 common cases a format, one flip per PNG chunk (IHDR, sRGB, IEND and one
    // IDAT or more: the 16-bit writer streams its rows into 14), 9 EXR attributes renamed and
    // 2 layout cases.
    assert!(count >= 3 * 4 + 2 * 4 + 9 + 2, "{count}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// 300 damages drawn per format (seeded): one bit of any PNG byte or of any byte of an EXR's
/// structure, bytes appended, or the file grown up to 4 GiB more; none passes as complete.
#[test]
fn generated_damages_are_refused() {
    let dir = scratch_dir("hostile-resume-generated");
    let damaged = dir.join("damaged");
    for (format, kind, path) in complete_frames(&dir) {
        let bytes = std::fs::read(&path).unwrap();
        for seed in 0..300 {
            let damage = frames::generated(&mut Rng::new(seed), kind, &bytes);
            let (got, peak) = check_damaged(&path, &damaged, format, &damage);
            assert!(
                matches!(
                    got,
                    Err(FrameDefect::Undecodable(_) | FrameDefect::Trailing { .. })
                ),
                "{format:?} seed {seed} {damage:?}: {got:?}"
            );
            assert!(peak < HEAP_BYTES, "{format:?} seed {seed}: {peak} bytes");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
