//! The guides under the analytic dance (`wisp::sim::dance`): rigid links and no penetration at
//! every step, the 3x-speed stress run at 30 Hz output, thread-count and frame-rate
//! independence, and the catch-up cap. The motion enters only through a collider closure, so
//! the same assertions run unchanged on a loaded glTF clip.

use crate::sim_common::*;
use glam::Vec3;
use wisp::hairstyle::Hairstyle;
use wisp::sim::dance::AnalyticDance;
use wisp::sim::{Colliders, SimState, Simulator};

/// Penetration allowed into the true head ellipsoid or a sphere, metres. Collisions push to a
/// 1 mm margin (`COLLISION_MARGIN_M`) and the final length projection may take some of it back;
/// 1 mm is a ninth of a wisp radius. The ellipsoid depth is measured with a conservative bound
/// (`Colliders::penetration_m`).
const PENETRATION_TOLERANCE_M: f32 = 1.0e-3;

/// Relative link-length tolerance: issue #4 required 1e-4, issue 11 keeps what held then,
/// 1e-5 (measured 6e-6 to 8e-6: about one f32 ulp of a world coordinate near 1.6 m, 1.2e-7 m,
/// relative to a 17 to 23 mm link).
const LENGTH_TOLERANCE: f32 = 1.0e-5;

fn presets() -> [Hairstyle; 2] {
    [Hairstyle::default_smooth(), Hairstyle::default_curly()]
}

/// Runs `frames` output frames of `frame_s` seconds under `motion`, calling `check` after each.
fn run<M, F>(
    sim: &mut Simulator,
    state: &mut SimState,
    frames: u32,
    frame_s: f64,
    motion: M,
    mut check: F,
) where
    M: Fn(f64, &mut Colliders) + Copy,
    F: FnMut(&SimState, u32),
{
    for f in 1..=frames {
        sim.advance(state, f64::from(f) * frame_s, motion);
        check(state, f);
    }
}

#[test]
fn dance_keeps_links_rigid_and_hair_outside_at_every_step() {
    for style in presets() {
        let dance = AnalyticDance::new(Vec3::from(style.head.radii_m));
        let motion = |t: f64, c: &mut Colliders| dance.colliders_at(t, c);
        let (guides, mut sim, mut state) = setup(&style, &dance.colliders(0.0));
        let ppg = guides.points_per_guide;
        let dt = f64::from(sim.params().step_s);
        let steps = (10.0 / dt).round() as u32;
        let mut c = dance.colliders(0.0);
        let (mut worst_pen, mut worst_len, mut sim_pen) = (0.0f32, 0.0f32, 0.0f32);
        for k in 1..=steps {
            let stats = sim.advance(&mut state, f64::from(k) * dt, motion);
            assert_eq!(stats.steps, 1, "one call per step");
            sim_pen = sim_pen.max(stats.max_penetration_m);
            dance.colliders_at(state.time_s, &mut c);
            let pen = max_penetration_m(&state, ppg, &c);
            worst_pen = worst_pen.max(pen);
            assert!(
                pen <= PENETRATION_TOLERANCE_M,
                "{}: step {k}: penetration {pen} m",
                style.name
            );
            worst_len = worst_len.max(max_length_error(&state, &guides));
        }
        eprintln!(
            "{}: 10 s dance: worst penetration {worst_pen:.2e} m (simulator's own {sim_pen:.2e}), \
             worst relative length error {worst_len:.2e}",
            style.name
        );
        assert!(
            worst_len < LENGTH_TOLERANCE,
            "{}: link length error {worst_len}",
            style.name
        );
        assert!(all_finite(&state));
    }
}

