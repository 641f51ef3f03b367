mod sim_common;
use glam::Vec3;
use sim_common::*;
use wisp::hairstyle::Hairstyle;
use wisp::sim::dance::AnalyticDance;
use wisp::sim::{Colliders, NoDensity};

#[test]
fn probe() {
    for corr in [0.0f32, 0.5, 0.9] {
        for limp in [false, true] {
            for mut style in [Hairstyle::default_smooth(), Hairstyle::default_curly()] {
                style.dynamics.ftl_correction = corr;
                if limp {
                    style.dynamics.bending_stiffness = 0.0;
                }
                let mut dance = AnalyticDance::new(Vec3::from(style.head.radii_m));
                dance.speed = 0.0;
                let (guides, mut sim, mut state) = setup(&style, &dance.colliders(0.0));
                let mut line = String::new();
                let mut wmax = 0.0f64;
                let mut snap = Vec::new();
                for k in 1..=2400 {
                    sim.advance(
                        &mut state,
                        k as f64 / 240.0,
                        |t, c: &mut Colliders| dance.colliders_at(t, c),
                        &NoDensity,
                    );
                    wmax = wmax.max(state.kinetic_energy());
                    if k % 240 == 0 {
                        line += &format!(" {:.0e}", wmax);
                        wmax = 0.0;
                    }
                    if k % 480 == 0 {
                        snap.push(state.positions.clone());
                    }
                }
                let disp: Vec<String> = snap
                    .iter()
                    .map(|w| {
                        format!(
                            "{:.0e}",
                            snap[0]
                                .iter()
                                .zip(w)
                                .map(|(a, b)| (*a - *b).length())
                                .fold(0.0f32, f32::max)
                        )
                    })
                    .collect();
                eprintln!(
                    "{} corr {corr} limp {limp}: KE/1s {line}   disp {:?} len {:.0e}",
                    style.name,
                    disp,
                    max_length_error(&state, &guides)
                );
            }
        }
    }
}
