//! Speed against error for the guide simulation (issue 11): guide-tip positions over the whole
//! embedded dance for several fixed steps, against a fine-step reference.
//!
//! ```text
//! cargo run --release --example sim_steps -- [--hairstyle smooth|curly|FILE]
//!     [--steps 60,120,240,480,960] [--reference 1920] [--check 3840] [--seconds 8]
//!     [--threads N] [--no-self-collision] [--detail] [--only RATE]
//! ```
//!
//! Rates are steps per second. For each, the guides settle for 2 s on the first pose, as the
//! engine does, then follow the dance (`animations/dance.glb`, embedded, with its body spheres)
//! frame by frame at 30 fps, with the hairstyle's dynamics (self-collision on unless
//! `--no-self-collision`). At every frame the tip of every guide is compared with the same tip
//! in the reference run. Printed per rate, as a Markdown table:
//!
//! - tip error: RMS over all frames and guides, 95th percentile and largest, mm;
//! - the RMS error in frames of motion: divided by the RMS tip displacement between two
//!   consecutive reference frames;
//! - the simulation's cost: median ms per 1/30 s frame in this process;
//! - the observed order log(e(h₁)/e(h₂)) / log(h₁/h₂) between consecutive rates.
//!
//! `--check C` also runs rate C and prints how far the reference is from it (a bound on the
//! reference's own error). `--detail` adds, per rate, the RMS error of each second of the
//! dance and the error against the reference shifted by −2..2 frames (a smaller error at a
//! negative shift means the coarse run lags). `--only RATE` runs that rate alone and prints
//! its cost (for profilers: `valgrind --tool=callgrind ... --only 240`).

use glam::Vec3;
use std::time::Instant;
use wisp::engine::write_colliders;
use wisp::hairstyle::{Hairstyle, generate};
use wisp::motion::Motion;
use wisp::sim::{Colliders, SimState, Simulator};

const FPS: f64 = 30.0;
const SETTLE_S: f64 = 2.0;

struct Args {
    style: Hairstyle,
    steps: Vec<u32>,
    reference: u32,
    check: Option<u32>,
    seconds: f64,
    threads: Option<usize>,
    self_collision: bool,
    detail: bool,
    only: Option<u32>,
}

fn parse() -> Result<Args, String> {
    let mut a = Args {
        style: Hairstyle::default_smooth(),
        steps: vec![60, 120, 240, 480, 960],
        reference: 1920,
        check: None,
        seconds: 8.0,
        threads: None,
        self_collision: true,
        detail: false,
        only: None,
    };
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |i: usize| {
        args.get(i + 1)
            .cloned()
            .ok_or(format!("{} needs a value", args[i]))
    };
    let rate = |s: &str| -> Result<u32, String> {
        s.parse::<u32>()
            .ok()
            .filter(|r| (10..=100_000).contains(r))
            .ok_or(format!(
                "bad step rate {s} (steps per second, 10 to 100000)"
            ))
    };
    let mut i = 0;
    while i < args.len() {
        let mut skip = 2;
        match args[i].as_str() {
            "--hairstyle" => {
                let v = value(i)?;
                a.style = match v.as_str() {
                    "smooth" => Hairstyle::default_smooth(),
                    "curly" => Hairstyle::default_curly(),
                    f => Hairstyle::load(std::path::Path::new(f)).map_err(|e| e.to_string())?,
                };
            }
            "--steps" => {
                a.steps = value(i)?.split(',').map(rate).collect::<Result<_, _>>()?;
            }
            "--reference" => a.reference = rate(&value(i)?)?,
            "--check" => a.check = Some(rate(&value(i)?)?),
            "--only" => a.only = Some(rate(&value(i)?)?),
            "--seconds" => {
                a.seconds = value(i)?
                    .parse()
                    .ok()
                    .filter(|s: &f64| s.is_finite() && *s > 0.0 && *s <= 600.0)
                    .ok_or("bad --seconds (0 to 600)")?;
            }
            "--threads" => {
                a.threads = Some(
                    value(i)?
                        .parse()
                        .ok()
                        .filter(|n| (1..=256).contains(n))
                        .ok_or("bad --threads (1 to 256)")?,
                );
            }
            "--no-self-collision" => {
                a.self_collision = false;
                skip = 1;
            }
            "--detail" => {
                a.detail = true;
                skip = 1;
            }
            other => return Err(format!("unknown argument {other}")),
        }
        i += skip;
    }
    Ok(a)
}