#[test]
fn stress_triple_speed_at_30_hz_output_stays_finite_and_rigid() {
    for style in presets() {
        let mut dance = AnalyticDance::new(Vec3::from(style.head.radii_m));
        dance.speed = 3.0;
        let motion = |t: f64, c: &mut Colliders| dance.colliders_at(t, c);
        let (guides, mut sim, mut state) = setup(&style, &dance.colliders(0.0));
        let mut worst_len = 0.0f32;
        let mut worst_pen = 0.0f32;
        let mut c = dance.colliders(0.0);
        run(&mut sim, &mut state, 300, 1.0 / 30.0, motion, |s, f| {
            assert!(all_finite(s), "{}: non-finite at frame {f}", style.name);
            assert!(s.kinetic_energy().is_finite());
            worst_len = worst_len.max(max_length_error(s, &guides));
            dance.colliders_at(s.time_s, &mut c);
            worst_pen = worst_pen.max(max_penetration_m(s, guides.points_per_guide, &c));
        });
        eprintln!(
            "{}: 3x dance, 1/30 s frames, 10 s: worst relative length error {worst_len:.2e}, \
             worst penetration at frame ends {worst_pen:.2e} m",
            style.name
        );
        assert!(
            worst_pen <= PENETRATION_TOLERANCE_M,
            "{}: {worst_pen}",
            style.name
        );
        assert!(worst_len < LENGTH_TOLERANCE, "{}: {worst_len}", style.name);
        assert!((state.time_s - 10.0).abs() < 1e-6);
    }
}

/// Two seconds of the dance inside a rayon pool of `threads` threads.
fn dance_in_pool(style: &Hairstyle, threads: usize) -> Vec<Vec3> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool");
    pool.install(|| {
        let dance = AnalyticDance::new(Vec3::from(style.head.radii_m));
        let motion = |t: f64, c: &mut Colliders| dance.colliders_at(t, c);
        let (_, mut sim, mut state) = setup(style, &dance.colliders(0.0));
        run(&mut sim, &mut state, 60, 1.0 / 30.0, motion, |_, _| {});
        state.positions
    })
}

fn same_bits(a: &[Vec3], b: &[Vec3]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(p, q)| {
            p.x.to_bits() == q.x.to_bits()
                && p.y.to_bits() == q.y.to_bits()
                && p.z.to_bits() == q.z.to_bits()
        })
}

#[test]
fn positions_are_bit_identical_with_one_and_two_threads() {
    for style in presets() {
        let one = dance_in_pool(&style, 1);
        let two = dance_in_pool(&style, 2);
        assert!(
            same_bits(&one, &two),
            "{}: thread count changed bits",
            style.name
        );
    }
}

#[test]
fn positions_do_not_depend_on_the_output_frame_rate() {
    let style = Hairstyle::default_curly();
    let dance = AnalyticDance::new(Vec3::from(style.head.radii_m));
    let motion = |t: f64, c: &mut Colliders| dance.colliders_at(t, c);
    let mut finals = Vec::new();
    // 30 Hz, 60 Hz, and an irregular slicing (frames of 7, 13 and 29 ms) ending at 2 s.
    for slicing in [
        vec![1.0 / 30.0],
        vec![1.0 / 60.0],
        vec![0.007, 0.013, 0.029],
    ] {
        let (_, mut sim, mut state) = setup(&style, &dance.colliders(0.0));
        let mut t = 0.0f64;
        let mut k = 0;
        let mut total_steps = 0;
        while t < 2.0 {
            t = (t + slicing[k % slicing.len()]).min(2.0);
            k += 1;
            total_steps += sim.advance(&mut state, t, motion).steps;
        }
        let dt = f64::from(style.dynamics.step_s);
        assert_eq!(total_steps, (2.0 / dt).round() as u32, "2 s of steps");
        finals.push(state.positions);
    }
    assert!(same_bits(&finals[0], &finals[1]), "1/30 s vs 1/60 s calls");
    assert!(
        same_bits(&finals[0], &finals[2]),
        "1/30 s vs irregular calls"
    );
}

#[test]
fn a_long_hiccup_is_capped_and_the_hair_follows_the_head() {
    let style = Hairstyle::default_smooth();
    let dance = AnalyticDance::new(Vec3::from(style.head.radii_m));
    let motion = |t: f64, c: &mut Colliders| dance.colliders_at(t, c);
    let (guides, mut sim, mut state) = setup(&style, &dance.colliders(0.0));
    run(&mut sim, &mut state, 15, 1.0 / 30.0, motion, |_, _| {});
    // A 1 s stall: only max_catch_up_s (0.25 s) is simulated, the rest is skipped.
    let stats = sim.advance(&mut state, 1.5, motion);
    let cap = f64::from(sim.params().max_catch_up_s);
    let dt = f64::from(sim.params().step_s);
    assert_eq!(stats.steps, (cap / dt).round() as u32);
    assert!(
        (stats.dropped_s - (1.0 - cap)).abs() < 1e-6,
        "{}",
        stats.dropped_s
    );
    assert!((state.time_s - 1.5).abs() <= dt / 2.0);
    assert!(all_finite(&state));
    assert!(max_length_error(&state, &guides) < LENGTH_TOLERANCE);
    let c = dance.colliders(state.time_s);
    let pen = max_penetration_m(&state, guides.points_per_guide, &c);
    assert!(
        pen <= PENETRATION_TOLERANCE_M,
        "penetration {pen} m after the hiccup"
    );
    // Roots are on the scalp of the head at the new time.
    let root = c.head.transform_point3(guides.rest[0]);
    assert!((state.positions[0] - root).length() < 1e-5);
}

