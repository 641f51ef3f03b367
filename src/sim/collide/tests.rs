use super::*;
use glam::Quat;

fn scene_colliders() -> Colliders {
    Colliders {
        head: Affine3A::from_rotation_translation(
            Quat::from_rotation_y(0.7) * Quat::from_rotation_x(-0.3),
            Vec3::new(0.1, 1.6, -0.2),
        ),
        head_radii_m: Vec3::new(0.076, 0.098, 0.094),
        spheres: vec![SphereCollider {
            center: Vec3::new(0.1, 1.3, -0.2),
            radius_m: 0.12,
        }],
        capsules: Vec::new(),
        carriers: Vec::new(),
    }
}

/// Seven capsules in a ring around a torso (two groups, the second partly unused), and
/// particles everywhere near them: the grouped test must give the bits of the capsule-by-
/// capsule loop it replaced, including where one capsule's push moves a particle into the
/// next capsule of the same group.
#[test]
fn grouped_capsules_resolve_as_one_by_one() {
    let mut c = scene_colliders();
    // The head far above and no sphere: only the capsules act here.
    c.head = Affine3A::from_translation(Vec3::new(0.0, 10.0, 0.0));
    c.spheres.clear();
    c.capsules = (0..7)
        .map(|i| {
            let a = i as f32 * 0.9;
            let centre = Vec3::new(0.1 + 0.09 * a.cos(), 1.1, -0.2 + 0.09 * a.sin());
            CapsuleCollider {
                a: centre - Vec3::new(0.02, 0.15, 0.01 * i as f32),
                b: centre + Vec3::new(0.0, 0.15, 0.02),
                radius_m: 0.04 + 0.005 * i as f32,
            }
        })
        .collect();
    let scene = CollisionScene::new(&c);
    assert_eq!(scene.groups.len(), 2);
    let one_by_one = |prev: Vec3A, cand: Vec3A, link: f32, fallback: Vec3A| {
        let mut p = cand;
        for _ in 0..COLLISION_ROUNDS {
            let mut moved = false;
            for bc in &scene.capsules {
                if bc.may_touch(p)
                    && let Some(q) = bc.capsule.push_out_usable(prev, p, link, fallback)
                {
                    p = q;
                    moved = true;
                }
            }
            if !moved {
                break;
            }
        }
        p
    };
    let mut hits = 0;
    for k in 0..4000 {
        let f = k as f32;
        let prev = Vec3A::new(
            0.1 + 0.2 * (f * 0.37).sin(),
            1.1 + 0.25 * (f * 0.11).cos(),
            -0.2 + 0.2 * (f * 0.23).cos(),
        );
        let dir = Vec3A::new((f * 0.7).cos(), (f * 0.3).sin(), (f * 0.5).sin()).normalize();
        let link = 0.01 + 0.02 * (f * 0.13).sin().abs();
        let cand = prev + dir * link;
        let (p, _) = scene.resolve(prev, cand, link, dir);
        let q = one_by_one(prev, cand, link, dir);
        if q != cand {
            hits += 1;
        }
        assert_eq!(
            p.to_array().map(f32::to_bits),
            q.to_array().map(f32::to_bits),
            "k = {k}"
        );
    }
    assert!(hits > 400, "only {hits} particles met a capsule");
}

#[test]
fn resolve_keeps_length_and_leaves_the_true_surface() {
    let c = scene_colliders();
    let scene = CollisionScene::new(&c);
    // Predecessors just outside the head, candidates driven inside at many angles.
    for k in 0..200 {
        let a = k as f32 * 0.37;
        let b = k as f32 * 0.11;
        let dir = Vec3::new(a.cos() * b.sin(), b.cos(), a.sin() * b.sin());
        let prev_h = dir * 1.01 / (dir / c.head_radii_m).length();
        let prev = Vec3A::from(c.head.transform_point3(prev_h));
        let link = 0.02;
        let inward = Vec3A::from(c.head.transform_vector3(-dir));
        let cand = prev + inward * link;
        let (p, touched) = scene.resolve(prev, cand, link, inward);
        assert!(touched);
        assert!(((p - prev).length() / link - 1.0).abs() < 1e-5);
        let pen = scene.penetration_m(p);
        assert!(pen < 1e-4, "penetration {pen} m at k={k}");
    }
}

