//! The guides under the analytic dance (`wisp::sim::dance`): rigid links, no penetration at
//! any step, the 3x-speed stress run, thread-count and frame-rate independence.

mod sim_common;

use glam::Vec3;
use sim_common::*;
use wisp::hairstyle::Hairstyle;
use wisp::sim::dance::AnalyticDance;
use wisp::sim::{Colliders, NoDensity};

/// Penetration allowed into the true head ellipsoid or a sphere, metres. Collisions push to a
/// 1 mm margin (`COLLISION_MARGIN_M`); the residual after the final length projection is what
/// this bounds. 1 mm is a tenth of a wisp radius.
const PENETRATION_TOLERANCE_M: f32 = 1.0e-3;

#[test]
fn dance_keeps_links_rigid_and_hair_outside_at_every_step() {
    for style in [Hairstyle::default_smooth(), Hairstyle::default_curly()] {
        let dance = AnalyticDance::new(Vec3::from(style.head.radii_m));
        let (guides, mut sim, mut state) = setup(&style, &dance.colliders(0.0));
        let ppg = guides.points_per_guide;
        let dt = f64::from(sim.params().step_s);
        let steps = (10.0 / dt).round() as u64;
        let mut c = dance.colliders(0.0);
        let mut worst_pen = 0.0f32;
        let mut worst_len = 0.0f32;
        for k in 1..=steps {
            let stats = sim.advance(
                &mut state,
                k as f64 * dt,
                |t, c: &mut Colliders| dance.colliders_at(t, c),
                &NoDensity,
            );
            assert_eq!(stats.steps, 1);
            dance.colliders_at(state.time_s, &mut c);
            let pen = max_penetration_m(&state, ppg, &c);
            worst_pen = worst_pen.max(pen);
            if pen > PENETRATION_TOLERANCE_M {
                for (i, p) in state.positions.iter().enumerate() {
                    if i % ppg >= 2 && c.penetration_m(*p) > 0.0 {
                        let q = c.head.inverse().transform_point3(*p);
                        let sph: Vec<f32> = c
                            .spheres
                            .iter()
                            .map(|s| s.radius_m - (*p - s.center).length())
                            .collect();
                        eprintln!(
                            "g {} i {} pen {} s {} spheres {:?} stats {}",
                            i / ppg,
                            i % ppg,
                            c.penetration_m(*p),
                            (q / c.head_radii_m).length(),
                            sph,
                            stats.max_penetration_m
                        );
                    }
                }
            }
            assert!(
                pen <= PENETRATION_TOLERANCE_M,
                "{}: step {k}: penetration {pen} m",
                style.name
            );
            if k % 60 == 0 {
                worst_len = worst_len.max(max_length_error(&state, &guides));
            }
        }
        let len = max_length_error(&state, &guides);
        worst_len = worst_len.max(len);
        eprintln!(
            "{}: worst penetration {worst_pen:e} m, worst length error {worst_len:e}, ke {}",
            style.name,
            state.kinetic_energy()
        );
        assert!(
            len < 1e-4,
            "{}: link length error {len} after 10 s",
            style.name
        );
        assert!(all_finite(&state));
    }
}
