//! The binary against hostile output conditions (issue 60, items 1 and 7): a `--resume`
//! folder whose frames are damaged in ways decoding the pixels alone misses, a file-size limit
//! (`ulimit -f`) that stops a frame mid-write, and file names with control characters echoed
//! in messages.

use crate::support::hostile::frames::{self, Damage, FOUR_GIB, Kind};
use crate::support::{scratch_dir, small_hairstyle};
use crate::{stderr, wisp};
use std::os::unix::fs::MetadataExt;
use std::path::Path;
use std::process::Command;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The names and contents of the files in `dir`, sorted.
fn contents(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let name = e.file_name().into_string().unwrap();
            (name, std::fs::read(e.path()).unwrap())
        })
        .collect();
    v.sort();
    v
}

/// A plain export of 4 frames, and a copy with frames 0, 1 and 2 damaged as the issue found
/// them kept (PNG: one bit flipped in the `sRGB` chunk; EXR: `pixelAspectRatio` renamed; both:
/// 18 bytes of junk appended, the file grown to 4 GiB). `--resume` names each damaged frame on
/// one line with why, renders exactly those three again (frame 3 keeps its inode), and the
/// folder ends byte-identical to the plain export.
fn resume_rerenders_damaged_frames(name: &str, kind: Kind, format: &str) {
    let root = scratch_dir(name);
    let hair = small_hairstyle(&root);
    let (plain, resumed) = (root.join("plain"), root.join("resumed"));
    let run = |out: &Path, resume: bool| {
        let mut args = vec![
            "render",
            "--width",
            "48",
            "--height",
            "48",
            "--frames",
            "4",
            "--map-res",
            "32",
            "--format",
            format,
            "--hairstyle",
            s(&hair),
            "--out",
            s(out),
        ];
        if resume {
            args.push("--resume");
        }
        let o = wisp(&args);
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        stderr(&o)
    };
    run(&plain, false);
    std::fs::create_dir_all(&resumed).unwrap();
    for (file, bytes) in contents(&plain) {
        std::fs::write(resumed.join(file), bytes).unwrap();
    }
    let extension = if kind == Kind::Exr { "exr" } else { "png" };
    let frame = |i: u32| resumed.join(format!("frame_{i:05}.{extension}"));
    let bytes = std::fs::read(frame(0)).unwrap();
    let first = match kind {
        Kind::Png => {
            let (_, at) = frames::png_chunks(&bytes)
                .into_iter()
                .find(|c| &c.0 == b"sRGB")
                .expect("an sRGB chunk");
            Damage::Flip {
                at: at + 8,
                mask: 1,
            }
        }
        Kind::Exr => {
            let at = bytes
                .windows(16)
                .position(|w| w == b"pixelAspectRatio")
                .unwrap();
            Damage::Flip {
                at: at + 15,
                mask: 0x20,
            }
        }
    };
    first.apply(&frame(0));
    Damage::Append(b"junk after the end".to_vec()).apply(&frame(1));
    Damage::Grow(FOUR_GIB).apply(&frame(2));
    let kept = std::fs::metadata(frame(3)).unwrap().ino();
    let err = run(&resumed, true);
    let why = match kind {
        Kind::Png => "CRC error",
        Kind::Exr => "no `pixelAspectRatio` attribute",
    };
    for (i, says) in [
        (0, why),
        (1, "has 18 bytes after the end of its image"),
        (2, "bytes after the end of its image"),
    ] {
        let name = format!("frame_{i:05}.{extension}");
        let lines: Vec<&str> = err.lines().filter(|l| l.contains(&name)).collect();
        assert_eq!(lines.len(), 1, "{name}: {err}");
        assert!(
            lines[0].contains(says) && lines[0].ends_with("rendering it again"),
            "{name}: {err}"
        );
    }
    assert!(err.contains("rendering 3 (3 of them again)"), "{err}");
    assert_eq!(std::fs::metadata(frame(3)).unwrap().ino(), kept);
    assert!(
        contents(&resumed) == contents(&plain),
        "the resumed folder differs from the plain export"
    );
}

#[test]
fn resume_rerenders_damaged_png_frames() {
    resume_rerenders_damaged_frames("hostile-resume-png", Kind::Png, "png");
}

