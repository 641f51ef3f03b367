//! `wisp render --format png|png16|exr` and `--resume`, through the binary: the three formats
//! of one frame agree (16-bit alpha = the EXR's coverage, colour composited over the
//! background = the 8-bit frame within one level), a resumed export re-renders exactly the
//! missing and damaged frames and ends byte-identical to a plain one (simulated, and from a
//! cache), and a bad --format is refused with exit code 2.

use crate::support::scratch_dir;
use crate::{stderr, wisp};
use std::os::unix::fs::MetadataExt;
use std::path::Path;

use glam::Vec3;
use wisp::engine::EngineConfig;
use wisp::output::{linear_to_srgb8, read_exr_rgba_f32};

/// Small frames keep each run to a few seconds (most of it the settle and the light map).
const SMALL: [&str; 6] = ["--width", "64", "--height", "64", "--frames", "3"];

/// Runs wisp and requires success.
fn ok(args: &[&str]) -> String {
    let o = wisp(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    stderr(&o)
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// (width, height, bit depth, colour type, samples; 16-bit samples widened from big-endian).
fn decode_png(path: &Path) -> (u32, u32, png::BitDepth, png::ColorType, Vec<u16>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())),
    ));
    let mut reader = decoder.read_info().expect("png header");
    let mut buf = vec![0; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut buf).expect("png data");
    buf.truncate(info.buffer_size());
    let samples = match info.bit_depth {
        png::BitDepth::Sixteen => buf
            .chunks_exact(2)
            .map(|b| u16::from_be_bytes([b[0], b[1]]))
            .collect(),
        _ => buf.iter().map(|&b| u16::from(b)).collect(),
    };
    (
        info.width,
        info.height,
        info.bit_depth,
        info.color_type,
        samples,
    )
}