#[test]
fn candidates_at_a_centre_resolve_to_finite_outside_points() {
    let c = scene_colliders();
    let scene = CollisionScene::new(&c);
    // A predecessor on the sphere's surface and a candidate at the sphere's centre (the link
    // as long as the radius): the answer is at link length, outside, and finite.
    let centre = Vec3A::from(c.spheres[0].center);
    let prev = centre + Vec3A::new(0.0, 0.0, -(0.12 + COLLISION_MARGIN_M));
    let link = 0.12 + COLLISION_MARGIN_M;
    let (p, _) = scene.resolve(prev, centre, link, Vec3A::Z);
    assert!(p.is_finite());
    assert!(((p - prev).length() / link - 1.0).abs() < 1e-5);
    assert!(scene.penetration_m(p) < 1e-5);
    let head_centre = c.head.translation;
    let outside = head_centre + Vec3A::new(0.0, 0.2, 0.0);
    let (p, _) = scene.resolve(outside, head_centre, 0.2, Vec3A::NEG_Y);
    assert!(p.is_finite());
    assert!(((p - outside).length() / 0.2 - 1.0).abs() < 1e-5);
}

#[test]
fn exit_point_is_continuous_as_the_predecessor_crosses_the_surface() {
    // Regression: a predecessor resting on the inflated sphere is inside or
    // outside it by rounding; the exit point must not jump between the two cases.
    let c = Vec3A::new(0.1, 1.3, -0.2);
    let r = 0.13;
    let link = 0.017;
    let normal = Vec3A::new(0.3, 0.9, -0.2).normalize();
    let tangent = normal.any_orthonormal_vector();
    // A candidate pushed 7 mm into the sphere, nearly on the axis prev → c (where the
    // nearest point is most sensitive).
    let mut exits = Vec::new();
    for rel in [-3e-7f32, -1e-7, 0.0, 1e-7, 3e-7] {
        let prev = c + normal * (r * (1.0 + rel));
        let p = prev - normal * 0.007 + tangent * 0.002;
        let e = circle_exit(prev, p, link, c, r, tangent).expect("circle exists");
        assert!(((e - prev).length() / link - 1.0).abs() < 1e-4);
        assert!((e - c).length() >= r * (1.0 - 1e-5), "exit inside: {e}");
        exits.push(e);
    }
    for e in &exits {
        assert!((*e - exits[2]).length() < 1e-6, "{e} vs {}", exits[2]);
    }
}

#[test]
fn penetration_bound_is_zero_outside_and_positive_inside() {
    let c = scene_colliders();
    assert_eq!(c.penetration_m(Vec3::new(5.0, 5.0, 5.0)), 0.0);
    assert!(c.penetration_m(c.head.translation.into()) > 0.07);
    let scene = CollisionScene::new(&c);
    let p = c.head.translation;
    assert!((scene.penetration_m(p) - c.penetration_m(p.into())).abs() < 1e-6);
}

/// Every point of positive depth, for the turned head, a sphere and a slanted capsule, lies in
/// one of `solid_bounds_m`'s boxes, and the head's box is tight: points inside the ellipsoid
/// reach within 2 mm of each of its six faces.
#[test]
fn solid_bounds_hold_every_point_inside_a_solid() {
    let mut c = scene_colliders();
    c.capsules.push(CapsuleCollider {
        a: Vec3::new(-0.2, 1.1, 0.0),
        b: Vec3::new(0.25, 1.45, -0.3),
        radius_m: 0.05,
    });
    let boxes = c.solid_bounds_m();
    assert_eq!(boxes.len(), 3);
    let scene = CollisionScene::new(&c);
    let mut rng = crate::rng::SplitMix64::new(5);
    let mut sample =
        |lo: Vec3, hi: Vec3| lo + (hi - lo) * Vec3::new(rng.unit(), rng.unit(), rng.unit());
    let in_a_box = |p: Vec3| {
        boxes
            .iter()
            .any(|(a, b)| p.cmpge(*a).all() && p.cmple(*b).all())
    };
    let mut inside = 0;
    for _ in 0..400_000 {
        let p = sample(Vec3::new(-0.4, 0.9, -0.6), Vec3::new(0.5, 1.8, 0.3));
        if scene.penetration_m(p.into()) > 0.0 {
            inside += 1;
            assert!(in_a_box(p), "{p} lies inside a solid but in no box");
        }
    }
    assert!(inside > 5_000, "{inside} points inside");
    let (a, b) = boxes[0];
    let margin = Vec3::splat(0.01);
    let mut reach = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for _ in 0..200_000 {
        let p = sample(a - margin, b + margin);
        let q = c.head.inverse().transform_point3(p) / c.head_radii_m;
        if q.length() < 1.0 {
            assert!(in_a_box(p), "{p} lies inside the head but in no box");
            reach = (reach.0.min(p), reach.1.max(p));
        }
    }
    assert!(
        (reach.0 - a).max_element() < 0.002 && (b - reach.1).max_element() < 0.002,
        "head box {a}..{b}, reached {reach:?}"
    );
}