#[test]
fn resume_rerenders_damaged_exr_frames() {
    resume_rerenders_damaged_frames("hostile-resume-exr", Kind::Exr, "exr");
}

/// Under `ulimit -f 50` (50 blocks: 25,600 bytes in dash's 512-byte blocks, 51,200 in bash's
/// 1,024) a 256 × 256 frame does not fit: the plain run here measures it first (about 63 KB
/// as `png16`, more as `exr`). The write fails with EFBIG, not SIGXFSZ (which killed the
/// process, exit status 153): wisp exits 1 naming the frame, and leaves no temporary file.
/// `wisp export` likewise, naming the first file over the limit.
#[test]
fn a_file_size_limit_is_an_error_naming_the_file() {
    let root = scratch_dir("hostile-ulimit");
    let hair = small_hairstyle(&root);
    const LIMIT_BYTES: u64 = 50 * 1024;
    for format in ["png16", "exr"] {
        let (plain, limited) = (root.join(format), root.join(format!("{format}-limited")));
        let frame_args = |out: &Path| -> Vec<String> {
            [
                "render",
                "--width",
                "256",
                "--height",
                "256",
                "--frames",
                "1",
                "--map-res",
                "32",
                "--quiet",
                "--format",
                format,
                "--hairstyle",
                s(&hair),
                "--out",
                s(out),
            ]
            .map(String::from)
            .to_vec()
        };
        let args = frame_args(&plain);
        let o = wisp(&args.iter().map(String::as_str).collect::<Vec<_>>());
        assert!(o.status.success(), "{}", stderr(&o));
        let extension = if format == "exr" { "exr" } else { "png" };
        let name = format!("frame_00000.{extension}");
        let size = std::fs::metadata(plain.join(&name)).unwrap().len();
        assert!(size > LIMIT_BYTES, "{format}: {size} bytes fit the limit");
        let o = limited_run(&frame_args(&limited));
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{format}: {:?} {err}", o.status);
        assert!(
            err.contains(&format!("{name}: File too large")),
            "{format}: {err}"
        );
        let left: Vec<_> = contents(&limited).into_iter().map(|c| c.0).collect();
        assert!(left.is_empty(), "{format}: left {left:?}");
    }
    let out = root.join("export");
    let o = limited_run(
        &[
            "export",
            "--still",
            "--width",
            "64",
            "--height",
            "64",
            "--out",
            s(&out),
        ]
        .map(String::from),
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "export: {:?} {err}", o.status);
    assert!(
        err.contains("File too large") && err.contains(s(&out)),
        "{err}"
    );
}

/// `wisp args` under `ulimit -f 50` (set in the child's shell, so the test process keeps its
/// own limit).
fn limited_run(args: &[String]) -> std::process::Output {
    Command::new("sh")
        .arg("-c")
        .arg("ulimit -f 50 && exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_wisp"))
        .args(args)
        .output()
        .expect("run sh")
}

/// A scene file and an output path named with an escape sequence (ESC [2J clears a terminal)
/// and a bell: the messages that echo them print each control character as `?`, as the names
/// read from groom files already are, and nothing else of the name is lost.
#[test]
fn control_characters_in_paths_print_as_question_marks() {
    let root = scratch_dir("hostile-control-names");
    let scene = root.join("bad\u{1b}[2Jscene\u{7}.json");
    std::fs::write(&scene, "{\"zzz\": 1}").unwrap();
    let o = wisp(&[
        "render",
        "--scene",
        s(&scene),
        "--out",
        s(&root.join("out")),
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("bad?[2Jscene?.json"), "{err}");
    assert!(!err.chars().any(|c| c.is_control() && c != '\n'), "{err:?}");
    // An output "directory" that is a file, named with an escape sequence.
    let out = root.join("out\u{1b}]0;title\u{7}");
    std::fs::write(&out, b"").unwrap();
    let o = wisp(&["render", "--still", "--frames", "1", "--out", s(&out)]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("out?]0;title?"), "{err}");
    assert!(!err.chars().any(|c| c.is_control() && c != '\n'), "{err:?}");
}
