//! Tests of the simulation step (`step.rs`): links, collisions, bending, rest, self-collision.
use super::*;
use crate::sim::{COLLISION_MARGIN_M, SphereCollider};

fn one_guide(rest: Vec<Vec3>, link: f32) -> GuideSet {
    GuideSet {
        points_per_guide: rest.len(),
        rest,
        link_length_m: vec![link],
        root_normal: vec![Vec3::NEG_Y],
        carrier: Vec::new(),
    }
}

#[test]
fn a_straight_hanging_guide_stays_put_and_keeps_its_links() {
    // Rooted on the underside of a small head, hanging straight down.
    let radii = Vec3::splat(0.05);
    let rest: Vec<Vec3> = (0..10)
        .map(|i| Vec3::new(0.0, -0.05 - i as f32 * 0.02, 0.0))
        .collect();
    let guides = one_guide(rest, 0.02);
    let colliders = Colliders::head_only(Affine3A::IDENTITY, radii);
    let mut sim = Simulator::new(&SimParams::default(), &guides, radii, 0.0);
    let mut state = SimState::at_rest(&guides, &colliders, 0.0);
    let start = state.positions.clone();
    let stats = sim.advance(&mut state, 2.0, |_, c: &mut Colliders| {
        *c = colliders.clone()
    });
    let dt = SimParams::default().step_s;
    assert_eq!(
        stats.steps,
        (0.25 / dt).round() as u32,
        "capped at max_catch_up_s = 0.25 s"
    );
    for (p, q) in state.positions.iter().zip(&start) {
        assert!((*p - *q).length() < 1e-5, "moved from {q} to {p}");
    }
}

#[test]
fn a_resting_guide_is_held_exactly_and_wakes_when_its_head_moves() {
    // A guide sticking out sideways settles under gravity, is held bit-for-bit still, and
    // follows the head the very step the head moves by a micrometre.
    let radii = Vec3::splat(0.05);
    let rest: Vec<Vec3> = (0..10)
        .map(|i| Vec3::new(0.05 + i as f32 * 0.02, 0.0, 0.0))
        .collect();
    let guides = GuideSet {
        root_normal: vec![Vec3::X],
        ..one_guide(rest, 0.02)
    };
    let params = SimParams::default();
    let mut sim = Simulator::new(&params, &guides, radii, 0.0);
    let still = Colliders::head_only(Affine3A::from_translation(Vec3::Y), radii);
    let mut state = SimState::at_rest(&guides, &still, 0.0);
    let dt = f64::from(params.step_s);
    let mut t = 0.0;
    let mut held_from = None;
    while t < 3.0 {
        t += dt;
        let stats = sim.advance(&mut state, t, |_, c: &mut Colliders| *c = still.clone());
        if stats.resting_guides == 1 && held_from.is_none() {
            held_from = Some(t);
        }
    }
    let held_from = held_from.expect("the guide came to rest");
    assert!(held_from < 2.0, "held only from {held_from} s");
    let before = state.positions.clone();
    let stats = sim.advance(&mut state, t + dt, |_, c: &mut Colliders| {
        *c = still.clone()
    });
    assert_eq!(stats.resting_guides, 1);
    assert_eq!(state.positions, before, "held exactly");
    assert_eq!(state.max_speed_m_s(), 0.0);
    // The head moves 1 µm along z: the guide wakes at once (its roots move with the head).
    let nudged = Colliders::head_only(Affine3A::from_translation(Vec3::new(0.0, 1.0, 1e-6)), radii);
    let stats = sim.advance(&mut state, t + 2.0 * dt, |_, c: &mut Colliders| {
        *c = nudged.clone()
    });
    assert_eq!(stats.resting_guides, 0);
    for (p, q) in state.positions[..2].iter().zip(&before) {
        assert!((p.z - q.z - 1e-6).abs() < 1e-8, "root {p} from {q}");
    }
    // Moved by 1 mm, the guide follows to within the tolerance (a response smaller than
    // the tolerance may be held part-way: that is the documented dead band).
    let moved = Colliders::head_only(Affine3A::from_translation(Vec3::new(0.0, 1.0, 1e-3)), radii);
    sim.advance(&mut state, t + 1.0, |_, c: &mut Colliders| {
        *c = moved.clone()
    });
    let tol = params.rest_tolerance_m;
    for (p, q) in state.positions.iter().zip(&before) {
        assert!(
            (p.z - q.z - 1e-3).abs() < 2.0 * tol,
            "{p} did not follow the head from {q}"
        );
    }
}

