//! The `wisp` binary under hostile flags, files and output paths, as a user meets it: each run
//! has a time bound (killed after it: a hang detector, not a speed test) and an address-space
//! cap (`ulimit -v`), and must exit with 0 or 2, never panic, and say what is wrong.
//! Plus a sample of the generated inputs of `hostile_loaders` through the real binary.

use crate::support::hostile::{Rng, formats};
use crate::support::scratch_dir;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Kill a run after this long.
const TIME_LIMIT: Duration = Duration::from_secs(60);
/// Address-space cap of a run in KiB (`ulimit -v`): 3 GiB, with `--max-memory-gb 1` on the
/// runs that render, so an accepted run must keep within its own budget.
const ADDRESS_SPACE_KIB: u64 = 3 << 20;

struct Run {
    code: Option<i32>,
    stderr: String,
    timed_out: bool,
}

impl Run {
    fn says(&self, needle: &str) -> bool {
        self.stderr.contains(needle)
    }
}

/// Runs `wisp args` under the address-space cap and the time limit, in `dir`.
fn wisp(args: &[&str], dir: &Path) -> Run {
    let err_path = dir.join(format!("stderr-{}.txt", std::process::id()));
    let err = std::fs::File::create(&err_path).expect("stderr file");
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v {ADDRESS_SPACE_KIB} && exec \"$0\" \"$@\""
        ))
        .arg(env!("CARGO_BIN_EXE_wisp"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(err)
        .spawn()
        .expect("spawn sh");
    let start = Instant::now();
    let (code, timed_out) = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break (status.code(), false);
        }
        if start.elapsed() > TIME_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            break (None, true);
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let stderr = std::fs::read_to_string(&err_path).unwrap_or_default();
    Run {
        code,
        stderr,
        timed_out,
    }
}

