//! Generated must-not-panic cases for every input format, in process: thousands of mutated
//! hairstyles, glTF files (binary, JSON with an external .bin, JSON with a base64 buffer) and
//! simulation caches from valid seeds. Each case must end accepted or refused with a short message naming the
//! file, with no panic, within a time bound (a hang detector, not a speed test) and a memory
//! bound.
//!
//! Reproduce a failure from the `WISP_HOSTILE_ONLY=<format>:<seed>` it prints (runs that case
//! alone, with `RUST_BACKTRACE=1` for a panic's backtrace). More cases per format:
//! `WISP_HOSTILE_CASES=20000`; another stream: `WISP_HOSTILE_SEED=<n>`.
//! The inputs of failing cases are written to `target/tmp/hostile-loaders/failures/`.

use crate::bounded::run_bounded;
use crate::support::hostile::Rng;
use crate::support::hostile::formats::{self, Verdict};
use crate::support::{full_size, scratch_dir};
use std::time::Duration;

/// Cases per format per run (the generated suite runs at least 1,000 cases in all).
const CASES_PER_FORMAT: [usize; 9] = [500, 300, 200, 100, 300, 200, 200, 300, 200];
/// Hang bound per case: the slowest case takes milliseconds (see the run's summary).
const TIME_LIMIT: Duration = Duration::from_secs(30);
/// Memory bound per case: a base for the parsed structures plus a multiple of the input size.
/// Measured: the largest peak over 10,000 cases was 9.6 MB for a 464 KB input (RobotExpressive,
/// mesh data decoded for the fit); the bound leaves a factor of about 4.
const MEMORY_BASE_BYTES: usize = 16 << 20;
const MEMORY_PER_INPUT_BYTE: usize = 64;

fn env_u64(name: &str) -> Option<u64> {
    std::env::var(name).ok().and_then(|v| v.parse().ok())
}