#[test]
fn a_long_many_link_guide_keeps_its_density_grid_within_budget() {
    // 256 links of 4 mm: the mean link would give a 2 m/4 mm = 500-node-wide lattice
    // (1.25e8 nodes); the spacing floor of reach/60 keeps the reachable cube within
    // DENSITY_GRID_MAX_NODES, so self-collision is never skipped, even with the hair
    // straight out sideways.
    let radii = Vec3::splat(0.05);
    let link = 0.004;
    let rest: Vec<Vec3> = (0..257)
        .map(|i| Vec3::new(0.05 + i as f32 * link, 0.0, 0.0))
        .collect();
    let guides = GuideSet {
        root_normal: vec![Vec3::X],
        ..one_guide(rest, link)
    };
    let mut sim = Simulator::new(&SimParams::default(), &guides, radii, 1e-6);
    assert!(sim.self_collision());
    let reach = 0.05 + 256.0 * link;
    assert!(sim.density_cell_m() >= reach / 60.0 * 0.999);
    let colliders = Colliders::head_only(Affine3A::IDENTITY, radii);
    let mut state = SimState::at_rest(&guides, &colliders, 0.0);
    let stats = sim.advance(&mut state, 0.05, |_, c: &mut Colliders| {
        *c = colliders.clone()
    });
    assert!(stats.steps > 0);
    assert_eq!(stats.self_collision_skipped_steps, 0);
    assert!(sim.density_grid_nodes() > 0);
    assert!(sim.density_grid_nodes() <= crate::sim::DENSITY_GRID_MAX_NODES);
}

#[test]
fn limp_guide_falls_and_swings_under_gravity_without_stretching() {
    // A horizontal guide (rest shape sticking out sideways) with zero stiffness must fall.
    let radii = Vec3::splat(0.05);
    let rest: Vec<Vec3> = (0..10)
        .map(|i| Vec3::new(0.05 + i as f32 * 0.02, 0.0, 0.0))
        .collect();
    let guides = GuideSet {
        root_normal: vec![Vec3::X],
        ..one_guide(rest, 0.02)
    };
    let params = SimParams {
        bending_stiffness: 0.0,
        ..SimParams::default()
    };
    let colliders = Colliders::head_only(Affine3A::IDENTITY, radii);
    let mut sim = Simulator::new(&params, &guides, radii, 0.0);
    let mut state = SimState::at_rest(&guides, &colliders, 0.0);
    let mut lowest_tip_m = 0.0f32;
    for f in 1..=18 {
        sim.advance(&mut state, f as f64 / 60.0, |_, c: &mut Colliders| {
            *c = colliders.clone()
        });
        lowest_tip_m = lowest_tip_m.min(state.positions[9].y);
        assert!(state.kinetic_energy() > 0.0);
        for w in state.positions.windows(2) {
            assert!(((w[1] - w[0]).length() / 0.02 - 1.0).abs() < 1e-5);
        }
        for p in &state.positions[2..] {
            assert!(colliders.penetration_m(*p) < 1e-4, "{p}");
        }
    }
    // The free part of the chain is 0.16 m long: swinging down, its tip passes well below
    // the root's height (free fall alone would drop it 0.44 m in 0.3 s).
    assert!(lowest_tip_m < -0.1, "tip did not fall: {lowest_tip_m}");
}

#[test]
fn a_fast_sphere_sweeping_through_hanging_hair_pushes_it_without_tunnelling() {
    // A 45 mm sphere crosses a hanging guide sideways at 5 m/s (under the 21.6 m/s limit
    // derived in collide.rs): every particle it meets is pushed ahead of it, none is
    // left inside or passed through.
    let radii = Vec3::splat(0.05);
    let rest: Vec<Vec3> = (0..12)
        .map(|i| Vec3::new(0.0, -0.05 - i as f32 * 0.02, 0.0))
        .collect();
    let guides = one_guide(rest, 0.02);
    let speed_m_s = 5.0f32;
    let sphere_at = move |t: f64| SphereCollider {
        center: Vec3::new(-0.2 + speed_m_s * t as f32, -0.17, 0.0),
        radius_m: 0.045,
    };
    let colliders_at = move |t: f64, c: &mut Colliders| {
        c.head = Affine3A::IDENTITY;
        c.head_radii_m = radii;
        c.spheres.clear();
        c.spheres.push(sphere_at(t));
    };
    let mut c0 = Colliders::head_only(Affine3A::IDENTITY, radii);
    colliders_at(0.0, &mut c0);
    let mut sim = Simulator::new(&SimParams::default(), &guides, radii, 0.0);
    let mut state = SimState::at_rest(&guides, &c0, 0.0);
    let dt = f64::from(sim.params().step_s);
    let mut c = c0.clone();
    let mut furthest_push_m = 0.0f32;
    // 0.1 s: the sphere travels 0.5 m, from x = -0.2 to 0.3, through the guide.
    for k in 1..=(0.1 / dt).round() as u32 {
        let stats = sim.advance(&mut state, f64::from(k) * dt, colliders_at);
        assert!(
            stats.max_penetration_m < 1e-4,
            "{}",
            stats.max_penetration_m
        );
        colliders_at(state.time_s, &mut c);
        for p in &state.positions[2..] {
            assert!(c.penetration_m(*p) < 1e-4, "step {k}: {p} inside");
        }
        for p in &state.positions[4..8] {
            furthest_push_m = furthest_push_m.max(p.x);
        }
    }
    // The particles at the sphere's height were carried along +x before the strand slid
    // around the sphere (the stiff rest shape then straightens it again).
    assert!(furthest_push_m > 0.03, "pushed only {furthest_push_m} m");
}