/// Runs each case and collects what went wrong: a hang, a panic, an exit code other than
/// expected, or a message without the expected words.
fn expect_all(dir: &Path, cases: &[(Vec<String>, i32, &str)]) {
    let mut failures = Vec::new();
    for (args, want, needle) in cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let r = wisp(&args, dir);
        let problem = if r.timed_out {
            Some(format!("did not finish within {} s", TIME_LIMIT.as_secs()))
        } else if r.says("panicked") {
            Some("panicked".to_string())
        } else if r.code != Some(*want) {
            Some(format!("exit {:?}, expected {want}", r.code))
        } else if !r.says(needle) {
            Some(format!("the message does not say {needle:?}"))
        } else {
            None
        };
        if let Some(p) = problem {
            failures.push(format!(
                "wisp {}: {p}\n  stderr: {}",
                args.join(" "),
                r.stderr.trim()
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

fn args(s: &str) -> Vec<String> {
    s.split_whitespace().map(str::to_string).collect()
}

/// A tiny, fast render: still head, one small frame, a 1 GB budget.
fn quick(extra: &str, out: &Path) -> Vec<String> {
    let mut a = args("render --still --frames 1 --width 32 --height 32 --max-memory-gb 1 --quiet");
    a.extend(args(extra));
    a.push("--out".into());
    a.push(out.display().to_string());
    a
}

#[test]
fn hostile_flags_exit_2_naming_the_flag() {
    let dir = scratch_dir("hostile-cli-flags");
    let cases: Vec<(Vec<String>, i32, &str)> = vec![
        (args("render --frames 0"), 2, "--frames"),
        (args("render --frames 100001"), 2, "--frames"),
        (args("render --width 8193"), 2, "--width"),
        (args("render --fps 0"), 2, "--fps"),
        (args("render --fps -1"), 2, "--fps"),
        (args("render --fps 1e9"), 2, "at most 1000"),
        (args("render --fps nan"), 2, "--fps"),
        (args("render --speed -inf"), 2, "must be finite"),
        (args("render --speed 0"), 2, "--speed"),
        (
            args("render --contact-mm -1"),
            2,
            "must be 0 (off) to 1000 mm",
        ),
        (
            args("render --contact-mm 5000"),
            2,
            "must be 0 (off) to 1000 mm",
        ),
        (args("render --contact-mm nan"), 2, "--contact-mm"),
        (args("render --segment-pieces 0"), 2, "--segment-pieces"),
        (args("render --segment-pieces 17"), 2, "not in 1..=16"),
        (args("render --segment-pieces 1.5"), 2, "--segment-pieces"),
        (
            args("render --volume-cell-mm 0"),
            2,
            "must be 0.5 to 100 mm",
        ),
        (args("render --volume-cell-mm inf"), 2, "--volume-cell-mm"),
        (args("render --volume-paths 10"), 2, "--volume-paths"),
        (args("render --volume-paths 1e12"), 2, "--volume-paths"),
        (args("render --volume-bins 17"), 2, "not in 1..=16"),
        (args("render --volume-bins 0"), 2, "not in 1..=16"),
        (args("render --speed 2000"), 2, "at most 1000"),
        (
            args("render --speed 1e308"),
            2,
            "1e308 is outside the range",
        ),
        (args("render --start-s nan"), 2, "--start-s"),
        (
            args("render --start-s 1e400"),
            2,
            "1e400 is outside the range",
        ),
        (args("render --light-dir 1,2"), 2, "--light-dir"),
        (args("render --map-res 3"), 2, "--map-res"),
        (args("render --map-hz 1001"), 2, "--map-hz"),
        (args("bench --fps 0"), 2, "--fps"),
        // A strand file of a format wisp reads is read as one: a missing one is named.
        (
            args("render --hairstyle missing-groom.ply"),
            2,
            "missing-groom.ply: cannot read",
        ),
        (
            args("render --hairstyle missing-strands.data"),
            2,
            "missing-strands.data: cannot read",
        ),
        (
            args("render --hairstyle strands.abc"),
            2,
            "unsupported hair format .abc; wisp reads .json, .tfx, .hair, .ply, .data",
        ),
        (
            args("render --hairstyle head.obj"),
            2,
            "unsupported hair format .obj",
        ),
        (args("render --max-memory-gb 0"), 2, "--max-memory-gb"),
        (args("render --max-memory-gb nan"), 2, "--max-memory-gb"),
        (
            args("render --max-work-cpu-min -5"),
            2,
            "--max-work-cpu-min",
        ),
        (args("--threads 0 render"), 2, "--threads"),
        (args("--threads 1025 render"), 2, "--threads"),
        (args("render --no-such-flag"), 2, "--no-such-flag"),
        (args("render --head-joint 3"), 2, "--animation"),
        (args("render --head-scale 1"), 2, "--head-offset"),
        (args("render --head-offset 0,0,0"), 2, "--head-scale"),
        (
            args("render --head-scale -1 --head-offset 0,0,0"),
            2,
            "--head-scale",
        ),
        (
            args("render --head-offset 0,nan,0 --head-scale 1"),
            2,
            "--head-offset",
        ),
        // A fit half a metre above the mannequin's head joint: the roots float off its head.
        (
            args("render --head-scale 1 --head-offset 0,0.5,0 --frames 1 --width 32 --height 32"),
            2,
            "do not lie on the head mesh",
        ),
        (args("bench --threads-list 1,100000"), 2, "--threads-list"),
        (args("bench --threads-list 1,200"), 2, "per core"),
        (args("fiber tables --eta -1"), 2, "--eta"),
        (args("fiber tables --beta-r-deg -3"), 2, "--beta-r-deg"),
        (args("fiber tables --eccentricity -1"), 2, "--eccentricity"),
        (args("fiber tables --sigma-a -1,0,0"), 2, "--sigma-a"),
        (args("fiber tables --sigma-a 1,2"), 2, "--sigma-a"),
        (
            args("fiber tables --theta-step-deg -5"),
            2,
            "--theta-step-deg",
        ),
        (
            args("fiber tables --theta-step-deg 1e308"),
            2,
            "--theta-step-deg",
        ),
        (
            args("fiber eval --theta-i-deg 91 --phi-i-deg 0 --theta-o-deg 0 --phi-o-deg 0"),
            2,
            "--theta-i-deg",
        ),
        (args("fiber eval --theta-i-deg 0"), 2, "--phi-i-deg"),
        // Accepted: a negative shift is a legal value.
        (
            args("fiber tables --alpha-r-deg -7.5 --theta-step-deg 45"),
            0,
            "",
        ),
    ];
    expect_all(&dir, &cases);
}

#[test]
fn work_implied_by_flags_is_bounded() {
    let dir = scratch_dir("hostile-cli-work");
    let out = dir.join("out");
    // --start-s 1e12 used to simulate every step from 0 (about 50 ms per simulated second).
    let mut start = args("render --frames 1 --width 32 --height 32 --start-s 1e12 --out");
    start.push(out.display().to_string());
    // 1,000 threads on 2 cores took 36 s for 2 small frames.
    let mut threads = args("--threads 1000 render --still --frames 2 --width 32 --height 32 --out");
    threads.push(out.display().to_string());
    let cases = vec![
        (start, 0, "into one 8.000 s loop"),
        (threads, 0, "more than 4 per core"),
    ];
    expect_all(&dir, &cases);
}

/// Writes a hairstyle: the smooth preset with one edit.
fn hairstyle_file(dir: &Path, name: &str, edit: impl FnOnce(&mut serde_json::Value)) -> PathBuf {
    let mut v: serde_json::Value = serde_json::from_str(wisp::hairstyle::SMOOTH_JSON).unwrap();
    edit(&mut v);
    let p = dir.join(name);
    std::fs::write(&p, v.to_string()).unwrap();
    p
}

#[test]
fn hostile_files_are_refused_with_exit_2() {
    let dir = scratch_dir("hostile-cli-files");
    let out = dir.join("out");
    let fifo = dir.join("pipe.json");
    let have_fifo = Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success());
    let sparse = dir.join("sparse.glb");
    std::fs::File::create(&sparse)
        .unwrap()
        .set_len(300 << 20)
        .unwrap();
    let empty = dir.join("empty.json");
    std::fs::write(&empty, "").unwrap();
    let trailing = dir.join("trailing.json");
    std::fs::write(
        &trailing,
        format!("{} trailing", wisp::hairstyle::SMOOTH_JSON),
    )
    .unwrap();
    let bom = dir.join("bom.json");
    std::fs::write(
        &bom,
        [
            b"\xEF\xBB\xBF".as_slice(),
            wisp::hairstyle::SMOOTH_JSON.as_bytes(),
        ]
        .concat(),
    )
    .unwrap();
    let array = hairstyle_file(&dir, "array.json", |v| {
        v["guides"] = serde_json::json!([1, 2])
    });
    let huge = hairstyle_file(&dir, "huge.json", |v| {
        v["guides"]["length_m"] = serde_json::json!(1e308)
    });
    let maxima = hairstyle_file(&dir, "maxima.json", |v| {
        v["wisps"] =
            serde_json::json!({"count": 100000, "radius_m": 0.013, "strands_per_wisp": 20});
        v["strands"] = serde_json::json!({"points": 20, "fibers_per_strand": 30});
    });
    let links = hairstyle_file(&dir, "links.json", |v| {
        v["wisps"] = serde_json::json!({"count": 100000, "radius_m": 0.013, "strands_per_wisp": 1});
        v["guides"]["links"] = serde_json::json!(256);
        v["strands"] = serde_json::json!({"points": 2, "fibers_per_strand": 30});
    });
    let loop_link = dir.join("loop.json");
    let _ = std::os::unix::fs::symlink(&loop_link, &loop_link);
    let s = |p: &Path| p.display().to_string();
    let mut cases: Vec<(Vec<String>, i32, &str)> = vec![
        (quick("--hairstyle /dev/zero", &out), 2, "character device"),
        (
            quick(&format!("--hairstyle {}", s(&dir)), &out),
            2,
            "is a directory",
        ),
        (
            quick(&format!("--hairstyle {}", s(&empty)), &out),
            2,
            "empty.json",
        ),
        (
            quick(&format!("--hairstyle {}", s(&trailing)), &out),
            2,
            "after the JSON value",
        ),
        (
            quick(&format!("--hairstyle {}", s(&array)), &out),
            2,
            "`guides`: must be an object",
        ),
        (
            quick(&format!("--hairstyle {}", s(&huge)), &out),
            2,
            "outside the range of a 32-bit float",
        ),
        (
            quick(&format!("--hairstyle {}", s(&loop_link)), &out),
            2,
            "loop.json",
        ),
        (
            quick("--hairstyle wavy", &out),
            2,
            "not a preset (smooth, curly, dense)",
        ),
        (quick("--hairstyle /no/such.json", &out), 2, "no such file"),
        (quick(&format!("--hairstyle {}", s(&bom)), &out), 0, ""),
        // The documented maxima: refused by the budget before anything is allocated.
        (
            args(&format!(
                "render --hairstyle {} --out {}",
                s(&maxima),
                s(&out)
            )),
            2,
            "the largest part is the light map",
        ),
        (
            args(&format!(
                "render --hairstyle {} --out {}",
                s(&links),
                s(&out)
            )),
            2,
            "the largest part is the simulation",
        ),
        (
            args(&format!("render --animation /dev/zero --out {}", s(&out))),
            2,
            "character device",
        ),
        (
            args(&format!(
                "render --animation {} --out {}",
                s(&sparse),
                s(&out)
            )),
            2,
            "over the 268.4 MB limit",
        ),
        (
            args(&format!("render --animation {} --out {}", s(&dir), s(&out))),
            2,
            "is a directory",
        ),
    ];
    if have_fifo {
        cases.push((
            quick(&format!("--hairstyle {}", s(&fifo)), &out),
            2,
            "named pipe",
        ));
    } else {
        println!("skipped: the FIFO case (mkfifo is not available)");
    }
    expect_all(&dir, &cases);
}

#[test]
fn motion_errors_name_the_flag_that_fixes_them() {
    let dir = scratch_dir("hostile-cli-motion");
    let out = dir.join("out");
    // A clip whose only node is not named like a head.
    let clip = serde_json::json!({
        "asset": {"version": "2.0"},
        "nodes": [{"name": "Root"}],
        "buffers": [{"byteLength": 8, "uri": "data:application/octet-stream;base64,AAAAAAAAgD8="}],
        "bufferViews": [{"buffer": 0, "byteLength": 8}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 2, "type": "SCALAR"}],
        "animations": [{"name": "Dance", "samplers": [{"input": 0, "output": 0}],
                        "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}]}]
    });
    let p = dir.join("nohead.gltf");
    std::fs::write(&p, clip.to_string()).unwrap();
    let s = p.display().to_string();
    let o = out.display().to_string();
    let cases = vec![
        (
            args(&format!("render --animation {s} --out {o}")),
            2,
            "choose the head with --head-joint",
        ),
        (
            args(&format!("render --animation {s} --clip Walk --out {o}")),
            2,
            "give one of these to --clip",
        ),
    ];
    expect_all(&dir, &cases);
    let r = wisp(
        &args(&format!("render --animation {s} --out {o}"))
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>(),
        &dir,
    );
    assert!(!r.says("MotionOptions"), "{}", r.stderr);
}

#[test]
fn hostile_output_paths_exit_2() {
    let dir = scratch_dir("hostile-cli-out");
    let file = dir.join("a-file");
    std::fs::write(&file, "x").unwrap();
    let s = |p: &Path| p.display().to_string();
    let cases = vec![
        (quick("", &file), 2, "exists and is not a directory"),
        (
            quick("", Path::new("/dev/null")),
            2,
            "exists and is not a directory",
        ),
        (
            quick("", &file.join("below")),
            2,
            "cannot create the output directory",
        ),
        (args(&format!("fiber plot --out {}", s(&file))), 2, "a-file"),
        (
            args(&format!("bench --json {}", s(&dir))),
            2,
            "is a directory, not a file name",
        ),
        (
            args(&format!("bench --json {}", s(&file.join("b.json")))),
            2,
            "does not exist",
        ),
        (
            args(&format!("play --screenshot {}", s(&dir))),
            2,
            "is a directory, not a file name",
        ),
    ];
    expect_all(&dir, &cases);
}

#[test]
fn a_second_export_removes_what_the_first_left() {
    let dir = scratch_dir("hostile-cli-leftovers");
    let out = dir.join("frames");
    std::fs::create_dir_all(&out).unwrap();
    // What a longer export killed during frame 3 leaves, and a file of the user's.
    for i in 0..3 {
        std::fs::write(out.join(format!("frame_{i:05}.png")), "old").unwrap();
    }
    std::fs::write(out.join("frame_00003.png.tmp"), "half").unwrap();
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let mut a = args("render --still --frames 2 --width 32 --height 32 --max-memory-gb 1 --out");
    a.push(out.display().to_string());
    let r = wisp(&a.iter().map(String::as_str).collect::<Vec<_>>(), &dir);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert!(r.says("removed from"), "{}", r.stderr);
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["frame_00000.png", "frame_00001.png", "notes.txt"]);
    let png = std::fs::read(out.join("frame_00001.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG", "frame 1 was rewritten");
}

#[test]
fn a_directory_named_like_a_frame_is_reported_before_the_work() {
    let dir = scratch_dir("hostile-cli-in-the-way");
    let out = dir.join("frames");
    std::fs::create_dir_all(out.join("frame_00000.png")).unwrap();
    let r = wisp(
        &quick("", &out)
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>(),
        &dir,
    );
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert!(r.says("frame_00000.png is in the way"), "{}", r.stderr);
}

/// Issue 10's hostile caches and flags through the binary: each exits 2 naming what is wrong
/// (or 0 where there is nothing wrong: a shard with no frames), never a panic or a hang.
#[test]
fn hostile_caches_and_cache_flags_exit_2_naming_the_problem() {
    use crate::support::hostile::cache::{SEED_HAIRSTYLE, record_at, reseal, seed};
    let dir = scratch_dir("hostile-cli-cache");
    let out = dir.join("out");
    let hair = dir.join("min.json");
    std::fs::write(&hair, SEED_HAIRSTYLE).unwrap();
    let good = dir.join("run.wcache");
    std::fs::write(&good, seed()).unwrap();
    let b = seed();
    std::fs::write(dir.join("short.wcache"), &b[..b.len() - 5]).unwrap();
    let mut v = b.clone();
    v[8] = 9;
    reseal(&mut v);
    std::fs::write(dir.join("v9.wcache"), &v).unwrap();
    let mut nan = b.clone();
    let (at, _) = record_at(&nan, 2).unwrap();
    nan[at + 8..at + 12].copy_from_slice(&f32::NAN.to_le_bytes());
    reseal(&mut nan);
    std::fs::write(dir.join("nan.wcache"), &nan).unwrap();
    let mut flipped = b.clone();
    flipped[at + 20] ^= 4;
    std::fs::write(dir.join("flipped.wcache"), &flipped).unwrap();
    std::fs::create_dir_all(dir.join("adir.wcache")).unwrap();
    let r = |extra: &str| {
        let mut a = args(&format!(
            "render --width 32 --height 32 --max-memory-gb 1 --quiet --hairstyle {} --out {}",
            hair.display(),
            out.display()
        ));
        a.extend(args(extra));
        a
    };
    let s = |extra: &str| args(&format!("simulate --frames 1 --quiet {extra}"));
    let cases: Vec<(Vec<String>, i32, &str)> = vec![
        (
            r("--cache missing.wcache"),
            2,
            "missing.wcache: cannot read",
        ),
        (r("--cache adir.wcache"), 2, "adir.wcache: is a directory"),
        (r("--cache /dev/zero"), 2, "character device"),
        (r("--cache short.wcache"), 2, "short.wcache: truncated"),
        (r("--cache v9.wcache"), 2, "version is 9"),
        (r("--cache nan.wcache"), 2, "frame 1: particle 0 is at [NaN"),
        (r("--cache flipped.wcache"), 2, "frame 1: checksum"),
        (
            args(&format!(
                "render --quiet --cache run.wcache --hairstyle curly --out {}",
                out.display()
            )),
            2,
            "not for this hairstyle \"curly\"",
        ),
        (
            r("--cache run.wcache --still"),
            2,
            "not with this motion, --still",
        ),
        (r("--cache run.wcache --speed 2"), 2, "speed 2"),
        (r("--cache run.wcache --shard 3/2"), 2, "I must be in 1..=2"),
        (r("--cache run.wcache --shard 0/2"), 2, "numbered from 1"),
        (
            r("--cache run.wcache --shard 1/2/3"),
            2,
            "not a whole number",
        ),
        (r("--shard 1/2"), 2, "--cache"),
        (r("--first-frame 1"), 2, "--cache"),
        (r("--cache run.wcache --fps 24"), 2, "cannot be used with"),
        (
            r("--cache run.wcache --start-s 1"),
            2,
            "cannot be used with",
        ),
        (r("--cache run.wcache --no-sim"), 2, "cannot be used with"),
        (
            r("--cache run.wcache --first-frame 3"),
            2,
            "holds frames 0 to 2",
        ),
        (
            r("--cache run.wcache --first-frame 1 --frames 3"),
            2,
            "--frames 3",
        ),
        (
            r("--cache run.wcache --first-frame 100000"),
            2,
            "--first-frame",
        ),
        (s("--out adir.wcache"), 2, "adir.wcache: is a directory"),
        (s("--out /dev/null"), 2, "not a regular file"),
        (s("--out no/such/run.wcache"), 2, "folder does not exist"),
        (s("--out"), 2, "--out"),
    ];
    expect_all(&dir, &cases);
    // More shards than frames: the empty shard has nothing to do and says so.
    let empty = r("--cache run.wcache --shard 1/7");
    let mut verbose = empty.clone();
    verbose.retain(|a| a != "--quiet");
    expect_all(&dir, &[(verbose, 0, "has no frames")]);
}

/// Generated inputs through the binary: a sample of `hostile_loaders`' mutated hairstyles,
/// glTF files and simulation caches, rendered (when accepted) as small frames.
#[test]
fn generated_inputs_through_the_binary() {
    let dir = scratch_dir("hostile-cli-generated");
    let out = dir.join("out");
    let all = formats::all();
    let mut failures = Vec::new();
    let mut runs = 0;
    for i in 0..48u64 {
        let fi = (i % 3) as usize; // hairstyles, .glb, .gltf + .bin
        let format = &all[fi];
        let seed = 0xC11_0008 + i;
        let mut rng = Rng::new(seed);
        let (case, what) = formats::mutated(format, &mut rng);
        let case_dir = dir.join(format!("case-{i}"));
        std::fs::create_dir_all(&case_dir).unwrap();
        let entry = case.write(&case_dir).unwrap();
        let flag = if fi == 0 {
            "--hairstyle"
        } else {
            "--animation"
        };
        let mut a = args("render --frames 1 --width 32 --height 32 --max-memory-gb 1 --quiet");
        if fi == 0 {
            a.push("--still".into());
        }
        a.extend([flag.to_string(), entry.display().to_string()]);
        a.extend(["--out".to_string(), out.display().to_string()]);
        let r = wisp(&a.iter().map(String::as_str).collect::<Vec<_>>(), &case_dir);
        runs += 1;
        let bad = if r.timed_out {
            Some("did not finish in time".to_string())
        } else if r.says("panicked") || !matches!(r.code, Some(0) | Some(2)) {
            Some(format!("exit {:?}: {}", r.code, r.stderr.trim()))
        } else {
            None
        };
        if let Some(b) = bad {
            failures.push(format!(
                "{} seed {seed} ({}): {b}",
                format.name,
                what.join("; ")
            ));
        }
    }
    // Mutated simulation caches, rendered with the seed's hairstyle.
    let hair = dir.join("min.json");
    std::fs::write(&hair, crate::support::hostile::cache::SEED_HAIRSTYLE).unwrap();
    let caches = all
        .iter()
        .find(|f| f.name == "simulation cache")
        .expect("the cache format");
    for i in 0..12u64 {
        let seed = 0xC12_0008 + i;
        let (case, what) = formats::mutated(caches, &mut Rng::new(seed));
        let case_dir = dir.join(format!("cache-{i}"));
        std::fs::create_dir_all(&case_dir).unwrap();
        let entry = case.write(&case_dir).unwrap();
        let mut a = args("render --width 32 --height 32 --max-memory-gb 1 --quiet");
        for (flag, path) in [("--hairstyle", &hair), ("--cache", &entry), ("--out", &out)] {
            a.extend([flag.to_string(), path.display().to_string()]);
        }
        let r = wisp(&a.iter().map(String::as_str).collect::<Vec<_>>(), &case_dir);
        runs += 1;
        if r.timed_out || r.says("panicked") || !matches!(r.code, Some(0) | Some(2)) {
            failures.push(format!(
                "cache seed {seed} ({}): exit {:?}: {}",
                what.join("; "),
                r.code,
                r.stderr.trim()
            ));
        }
    }
    assert!(runs >= 60);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Generated command lines: random subsets of the render flags with hostile and edge values,
/// under a 1 GB and 1 CPU-minute budget. Each ends with 0 or 2, never a panic or a hang.
#[test]
fn generated_flag_combinations() {
    let dir = scratch_dir("hostile-cli-generated-flags");
    let dance = Path::new(env!("CARGO_MANIFEST_DIR")).join("animations/dance.glb");
    let dance = dance.display().to_string();
    let table: Vec<(&str, Vec<&str>)> = vec![
        ("--frames", vec!["0", "1", "2", "100001", "-1", "1e3", "x"]),
        (
            "--fps",
            vec!["0", "-1", "1e-30", "0.001", "1000", "1001", "nan", "inf"],
        ),
        (
            "--start-s",
            vec!["-1e300", "1e300", "nan", "-0", "1e12", "3.5"],
        ),
        (
            "--speed",
            vec!["-inf", "0", "1e-30", "1000", "1e308", "-1", "0.25"],
        ),
        (
            "--width",
            vec!["15", "16", "8192", "8193", "-16", "1e3", "64"],
        ),
        ("--height", vec!["15", "16", "8192", "8193", "-16", "48"]),
        ("--map-res", vec!["3", "4", "1024", "1025", "33"]),
        (
            "--light-dir",
            vec![
                "0,0,0",
                "1e30,1e30,1e30",
                "1,nan,0",
                "-1,-1,-1",
                "1,2",
                "a,b,c",
            ],
        ),
        (
            "--shading",
            vec!["dual", "single", "kajiya-kay", "phong", ""],
        ),
        (
            "--hairstyle",
            vec!["smooth", "curly", "wavy", "", "/dev/null"],
        ),
        ("--animation", vec!["/dev/zero", dance.as_str(), ""]),
        ("--clip", vec!["Dance", "", "#0"]),
        ("--head-joint", vec!["0", "Head", "99999999999999999999"]),
    ];
    let switches = ["--still", "--no-sim", "--no-self-collision"];
    let runs = std::env::var("WISP_HOSTILE_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(40u64);
    let (mut failures, mut accepted) = (Vec::new(), 0);
    for i in 0..runs {
        let seed = 0xF1A6_0008 + i;
        let mut rng = Rng::new(seed);
        let mut a = args("render --max-memory-gb 1 --max-work-cpu-min 1 --quiet");
        for (flag, values) in &table {
            if rng.chance(0.25) {
                a.push(flag.to_string());
                a.push(rng.pick(values).to_string());
            }
        }
        for s in switches {
            if rng.chance(0.2) {
                a.push(s.to_string());
            }
        }
        // Keep accepted runs small unless the generator chose a size.
        if !a.iter().any(|x| x == "--frames") {
            a.extend(args("--frames 1"));
        }
        if !a.iter().any(|x| x == "--width") {
            a.extend(args("--width 32"));
        }
        if !a.iter().any(|x| x == "--height") {
            a.extend(args("--height 32"));
        }
        a.push("--out".into());
        a.push(dir.join("out").display().to_string());
        let r = wisp(&a.iter().map(String::as_str).collect::<Vec<_>>(), &dir);
        accepted += usize::from(r.code == Some(0));
        if r.timed_out || r.says("panicked") || !matches!(r.code, Some(0) | Some(2)) {
            failures.push(format!(
                "seed {seed}: wisp {}: exit {:?}, timed out {}: {}",
                a.join(" "),
                r.code,
                r.timed_out,
                r.stderr.trim()
            ));
        }
    }
    println!("{runs} command lines, {accepted} accepted");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