/// Guide tips at every frame, and the median simulation time per frame (ms).
struct Run {
    tips: Vec<Vec<Vec3>>,
    ms_per_frame: f64,
}

fn run(args: &Args, rate: u32, motion: &Motion) -> Run {
    let mut style = args.style.clone();
    style.dynamics.step_s = 1.0 / rate as f32;
    let (guides, _) = generate(&style);
    let radii = Vec3::from(style.head.radii_m);
    let mut sim = Simulator::from_hairstyle(&style, &guides);
    sim.set_self_collision(args.self_collision);
    let mut pose = motion.sample(0.0);
    let mut c0 = Colliders::head_only(pose.head, radii);
    write_colliders(&pose, radii, &mut c0);
    let mut state = SimState::at_rest(&guides, &c0, -SETTLE_S);
    let ppg = guides.points_per_guide;
    let mut colliders_at = |t: f64, c: &mut Colliders| {
        motion.sample_into(t.max(0.0) as f32, &mut pose);
        write_colliders(&pose, radii, c);
    };
    // The settle, in slices under the catch-up cap, as `Engine::run_up_to` does.
    let mut t = -SETTLE_S;
    while t < 0.0 {
        t = (t + 0.2).min(0.0);
        sim.advance(&mut state, t, &mut colliders_at);
    }
    let frames = (args.seconds * FPS).round() as u32;
    let mut tips = Vec::with_capacity(frames as usize);
    let mut times = Vec::with_capacity(frames as usize);
    for f in 1..=frames {
        let t0 = Instant::now();
        sim.advance(&mut state, f64::from(f) / FPS, &mut colliders_at);
        times.push(t0.elapsed().as_secs_f64() * 1e3);
        tips.push(state.positions.chunks(ppg).map(|g| g[ppg - 1]).collect());
    }
    times.sort_by(f64::total_cmp);
    Run {
        tips,
        ms_per_frame: times[times.len() / 2],
    }
}

/// Tip distances (metres) between two runs, frame `f` of `a` against frame `f + shift` of
/// `b`, over all guides and the frames where both exist.
fn distances(a: &Run, b: &Run, shift: i64) -> Vec<f64> {
    let mut out = Vec::new();
    for (f, fa) in a.tips.iter().enumerate() {
        let Some(fb) = usize::try_from(f as i64 + shift)
            .ok()
            .and_then(|g| b.tips.get(g))
        else {
            continue;
        };
        out.extend(
            fa.iter()
                .zip(fb)
                .map(|(p, q)| f64::from((*p - *q).length())),
        );
    }
    out
}

fn rms(d: &[f64]) -> f64 {
    (d.iter().map(|x| x * x).sum::<f64>() / d.len().max(1) as f64).sqrt()
}

/// The `q` quantile of `d` (sorted in place).
fn quantile(d: &mut [f64], q: f64) -> f64 {
    d.sort_by(f64::total_cmp);
    d.get(((d.len().max(1) - 1) as f64 * q).round() as usize)
        .copied()
        .unwrap_or(0.0)
}

/// RMS tip displacement between consecutive frames (metres): one frame of motion.
fn frame_motion(r: &Run) -> f64 {
    let d: Vec<f64> = r
        .tips
        .windows(2)
        .flat_map(|w| {
            w[0].iter()
                .zip(&w[1])
                .map(|(p, q)| f64::from((*p - *q).length()))
                .collect::<Vec<_>>()
        })
        .collect();
    rms(&d)
}