#[test]
fn mutated_inputs_never_panic_hang_or_balloon() {
    let base_seed = env_u64("WISP_HOSTILE_SEED").unwrap_or(0x5EED_0008);
    let mut scale = env_u64("WISP_HOSTILE_CASES");
    let only: Option<(usize, u64)> = std::env::var("WISP_HOSTILE_ONLY").ok().and_then(|v| {
        let (f, s) = v.split_once(':')?;
        Some((f.parse().ok()?, s.parse().ok()?))
    });
    if only.is_some() {
        scale = Some(1);
    }
    let root = scratch_dir("hostile-loaders");
    let failures_dir = root.join("failures");
    let mut failures = Vec::new();
    let mut total = 0usize;
    for (fi, format) in formats::all().into_iter().enumerate() {
        if only.is_some_and(|(f, _)| f != fi) {
            continue;
        }
        let cases = scale.map_or(CASES_PER_FORMAT[fi], |n| n as usize);
        let (mut accepted, mut refused) = (0usize, 0usize);
        let (mut max_peak, mut max_ms) = (0usize, 0.0f64);
        let load = format.load;
        for i in 0..cases {
            let seed = only.map_or(
                base_seed
                    .wrapping_add((fi as u64) << 32)
                    .wrapping_add(i as u64),
                |(_, s)| s,
            );
            let mut rng = Rng::new(seed);
            let (case, what) = formats::mutated(&format, &mut rng);
            let dir = root.join(format!("case-{fi}-{i}"));
            std::fs::create_dir_all(&dir).expect("case dir");
            let input_bytes = case.bytes();
            let bound = MEMORY_BASE_BYTES + MEMORY_PER_INPUT_BYTE * input_bytes;
            let kept = case.clone();
            let dir_for_case = dir.clone();
            let outcome = run_bounded(move || load(&kept, &dir_for_case), TIME_LIMIT);
            let problem = match outcome {
                Err(e) => Some(e),
                Ok(report) => {
                    max_peak = max_peak.max(report.peak_bytes);
                    max_ms = max_ms.max(report.elapsed.as_secs_f64() * 1e3);
                    match report.value {
                        Err(broken) => Some(broken),
                        Ok(_) if report.peak_bytes > bound => Some(format!(
                            "peak memory {} B for a {input_bytes} B input (bound {bound} B)",
                            report.peak_bytes
                        )),
                        Ok(Verdict::Accepted) => {
                            accepted += 1;
                            None
                        }
                        Ok(Verdict::Refused(_)) => {
                            refused += 1;
                            None
                        }
                    }
                }
            };
            let _ = std::fs::remove_dir_all(&dir);
            if let Some(p) = problem {
                let keep = failures_dir.join(format!("{fi}-{seed}"));
                let _ = std::fs::create_dir_all(&keep);
                let _ = case.write(&keep);
                failures.push(format!(
                    "{} WISP_HOSTILE_ONLY={fi}:{seed} ({}): {p}",
                    format.name,
                    what.join("; ")
                ));
            }
            total += 1;
        }
        println!(
            "{}: {cases} cases, {accepted} accepted, {refused} refused; peak memory {:.1} MB, slowest {max_ms:.1} ms",
            format.name,
            max_peak as f64 / 1e6
        );
    }
    if scale.is_none() && only.is_none() {
        assert!(total >= 1000, "only {total} cases ran");
    }
    assert!(
        failures.is_empty(),
        "{} of {total} cases failed (inputs in {}):\n{}",
        failures.len(),
        failures_dir.display(),
        failures
            .iter()
            .take(20)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// What an accepted hairstyle promises further down the pipeline: a small frame of the dance
/// renders with every pixel finite, no render point skipped as non-finite, and hair or head
/// drawn (not a blank frame). Generated hairstyles are loaded until 12 accepted ones within a
/// small budget have rendered, 24 at full size (`WISP_FULL_TESTS=1`; `WISP_HOSTILE_RENDERS=<n>`
/// for any other count).
#[test]
fn accepted_hairstyles_render_finite_nonblank_frames() {
    use wisp::budget::{Budget, RunPlan};
    use wisp::engine::{Engine, EngineConfig};
    use wisp::engine::{estimate, fit_map_resolution};
    use wisp::hairstyle::Hairstyle;
    use wisp::motion::Motion;

    let format = &formats::all()[0];
    let small = Budget {
        memory_bytes: 400_000_000,
        work_cpu_s: 3.0,
    };
    let plan = RunPlan {
        export_png: false,
        ..RunPlan::default()
    };
    let wanted =
        env_u64("WISP_HOSTILE_RENDERS").unwrap_or(if full_size() { 24 } else { 12 }) as usize;
    let (mut rendered, mut heavy) = (0usize, 0usize);
    let mut failures = Vec::new();
    for seed in 0xF11_0008u64..0xF11_0008 + 1_000_000 {
        if rendered == wanted {
            break;
        }
        let mut rng = Rng::new(seed);
        let (case, what) = formats::mutated(format, &mut rng);
        let Ok(style) = Hairstyle::from_bytes(&case.files[0].1, "h.json") else {
            continue;
        };
        let motion = Motion::default_dance();
        let mut config = {
            let mut config = EngineConfig::sized(48, 48);
            config.simulation.settle_s = 0.2;
            config
        };
        if let Some((_, n)) = fit_map_resolution(&style, &motion, &config, &plan, &small) {
            config.hair_map.map_res = Some(n);
        }
        if estimate(&style, &motion, &config, &plan)
            .check(&small)
            .is_err()
        {
            heavy += 1;
            continue;
        }
        let outcome = run_bounded(
            move || {
                let background = config.scene.background;
                let mut engine = Engine::new(style, motion, config);
                engine.frame(0.3);
                let fb = engine.framebuffer();
                if let Some(c) = fb.color.iter().find(|c| !c.is_finite()) {
                    return Err(format!("a pixel is {c}"));
                }
                let stats = engine.map_stats();
                if stats.skipped > 0 {
                    return Err(format!("{} render points are not finite", stats.skipped));
                }
                if fb.color.iter().all(|c| *c == background) {
                    return Err("the frame is blank".into());
                }
                Ok(())
            },
            Duration::from_secs(120),
        );
        rendered += 1;
        let problem = match outcome {
            Err(e) => Some(e),
            Ok(r) => r.value.err(),
        };
        if let Some(p) = problem {
            failures.push(format!("seed {seed} ({}): {p}", what.join("; ")));
        }
    }
    println!("rendered {rendered} accepted hairstyles; {heavy} over the small budget skipped");
    assert_eq!(rendered, wanted);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The same promise for accepted glTF motions (mutated dance clips, odd options included):
/// the smooth preset rides them through two small frames with every pixel finite.
#[test]
fn accepted_motions_render_finite_nonblank_frames() {
    use wisp::engine::{Engine, EngineConfig};
    use wisp::hairstyle::Hairstyle;
    use wisp::motion::Motion;

    let format = &formats::all()[1];
    let wanted = env_u64("WISP_HOSTILE_RENDERS").map_or(8, |n| n as usize);
    let mut rendered = 0usize;
    let mut failures = Vec::new();
    for seed in 0xF12_0008u64..0xF12_0008 + 1_000_000 {
        if rendered == wanted {
            break;
        }
        let mut rng = Rng::new(seed);
        let (case, what) = formats::mutated(format, &mut rng);
        // The dance seed only (138 KB with its mannequin; RobotExpressive, 464 KB, has meshes
        // that make each load slower).
        if case.files[0].1.len() > 300_000 {
            continue;
        }
        let Ok(motion) = Motion::from_glb_bytes(&case.files[0].1, "m.glb", &Default::default())
        else {
            continue;
        };
        let outcome = run_bounded(
            move || {
                let config = {
                    let mut config = EngineConfig::sized(48, 48);
                    config.simulation.settle_s = 0.2;
                    config
                };
                let background = config.scene.background;
                let mut engine = Engine::new(Hairstyle::default_smooth(), motion, config);
                for t in [0.3, 2.1] {
                    engine.frame(t);
                    let fb = engine.framebuffer();
                    if let Some(c) = fb.color.iter().find(|c| !c.is_finite()) {
                        return Err(format!("at {t} s a pixel is {c}"));
                    }
                    if engine.map_stats().skipped > 0 {
                        return Err(format!("at {t} s render points are not finite"));
                    }
                    if fb.color.iter().all(|c| *c == background) {
                        return Err(format!("the frame at {t} s is blank"));
                    }
                }
                Ok(())
            },
            Duration::from_secs(120),
        );
        rendered += 1;
        let problem = match outcome {
            Err(e) => Some(e),
            Ok(r) => r.value.err(),
        };
        if let Some(p) = problem {
            failures.push(format!("seed {seed} ({}): {p}", what.join("; ")));
        }
    }
    println!("rendered {rendered} accepted motions");
    assert_eq!(rendered, wanted);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The same promise for accepted simulation caches (generated edits that keep the checksums
/// valid, such as a position nudged by a millimetre): every frame renders from the cache with
/// every pixel finite and something drawn.
#[test]
fn accepted_caches_render_finite_nonblank_frames() {
    use crate::support::hostile::cache::{expected, seed_config, seed_style};
    use wisp::cache::CacheReader;
    use wisp::engine::Engine;
    use wisp::motion::Motion;

    let all = formats::all();
    let format = all
        .iter()
        .find(|f| f.name == "simulation cache")
        .expect("the cache format");
    let root = scratch_dir("hostile-cache-renders");
    let wanted = env_u64("WISP_HOSTILE_RENDERS").map_or(8, |n| n as usize);
    let (mut rendered, mut failures) = (0usize, Vec::new());
    for seed in 0xF13_0008u64..0xF13_0008 + 100_000 {
        if rendered == wanted {
            break;
        }
        let mut rng = Rng::new(seed);
        let (case, what) = formats::mutated(format, &mut rng);
        let path = case.write(&root).expect("write case");
        let motion = Motion::default_dance();
        let Ok(mut reader) = CacheReader::open(&path, &expected()) else {
            continue;
        };
        let Ok(settled) = reader.read_settled(&motion).map(<[_]>::to_vec) else {
            continue;
        };
        let frames: Result<Vec<_>, _> = (0..reader.header().frames)
            .map(|i| {
                let t = reader.header().frame_time_s(i);
                reader.read_frame(i, &motion).map(|p| (t, p.to_vec()))
            })
            .collect();
        let Ok(frames) = frames else { continue };
        let outcome = run_bounded(
            move || {
                let config = seed_config();
                let background = config.scene.background;
                let mut engine = Engine::from_settled(seed_style(), motion, config, &settled);
                for (t, p) in &frames {
                    engine.set_guide_state(*t, p);
                    let fb = engine.render();
                    if let Some(c) = fb.color.iter().find(|c| !c.is_finite()) {
                        return Err(format!("at {t} s a pixel is {c}"));
                    }
                    if fb.color.iter().all(|c| *c == background) {
                        return Err(format!("the frame at {t} s is blank"));
                    }
                }
                Ok(())
            },
            Duration::from_secs(120),
        );
        rendered += 1;
        if let Some(p) = match outcome {
            Err(e) => Some(e),
            Ok(r) => r.value.err(),
        } {
            failures.push(format!("seed {seed} ({}): {p}", what.join("; ")));
        }
    }
    println!("rendered {rendered} accepted caches");
    assert_eq!(rendered, wanted);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