/// The sRGB decoding curve (IEC 61966-2-1), [0, 1] -> linear.
fn srgb_to_linear(s: f64) -> f64 {
    if s <= 0.04045 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

/// Every file name in `dir` with its bytes, sorted.
fn contents(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().into_string().unwrap(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    v.sort();
    v
}

fn copy_dir(from: &Path, to: &Path) {
    for (name, bytes) in contents(from) {
        std::fs::write(to.join(name), bytes).unwrap();
    }
}

/// One hair-only frame (`--no-solids`) in the three formats. The 16-bit PNG's alpha is the
/// EXR's coverage rounded to 16 bits: 0 on background pixels (written as transparent black,
/// like the EXR's premultiplied 0), 65535 where the hair covers a pixel fully, both present.
/// Its colour is straight sRGB: decoded, composited over the background in linear light
/// (`a·c + (1 − a)·B`) and encoded to 8 bits it is the 8-bit frame within one level
/// (= 1/255; the 16-bit quantisation alone moves the composite by < 10⁻⁴). The EXR's
/// premultiplied colour composited the same way (`rgb + (1 − a)·B`) gives it within one level
/// too. B is the engine's default background, which `render` draws over.
///
/// png16 and exr frames are byte-identical on 1 and 2 threads. stderr is a pipe here, so the
/// progress bar must be hidden (no carriage returns or escape sequences) while the summary
/// stays; `--quiet` prints nothing.
#[test]
fn png16_and_exr_carry_the_8_bit_frame_and_its_coverage() {
    let root = scratch_dir("formats");
    let dirs = ["png", "png16", "exr"].map(|f| {
        let d = root.join(f);
        let err = ok(&[
            &["--threads", "2", "render", "--no-solids", "--format", f],
            &["--out", s(&d)][..],
            &SMALL[..],
        ]
        .concat());
        assert!(
            !err.contains('\r') && !err.contains('\u{1b}'),
            "progress bar drawn into a pipe: {err:?}"
        );
        assert!(err.contains("per frame (ms)"), "{err}");
        d
    });
    // The conversions are per pixel: the same bytes on 1 thread as on 2.
    for (f, d) in [("png16", &dirs[1]), ("exr", &dirs[2])] {
        let one = root.join(format!("{f}-1-thread"));
        ok(&[
            &["--threads", "1", "render", "--no-solids", "--format", f],
            &["--out", s(&one)][..],
            &SMALL[..],
        ]
        .concat());
        assert!(contents(&one) == contents(d), "{f}: 1 and 2 threads differ");
    }
    let quiet = root.join("quiet");
    let o = wisp(&[&["render", "--quiet", "--out", s(&quiet)], &SMALL[..]].concat());
    assert!(o.status.success());
    assert_eq!(stderr(&o), "");

    let bg = EngineConfig::default().scene.background;
    let (mut transparent, mut opaque, mut partial) = (0, 0, 0);
    for i in 0..3 {
        let name = format!("frame_{i:05}");
        let (w8, h8, d8, c8, rgb8) = decode_png(&dirs[0].join(format!("{name}.png")));
        assert_eq!(
            (w8, h8, d8, c8),
            (64, 64, png::BitDepth::Eight, png::ColorType::Rgb)
        );
        let (w, h, depth, color, rgba16) = decode_png(&dirs[1].join(format!("{name}.png")));
        assert_eq!(
            (w, h, depth, color),
            (64, 64, png::BitDepth::Sixteen, png::ColorType::Rgba)
        );
        let (we, he, rgb, alpha) = read_exr_rgba_f32(&dirs[2].join(format!("{name}.exr")))
            .expect("the EXR frame reads back");
        assert_eq!((we, he), (64, 64));
        for p in 0..(64 * 64) as usize {
            let px = &rgba16[4 * p..4 * p + 4];
            let a = alpha[p];
            assert!((0.0..=1.0).contains(&a) && rgb[p].is_finite(), "pixel {p}");
            assert_eq!(px[3], (a * 65535.0).round() as u16, "{name} pixel {p}");
            if a == 0.0 {
                assert_eq!(px, [0; 4], "{name} pixel {p}: background not transparent");
                assert_eq!(rgb[p], Vec3::ZERO, "{name} pixel {p}");
                transparent += 1;
            } else if px[3] == 65535 {
                opaque += 1;
            } else {
                partial += 1;
            }
            let a16 = f64::from(px[3]) / 65535.0;
            for k in 0..3 {
                let want = i32::from(rgb8[3 * p + k] as u8);
                let straight = srgb_to_linear(f64::from(px[k]) / 65535.0);
                let over = a16 * straight + (1.0 - a16) * f64::from(bg[k]);
                let got16 = i32::from(linear_to_srgb8(over as f32));
                assert!(
                    (got16 - want).abs() <= 1,
                    "{name} pixel {p} channel {k}: png16 over the background gives {got16}, png {want} (alpha {a16})"
                );
                let over = rgb[p][k] + (1.0 - a) * bg[k];
                let got_exr = i32::from(linear_to_srgb8(over));
                assert!(
                    (got_exr - want).abs() <= 1,
                    "{name} pixel {p} channel {k}: exr over the background gives {got_exr}, png {want}"
                );
            }
        }
    }
    println!("pixels: {transparent} transparent, {opaque} opaque, {partial} partly covered");
    assert!(transparent > 0 && opaque > 0 && partial > 0);
}

/// The inode of each file: a frame written again is a new file renamed into place, a kept
/// frame keeps its inode.
fn inodes(dir: &Path, names: &[String]) -> Vec<u64> {
    names
        .iter()
        .map(|n| std::fs::metadata(dir.join(n)).unwrap().ino())
        .collect()
}

/// A plain export of 4 frames; then a copy with frame 1 deleted and frame 2 cut to half its
/// bytes (as a full disk or a copy cut short leaves it) resumed: exactly frames 1 and 2 are
/// written (frames 0 and 3 keep their inode), stderr says frame 2 does not decode, and the
/// folder ends byte-identical to the plain export, so the simulation ran through the kept
/// frame 0. A second --resume has nothing to do and touches nothing.
fn resume_rewrites_exactly_the_damaged_frames(name: &str, extension: &str, extra: &[&str]) {
    let root = scratch_dir(name);
    let (plain, resumed) = (root.join("plain"), root.join("resumed"));
    let frames = ["--width", "64", "--height", "64", "--frames", "4"];
    ok(&[&["render", "--out", s(&plain)], &frames[..], extra].concat());
    std::fs::create_dir_all(&resumed).unwrap();
    copy_dir(&plain, &resumed);
    let names: Vec<String> = (0..4)
        .map(|i| format!("frame_{i:05}.{extension}"))
        .collect();
    assert_eq!(
        contents(&plain).iter().map(|c| &c.0).collect::<Vec<_>>(),
        names.iter().collect::<Vec<_>>()
    );
    std::fs::remove_file(resumed.join(&names[1])).unwrap();
    let whole = std::fs::read(resumed.join(&names[2])).unwrap();
    std::fs::write(resumed.join(&names[2]), &whole[..whole.len() / 2]).unwrap();
    let before = inodes(&resumed, &[names[0].clone(), names[3].clone()]);
    let err = ok(&[
        &["render", "--resume", "--out", s(&resumed)],
        &frames[..],
        extra,
    ]
    .concat());
    assert!(
        err.contains(&format!("{} does not decode", names[2])),
        "{err}"
    );
    assert!(err.contains("rendering 2 (1 of them again)"), "{err}");
    assert!(err.contains("wrote 2 frames and kept 2"), "{err}");
    assert_eq!(
        inodes(&resumed, &[names[0].clone(), names[3].clone()]),
        before,
        "a complete frame was written again"
    );
    assert!(
        contents(&resumed) == contents(&plain),
        "the resumed folder differs from the plain export"
    );
    let all = inodes(&resumed, &names);
    let err = ok(&[
        &["render", "--resume", "--out", s(&resumed)],
        &frames[..],
        extra,
    ]
    .concat());
    assert!(err.contains("nothing to render"), "{err}");
    assert_eq!(inodes(&resumed, &names), all);
}

#[test]
fn resume_after_a_deleted_and_a_cut_png_matches_a_plain_export() {
    resume_rewrites_exactly_the_damaged_frames("resume-png", "png", &[]);
}

/// From a cache the frames are independent (nothing is simulated through the kept ones); EXR
/// frames are checked by reading them whole.
#[test]
fn resume_from_a_cache_in_exr_matches_a_plain_export() {
    let root = scratch_dir("resume-cache");
    let cache = root.join("dance.cache");
    ok(&["simulate", "--frames", "4", "--quiet", "--out", s(&cache)]);
    resume_rewrites_exactly_the_damaged_frames(
        "resume-exr-cache",
        "exr",
        &["--format", "exr", "--cache", s(&cache)],
    );
}

#[test]
fn bad_format_exits_2_naming_the_choices() {
    for bad in ["tiff", "PNG16", ""] {
        let o = wisp(&["render", "--format", bad]);
        assert_eq!(o.status.code(), Some(2), "--format {bad:?}: {}", stderr(&o));
        let e = stderr(&o);
        assert!(e.contains("--format"), "{e}");
        assert!(e.contains("png, png16, exr"), "{e}");
        assert!(!e.contains("panicked"));
    }
}