fn main() {
    let args = match parse() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("sim_steps: {e}");
            std::process::exit(2);
        }
    };
    if let Some(n) = args.threads
        && let Err(e) = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
    {
        eprintln!("sim_steps: thread pool: {e}");
        std::process::exit(1);
    }
    let motion = Motion::default_dance();
    if let Some(rate) = args.only {
        let r = run(&args, rate, &motion);
        println!(
            "{}: step 1/{rate} s, {} s of the dance: {:.2} ms per frame (median)",
            args.style.name, args.seconds, r.ms_per_frame
        );
        return;
    }
    eprintln!("reference 1/{} s ...", args.reference);
    let reference = run(&args, args.reference, &motion);
    let motion_m = frame_motion(&reference);
    println!(
        "{}: {} s of the dance at {FPS} fps, self-collision {}, {} threads; reference step \
         1/{} s ({:.1} ms per frame); one frame of motion = {:.2} mm RMS tip displacement",
        args.style.name,
        args.seconds,
        if args.self_collision { "on" } else { "off" },
        rayon::current_num_threads(),
        args.reference,
        reference.ms_per_frame,
        motion_m * 1e3
    );
    if let Some(check) = args.check {
        let fine = run(&args, check, &motion);
        let mut d = distances(&reference, &fine, 0);
        println!(
            "reference 1/{} s against 1/{check} s: RMS {:.2} mm, 95th percentile {:.2} mm, \
             largest {:.1} mm",
            args.reference,
            rms(&d) * 1e3,
            quantile(&mut d, 0.95) * 1e3,
            quantile(&mut d, 1.0) * 1e3
        );
    }
    println!(
        "\n| step (s) | tip error RMS (mm) | 95th pct (mm) | largest (mm) | frames of motion \
         | sim ms / frame | observed order |"
    );
    println!("|---|---|---|---|---|---|---|");
    let mut prev: Option<(u32, f64)> = None;
    let mut details = Vec::new();
    for &rate in &args.steps {
        let r = run(&args, rate, &motion);
        let mut d = distances(&r, &reference, 0);
        let e = rms(&d);
        let order = match prev {
            Some((pr, pe)) if e > 0.0 && rate != pr => format!(
                "{:.2}",
                (pe / e).ln() / (f64::from(rate) / f64::from(pr)).ln()
            ),
            _ => "—".to_string(),
        };
        println!(
            "| 1/{rate} | {:.2} | {:.1} | {:.0} | {:.2} | {:.2} | {order} |",
            e * 1e3,
            quantile(&mut d, 0.95) * 1e3,
            quantile(&mut d, 1.0) * 1e3,
            e / motion_m,
            r.ms_per_frame
        );
        prev = Some((rate, e));
        if args.detail {
            let per_s: Vec<String> = r
                .tips
                .chunks(FPS as usize)
                .zip(reference.tips.chunks(FPS as usize))
                .map(|(a, b)| {
                    let d: Vec<f64> = a
                        .iter()
                        .zip(b)
                        .flat_map(|(fa, fb)| {
                            fa.iter()
                                .zip(fb)
                                .map(|(p, q)| f64::from((*p - *q).length()))
                                .collect::<Vec<_>>()
                        })
                        .collect();
                    format!("{:.1}", rms(&d) * 1e3)
                })
                .collect();
            let shifts: Vec<String> = (-2..=2)
                .map(|s| format!("{s:+}: {:.1}", rms(&distances(&r, &reference, s)) * 1e3))
                .collect();
            details.push(format!(
                "1/{rate} s: RMS per second of the dance (mm) {}; against the reference shifted \
                 by frames (mm) {}",
                per_s.join(" "),
                shifts.join(", ")
            ));
        }
    }
    for d in details {
        println!("\n{d}");
    }
}