#[test]
fn at_rest_moves_hair_out_of_a_sphere_it_starts_in() {
    let radii = Vec3::splat(0.05);
    let rest: Vec<Vec3> = (0..10)
        .map(|i| Vec3::new(0.0, -0.05 - i as f32 * 0.02, 0.0))
        .collect();
    let guides = one_guide(rest, 0.02);
    let colliders = Colliders {
        head: Affine3A::from_translation(Vec3::new(0.0, 1.6, 0.0)),
        head_radii_m: radii,
        spheres: vec![SphereCollider {
            center: Vec3::new(0.01, 1.6 - 0.17, 0.0),
            radius_m: 0.05,
        }],
        capsules: Vec::new(),
        carriers: Vec::new(),
    };
    let state = SimState::at_rest(&guides, &colliders, 0.0);
    for p in &state.positions[2..] {
        assert!(
            colliders.penetration_m(*p) < 0.1 * COLLISION_MARGIN_M,
            "{p}"
        );
    }
    for w in state.positions.windows(2) {
        assert!(((w[1] - w[0]).length() / 0.02 - 1.0).abs() < 1e-5);
    }
    assert_eq!(state.kinetic_energy(), 0.0);
    assert!(state.velocities().iter().all(|v| *v == Vec3::ZERO));
}

#[test]
fn inconsistent_guide_sets_and_states_do_nothing_instead_of_panicking() {
    let radii = Vec3::splat(0.05);
    let mut guides = one_guide(vec![Vec3::Y * 0.05, Vec3::Y * 0.07, Vec3::Y * 0.09], 0.02);
    guides.link_length_m.push(0.02); // claims 2 guides, holds 1
    let colliders = Colliders::head_only(Affine3A::IDENTITY, radii);
    let mut sim = Simulator::new(&SimParams::default(), &guides, radii, 0.0);
    assert_eq!(sim.particle_count(), 3);
    let mut state = SimState::at_rest(&guides, &colliders, 0.0);
    assert_eq!(state.positions.len(), 3);
    state.positions.push(Vec3::ZERO); // now mismatched
    let stats = sim.advance(&mut state, 1.0, |_, _: &mut Colliders| {});
    assert_eq!(stats.steps, 0);
    let params = SimParams {
        step_s: f32::NAN,
        bending_stiffness: 7.0,
        ..SimParams::default()
    };
    let sim = Simulator::new(&params, &guides, radii, 0.0);
    assert_eq!(sim.params().step_s, SimParams::default().step_s);
    // A non-finite head at construction gives a finite state.
    let mut nan_head = colliders.clone();
    nan_head.head.translation.x = f32::NAN;
    let state = SimState::at_rest(&guides, &nan_head, 0.0);
    assert!(state.positions.iter().all(|p| p.is_finite()));
    // Degenerate guide sets: no particles, no panic.
    for ppg in [0, 1] {
        let empty = GuideSet {
            points_per_guide: ppg,
            ..guides.clone()
        };
        let mut sim = Simulator::new(&SimParams::default(), &empty, radii, 0.0);
        let mut state = SimState::at_rest(&empty, &colliders, 0.0);
        assert!(state.positions.is_empty());
        let stats = sim.advance(&mut state, 1.0, |_, _: &mut Colliders| {});
        assert_eq!(stats.steps, 0);
    }
    assert_eq!(sim.params().bending_stiffness, 1.0);
    assert!(sim.params().validate().is_ok());
}
