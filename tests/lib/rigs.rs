//! Rigs in other units and axes give the same hair: the embedded dance re-expressed the way
//! other exporters write it (`support::rig_variants`: centimetres under a 0.01 scale node, Z-up
//! data under a correcting root, Z-up data with no correction, joints without names) must load
//! to the same poses and, simulated through the dance's fastest second, to the same hair.
//!
//! Tolerances: the poses are the same maths on data scaled by 100 or rotated by 90°, so they
//! agree to f32 rounding of 1.7 m (2⁻²³ · 1.7 ≈ 2e-7 m per operation, some tens of operations:
//! 1e-5 m, 1e-5 rad), but for capsule ends on nearly round limbs (see the test). The hair goes through 1,000 steps of a simulation that is sensitive to
//! such rounding (contacts switch on a sign): 0.2 mm at any guide point, 10 µm on the mean
//! (measured: 36 µm and 1.4 µm at most over the variants).

use crate::support::rig_variants::{Frame, re_expressed, with_rest_rotations};
use glam::{Quat, Vec3};
use wisp::engine::{Engine, EngineConfig};
use wisp::hairstyle::Hairstyle;
use wisp::motion::dance::DANCE_GLB;
use wisp::motion::{Motion, MotionOptions};

fn variant(frame: Frame) -> Motion {
    let bytes = re_expressed(DANCE_GLB, frame);
    Motion::from_glb_bytes(&bytes, "variant.glb", &MotionOptions::default()).expect("loads")
}

fn unnamed() -> Frame {
    Frame {
        scale: 1.0,
        rotation: Quat::IDENTITY,
        correcting_root: false,
        unnamed: true,
    }
}

/// Every variant, named for messages.
fn variants() -> Vec<(&'static str, Frame)> {
    let mut cm_z_up = Frame::z_up_corrected();
    cm_z_up.scale = 100.0;
    vec![
        ("cm under a 0.01 node", Frame::CM_UNDER_SCALE_NODE),
        ("Z-up under a correcting root", Frame::z_up_corrected()),
        ("Z-up, no correction", Frame::z_up_raw()),
        ("cm and Z-up under one root", cm_z_up),
        ("unnamed joints", unnamed()),
    ]
}

#[test]
fn every_variant_loads_to_the_original_poses() {
    let original = Motion::default_dance();
    for (name, frame) in variants() {
        let m = variant(frame);
        assert!(
            (m.fit().scale - original.fit().scale).abs() < 1e-5,
            "{name}: {:?}",
            m.fit()
        );
        assert_eq!(
            m.head_joint().0,
            original.head_joint().0,
            "{name}: head joint"
        );
        for t in [0.0, 2.1, 4.21, 4.86, 5.7] {
            let (a, b) = (original.sample(t), m.sample(t));
            let dt = (Vec3::from(a.head.translation) - Vec3::from(b.head.translation)).length();
            let qa = Quat::from_mat3a(&a.head.matrix3);
            let qb = Quat::from_mat3a(&b.head.matrix3);
            assert!(dt < 1e-5, "{name} at {t} s: head {dt} m apart");
            assert!(
                qa.angle_between(qb) < 1e-5 * 10.0,
                "{name} at {t} s: head turned"
            );
            assert_eq!(a.capsules.len(), b.capsules.len(), "{name}: capsules");
            for (ca, cb) in a.capsules.iter().zip(&b.capsules) {
                let d = (ca.a - cb.a).length().max((ca.b - cb.b).length());
                // A capsule's axis is an eigenvector of its vertices' covariance, found by a
                // fixed number of power iterations: where two extents nearly tie (a hand),
                // rounding turns it by a few degrees and moves the ends by millimetres (7.7 mm
                // measured on a hand of the centimetre rig), the radius by 2.1 mm.
                assert!(d < 1e-2, "{name} at {t} s: capsule {d} m apart");
                let dr = (ca.radius_m - cb.radius_m).abs();
                assert!(dr < 3e-3, "{name}: capsule radius {dr} m apart");
            }
        }
    }
}