#[test]
fn non_finite_colliders_and_times_do_not_poison_the_state() {
    let style = Hairstyle::default_curly();
    let dance = AnalyticDance::new(Vec3::from(style.head.radii_m));
    let (guides, mut sim, mut state) = setup(&style, &dance.colliders(0.0));
    let stats = sim.advance(&mut state, f64::NAN, |t, c: &mut Colliders| {
        dance.colliders_at(t, c)
    });
    assert_eq!(stats.steps, 0);
    let bad = |t: f64, c: &mut Colliders| {
        dance.colliders_at(t, c);
        if t > 0.05 {
            c.head.translation.x = f32::NAN;
            c.spheres[0].radius_m = f32::INFINITY;
            c.spheres[1].center.y = f32::NAN;
        }
    };
    let stats = sim.advance(&mut state, 0.2, bad);
    assert!(stats.steps > 0);
    assert!(all_finite(&state));
    assert!(max_length_error(&state, &guides) < LENGTH_TOLERANCE);
    // Going back in time does nothing.
    let before = state.positions.clone();
    let stats = sim.advance(&mut state, 0.1, bad);
    assert_eq!(stats.steps, 0);
    assert!(same_bits(&before, &state.positions));
}

/// Angles (radians) between consecutive free links of every guide, guide-major.
fn turning_angles(points: &[Vec3], ppg: usize) -> Vec<f32> {
    let mut out = Vec::new();
    for g in points.chunks(ppg) {
        for i in 2..ppg {
            let a = (g[i - 1] - g[i - 2]).normalize();
            let b = (g[i] - g[i - 1]).normalize();
            out.push(a.dot(b).clamp(-1.0, 1.0).acos());
        }
    }
    out
}

#[test]
fn curly_guides_keep_their_rest_bends_through_the_dance() {
    let base = Hairstyle::default_curly();
    let mut deviation = Vec::new();
    let mut rest_mean = 0.0;
    for stiffness in [base.dynamics.bending_stiffness, 0.0] {
        let mut style = base.clone();
        style.dynamics.bending_stiffness = stiffness;
        let dance = AnalyticDance::new(Vec3::from(style.head.radii_m));
        let motion = |t: f64, c: &mut Colliders| dance.colliders_at(t, c);
        let (guides, mut sim, mut state) = setup(&style, &dance.colliders(0.0));
        let ppg = guides.points_per_guide;
        let rest = turning_angles(&guides.rest, ppg);
        rest_mean = rest.iter().sum::<f32>() / rest.len() as f32;
        // Mean |bend − rest bend| over all links, averaged over the frames of seconds 3 to 5.
        let mut dev = 0.0f32;
        run(&mut sim, &mut state, 150, 1.0 / 30.0, motion, |s, f| {
            if f > 90 {
                let now = turning_angles(&s.positions, ppg);
                let d: f32 = now.iter().zip(&rest).map(|(a, b)| (a - b).abs()).sum();
                dev += d / now.len() as f32 / 60.0;
            }
        });
        deviation.push(dev);
    }
    eprintln!(
        "curly: mean rest bend {rest_mean:.3} rad; mean bend change in the dance: stiffness {} -> \
         {:.3} rad, limp -> {:.3} rad",
        base.dynamics.bending_stiffness, deviation[0], deviation[1]
    );
    assert!(
        deviation[0] < 0.1 * rest_mean,
        "{deviation:?} vs {rest_mean}"
    );
    assert!(deviation[0] < 0.1 * deviation[1], "{deviation:?}");
}
