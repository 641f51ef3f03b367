//! Issue 10 end to end, through the binary and the shipped scripts, as CI runs it: `wisp
//! simulate` a short clip, render it as two shards run at once by the local runner
//! (`deploy/local/render-shards.sh`), with GNU parallel and with its `xargs -P` fallback, and
//! compare every PNG byte for byte with one `wisp render` of the same clip. Then the checks of
//! the deploy files that this machine can run: `bash -n`, shellcheck, and the Kubernetes
//! manifests against the published schemas and the rules schemas cannot state
//! (`deploy/check.py`). A missing tool prints "skipped: ..." and that check does not run.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const WISP: &str = env!("CARGO_BIN_EXE_wisp");

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("scratch dir");
    d
}

fn run(cmd: &mut Command) -> Output {
    let out = cmd.output().expect("spawn");
    if !out.status.success() {
        panic!(
            "{cmd:?} failed ({}):\n{}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
    }
    out
}

fn has(tool: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {tool}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// The frames of a folder: name -> bytes.
fn frames(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .expect("frames folder")
        .map(|e| {
            let e = e.expect("entry");
            let name = e.file_name().to_string_lossy().into_owned();
            (name, std::fs::read(e.path()).expect("frame"))
        })
        .collect();
    v.sort();
    v
}

/// The scene of the clip: the defaults (smooth hair, the dance, self-collision) in a small
/// image with a coarse map, so the whole test takes seconds.
const SCENE: [&str; 6] = ["--width", "40", "--height", "40", "--map-res", "64"];
const FRAMES: usize = 5;

#[test]
fn simulate_then_two_local_shards_give_the_bytes_of_one_render() {
    let dir = scratch("cache-cli-shards");
    let cache = dir.join("run.wcache");
    // The clip starts 0.5 s into the dance, so the cache also carries the warm-up.
    let clip = ["--frames", "5", "--start-s", "0.5"];
    run(Command::new(WISP)
        .args(["--threads", "2", "simulate", "--quiet", "--out"])
        .arg(&cache)
        .args(clip)
        .args(SCENE));
    let single = dir.join("single");
    run(Command::new(WISP)
        .args(["--threads", "2", "render", "--quiet", "--out"])
        .arg(&single)
        .args(clip)
        .args(SCENE));
    let want = frames(&single);
    assert_eq!(want.len(), FRAMES);
    assert!(
        want.windows(2).any(|w| w[0].1 != w[1].1),
        "the frames are all alike"
    );

    let mut runners = vec!["xargs"];
    if has("parallel") {
        runners.push("parallel");
    } else {
        println!("skipped: the GNU parallel runner (parallel is not installed; xargs -P ran)");
    }
    for runner in runners {
        let out = dir.join(format!("shards-{runner}"));
        let r = run(Command::new(repo().join("deploy/local/render-shards.sh"))
            .env("WISP", WISP)
            .env("WISP_RUNNER", runner)
            .env("WISP_JOBS", "2")
            .arg("2")
            .arg(&cache)
            .arg(&out)
            .arg("--quiet")
            .args(SCENE));
        let said = String::from_utf8_lossy(&r.stderr);
        assert!(
            said.contains(&format!("2 at once with 1 threads each ({runner})")),
            "{said}"
        );
        let got = frames(&out);
        let names = |v: &[(String, Vec<u8>)]| v.iter().map(|f| f.0.clone()).collect::<Vec<_>>();
        assert_eq!(names(&got), names(&want), "{runner}: other file names");
        for ((name, a), (_, b)) in want.iter().zip(&got) {
            assert!(a == b, "{runner}: {name} differs from the single run");
        }
    }
}

/// Light paths built once per slot of motion (`--volume-hz`) are built from the slot's first
/// frame in every run: a cache render that starts inside a slot (`--first-frame`, as a shard
/// does) sets that frame's hair first, and gives the bytes of a render from the start. At 6
/// builds a second, the clip's frames 0.5–0.63 s lie in one slot (0.5–0.67 s), so frames 2
/// and 3 are read through a build two and three frames old.
#[test]
fn a_cache_render_inside_a_light_path_slot_gives_the_bytes_of_one_render() {
    let dir = scratch("cache-cli-path-slots");
    let cache = dir.join("run.wcache");
    let clip = ["--frames", "5", "--start-s", "0.5"];
    let paths = [
        "--quality",
        "final",
        "--volume-hz",
        "6",
        "--volume-paths",
        "20000",
    ];
    // Large enough that the light paths' change shows in 8-bit pixels.
    let scene = ["--width", "120", "--height", "120", "--map-res", "64"];
    run(Command::new(WISP)
        .args(["--threads", "2", "simulate", "--quiet", "--out"])
        .arg(&cache)
        .args(clip)
        .args(scene));
    let single = dir.join("single");
    run(Command::new(WISP)
        .args(["--threads", "2", "render", "--quiet", "--out"])
        .arg(&single)
        .args(clip)
        .args(scene)
        .args(paths));
    let part = dir.join("part");
    run(Command::new(WISP)
        .args(["--threads", "1", "render", "--quiet", "--cache"])
        .arg(&cache)
        .args(["--first-frame", "2", "--frames", "2", "--out"])
        .arg(&part)
        .args(scene)
        .args(paths));
    let want = frames(&single);
    let got = frames(&part);
    assert_eq!(got.len(), 2);
    for (name, bytes) in &got {
        let same = want.iter().find(|(n, _)| n == name).map(|(_, b)| b);
        assert!(same == Some(bytes), "{name} differs from the single run");
    }
    // The paths a build old read otherwise than a build of their own would: without the
    // slot's first frame, the part's frames would differ (a render of frame 2 alone at every
    // frame's rate is not the bytes).
    let own = dir.join("own");
    run(Command::new(WISP)
        .args(["--threads", "1", "render", "--quiet", "--cache"])
        .arg(&cache)
        .args(["--first-frame", "2", "--frames", "1", "--out"])
        .arg(&own)
        .args(scene)
        .args([
            "--quality",
            "final",
            "--volume-hz",
            "0",
            "--volume-paths",
            "20000",
        ]));
    assert_ne!(
        frames(&own)[0].1,
        got[0].1,
        "frame 2 read through its own build"
    );
}

/// A failing shard makes the runner fail, with wisp's message (here: the cache was made for
/// another hairstyle), under either runner.
#[test]
fn the_local_runner_fails_when_a_shard_fails() {
    let dir = scratch("cache-cli-runner-fails");
    let cache = dir.join("run.wcache");
    run(Command::new(WISP)
        .args(["simulate", "--quiet", "--still", "--out"])
        .arg(&cache)
        .args(SCENE));
    let mut runners = vec!["xargs"];
    if has("parallel") {
        runners.push("parallel");
    }
    for runner in runners {
        let out = Command::new(repo().join("deploy/local/render-shards.sh"))
            .env("WISP", WISP)
            .env("WISP_RUNNER", runner)
            .args(["2"])
            .arg(&cache)
            .arg(dir.join("out"))
            .args(["--still", "--hairstyle", "curly"])
            .output()
            .expect("spawn");
        let said = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{runner}: {said}");
        assert!(
            said.contains("not for this hairstyle \"curly\""),
            "{runner}: {said}"
        );
        assert!(said.contains("a shard failed"), "{runner}: {said}");
    }
    let out = Command::new(repo().join("deploy/local/render-shards.sh"))
        .env("WISP", WISP)
        .args(["0", "run.wcache", "out"])
        .output()
        .expect("spawn");
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("SHARDS must be a whole number"));
}

/// Re-lighting from the cache: another light renders without simulating and says that the
/// hair moves as simulated under the cache's light.
#[test]
fn another_light_from_the_cache_gives_the_bytes_of_a_run_in_that_light() {
    // The motion does not depend on the light (self-collision reads the simulator's own
    // density grid), so a cache simulated in the default light and rendered in another gives
    // the PNGs of a single run in that light.
    let dir = scratch("cache-cli-relight");
    let cache = dir.join("run.wcache");
    run(Command::new(WISP)
        .args(["simulate", "--quiet", "--frames", "2", "--out"])
        .arg(&cache)
        .args(SCENE));
    let look = ["--light-dir", "1,-0.5,0.3", "--shading", "kajiya-kay"];
    let r = run(Command::new(WISP)
        .args(["render", "--cache"])
        .arg(&cache)
        .args(look)
        .arg("--out")
        .arg(dir.join("relit"))
        .args(SCENE));
    let said = String::from_utf8_lossy(&r.stderr);
    assert!(said.contains("wrote 2 frames"), "{said}");
    run(Command::new(WISP)
        .args(["render", "--quiet", "--frames", "2"])
        .args(look)
        .arg("--out")
        .arg(dir.join("single"))
        .args(SCENE));
    let (relit, single) = (frames(&dir.join("relit")), frames(&dir.join("single")));
    assert_eq!(relit.len(), 2);
    assert_eq!(
        relit, single,
        "relit frames differ from a single run in that light"
    );
}

fn scripts() -> Vec<PathBuf> {
    let mut v = vec![repo().join(".ci/run")];
    for sub in ["deploy/local", "deploy/slurm"] {
        for e in std::fs::read_dir(repo().join(sub)).expect("deploy folder") {
            v.push(e.expect("entry").path());
        }
    }
    v.sort();
    v
}

#[test]
fn deploy_scripts_pass_bash_n_and_shellcheck() {
    let scripts = scripts();
    assert!(scripts.len() >= 4, "{scripts:?}");
    for s in &scripts {
        let out = Command::new("bash")
            .arg("-n")
            .arg(s)
            .output()
            .expect("bash");
        assert!(
            out.status.success(),
            "bash -n {}: {}",
            s.display(),
            String::from_utf8_lossy(&out.stderr)
        );
    }
    if !has("shellcheck") {
        println!("skipped: shellcheck (not installed; .ci/run installs it from Debian)");
        return;
    }
    let out = Command::new("shellcheck")
        .args(&scripts)
        .output()
        .expect("shellcheck");
    assert!(
        out.status.success(),
        "shellcheck:\n{}",
        String::from_utf8_lossy(&out.stdout)
    );
}

#[test]
fn kubernetes_manifests_pass_the_schema_and_the_rules() {
    let yaml = Command::new("python3")
        .args(["-c", "import yaml"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !yaml {
        println!("skipped: the manifest check (needs python3 with PyYAML)");
        return;
    }
    let out = Command::new("python3")
        .arg(repo().join("deploy/check.py"))
        .output()
        .expect("python3");
    let said = String::from_utf8_lossy(&out.stdout);
    println!("{said}");
    assert!(out.status.success(), "deploy/check.py:\n{said}");
    assert!(said.contains("deploy check: 3 manifests ok"), "{said}");
}