/// The dance with a T-pose rest: both upper arms turned 90° out to the sides (the clip
/// animates them, so only the rest the loader fits the capsules in changes).
fn t_pose_rest() -> Motion {
    use std::f32::consts::FRAC_PI_2;
    let bytes = with_rest_rotations(
        DANCE_GLB,
        &[
            ("UpperArm.L", Quat::from_rotation_z(FRAC_PI_2)),
            ("UpperArm.R", Quat::from_rotation_z(-FRAC_PI_2)),
        ],
    );
    Motion::from_glb_bytes(&bytes, "t_pose.glb", &MotionOptions::default()).expect("loads")
}

#[test]
fn a_t_pose_rest_gives_the_same_head_and_hair() {
    let (original, t_pose) = (Motion::default_dance(), t_pose_rest());
    assert_eq!(t_pose.fit(), original.fit());
    for t in [0.0, 4.21] {
        assert_eq!(t_pose.sample(t).head, original.sample(t).head);
    }
    let (a, b) = (hair_after_whips(original), hair_after_whips(t_pose));
    let max = a
        .iter()
        .zip(&b)
        .map(|(p, q)| p.distance(*q))
        .fold(0.0, f32::max);
    eprintln!("T-pose rest: hair {max:.2e} m apart at most");
    // The capsules are fitted per bone in the bone's own frame, so holding the arms out at
    // rest changes them only through vertices blended across bones (1.1 µm measured).
    assert!(max < 1e-4, "hair {max} m apart");
}

#[test]
fn a_model_lying_along_z_is_turned_upright_and_says_so() {
    assert_eq!(Motion::default_dance().file_up(), Vec3::Y);
    assert_eq!(variant(Frame::z_up_corrected()).file_up(), Vec3::Y);
    assert_eq!(variant(Frame::z_up_raw()).file_up(), Vec3::Z);
    // Kept as the file has it, the head stands along +Z, 1.66 m up.
    let bytes = re_expressed(DANCE_GLB, Frame::z_up_raw());
    let opts = MotionOptions {
        keep_axes: true,
        ..MotionOptions::default()
    };
    let kept = Motion::from_glb_bytes(&bytes, "raw.glb", &opts).expect("loads");
    let head = Vec3::from(kept.sample(0.0).head.translation);
    assert!(
        (head.z - 1.66).abs() < 0.01 && head.y.abs() < 0.01,
        "{head}"
    );
}

#[test]
fn unnamed_joints_give_the_topmost_joint_below_its_end_bone_as_head() {
    let m = variant(unnamed());
    let original = Motion::default_dance();
    assert!(m.head_is_topmost() && !original.head_is_topmost());
    // `Head` (node 4), not `HeadTop_End` (node 5, a leaf above it), nor `Neck`.
    assert_eq!(m.head_joint().0, original.head_joint().0);
    assert_eq!(original.head_joint().1, "Head");
}

/// Guide particles after the dance's whips and head-bang (3.6 s to 4.9 s), 96 × 96 px.
fn hair_after_whips(motion: Motion) -> Vec<Vec3> {
    let mut style = Hairstyle::default_smooth();
    style.wisps.count = 40;
    style.wisps.strands_per_wisp = 2;
    let mut config = EngineConfig::sized(96, 96);
    config.simulation.settle_s = 0.3;
    let mut engine = Engine::new(style, motion, config);
    engine.run_up_to(4.9);
    engine.state().positions.clone()
}

#[test]
fn every_variant_simulates_the_same_hair() {
    let original = hair_after_whips(Motion::default_dance());
    for (name, frame) in variants() {
        let hair = hair_after_whips(variant(frame));
        assert_eq!(hair.len(), original.len());
        let d: Vec<f32> = hair
            .iter()
            .zip(&original)
            .map(|(a, b)| (*a - *b).length())
            .collect();
        let max = d.iter().copied().fold(0.0, f32::max);
        let mean = d.iter().sum::<f32>() / d.len() as f32;
        eprintln!("{name}: hair {max:.2e} m apart at most, {mean:.2e} m on average");
        assert!(
            max < 2e-4 && mean < 1e-5,
            "{name}: hair {max} m apart at most, {mean} m on average"
        );
    }
}
