//! Grooms that are not a whole scalp's. A mohawk (roots along a strip over the top of the
//! head) and bangs (roots along the front hairline) are placed on the head at the scale they
//! were made at, instead of being shrunk onto a point by the fit onto the head
//! (`groom::place`, `groom::root_sphere`); fur on an animal's body is refused by the fit and
//! kept where it was authored on request (`groom::as_authored`).
//!
//! Both are generated here in a capture's conventions: centimetres, Y-up, on a 9 cm head
//! whose centre is 150 cm above the origin (a head on a standing character), 16 points a
//! strand. Placed on wisp's head (semi-axes 7.5, 10, 9.5 cm, mean 9.0), the scale is then 9.0 /
//! 9 cm = 0.01 (metres per centimetre) within the fit's error, and a 12 cm spike is 0.12 m.

use glam::Vec3;
use wisp::groom::{GroomError, GroomOptions, build_groom};
use wisp::hairstyle::Hairstyle;
use wisp::input::strands::StrandFile;

const HEAD_CM: Vec3 = Vec3::new(0.0, 150.0, 0.0);
const RADIUS_CM: f32 = 9.0;

/// Strands rooted at the head directions `dirs`, each `length_cm` along `grow(dir)`.
fn strands(dirs: &[Vec3], length_cm: f32, grow: impl Fn(Vec3) -> Vec3) -> StrandFile {
    let mut f = StrandFile::default();
    for d in dirs {
        let d = d.normalize();
        let root = HEAD_CM + RADIUS_CM * d;
        let step = grow(d).normalize() * length_cm / 15.0;
        for k in 0..16 {
            f.points.push(root + k as f32 * step);
        }
        f.strand_points.push(16);
    }
    f
}

/// A mohawk: 3 rows 1 cm apart across the midline, over 140° from the forehead to the nape;
/// spikes 12 cm long straight out of the scalp.
fn mohawk() -> StrandFile {
    let dirs: Vec<Vec3> = (0..240)
        .map(|i| {
            let t = (i / 3) as f32 / 79.0 * 140f32.to_radians() - 60f32.to_radians();
            let side = (i % 3) as f32 - 1.0;
            Vec3::new(side / RADIUS_CM, t.cos(), t.sin())
        })
        .collect();
    strands(&dirs, 12.0, |d| d)
}

/// Bangs: one row along the front hairline (30° above the eyes, ±60° to the sides), 10 cm
/// falling forward and down over the forehead.
fn bangs() -> StrandFile {
    let dirs: Vec<Vec3> = (0..120)
        .map(|i| {
            let a = (i as f32 / 119.0 - 0.5) * 120f32.to_radians();
            let up = 30f32.to_radians();
            Vec3::new(a.sin() * up.cos(), up.sin(), a.cos() * up.cos())
        })
        .collect();
    strands(&dirs, 10.0, |d| d + Vec3::new(0.0, -2.0, 0.6))
}

#[test]
fn a_mohawk_keeps_its_scale_and_stands_on_top_of_the_head() {
    let files = vec![("mohawk.hair".to_string(), mohawk())];
    let base = Hairstyle::default_smooth();
    let g = build_groom(&files, &base, &GroomOptions::default()).expect("a mohawk is placed");
    let p = g.report.placement.expect("placed");
    assert!(g.report.placed_by_root_sphere, "{:?}", g.report);
    assert!((p.scale - 0.01).abs() < 0.001, "scale {}", p.scale);
    // Roots within the fit's tolerance of the scalp, the strip over the top of the head.
    assert!(g.report.root_distance_max_m < 0.012, "{:?}", g.report);
    let roots: Vec<Vec3> = (0..g.guides.count())
        .map(|k| g.guides.rest[k * g.guides.points_per_guide])
        .collect();
    let mean_y = roots.iter().map(|r| r.y).sum::<f32>() / roots.len() as f32;
    assert!(
        mean_y > 0.05,
        "the strip's roots average {mean_y} m above the head centre"
    );
    assert!(
        roots.iter().all(|r| r.x.abs() < 0.02),
        "roots across the midline"
    );
}

#[test]
fn bangs_keep_their_scale_and_sit_at_the_front() {
    let files = vec![("bangs.hair".to_string(), bangs())];
    let base = Hairstyle::default_smooth();
    let opts = GroomOptions {
        yaw_rad: Some(0.0),
        ..GroomOptions::default()
    };
    let g = build_groom(&files, &base, &opts).expect("bangs are placed");
    let p = g.report.placement.expect("placed");
    assert!((p.scale - 0.01).abs() < 0.003, "scale {}", p.scale);
    let roots: Vec<Vec3> = (0..g.guides.count())
        .map(|k| g.guides.rest[k * g.guides.points_per_guide])
        .collect();
    assert!(
        roots.iter().all(|r| r.z > 0.02),
        "the hairline is at the face (+Z)"
    );
}

/// Fur: 2,000 strands of 4 points, 3 cm, over an ellipsoid body 60 × 30 × 30 cm whose centre
/// is 50 cm up (no head in the file).
fn fur() -> StrandFile {
    let mut f = StrandFile::default();
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    for i in 0..2000 {
        let y = 1.0 - 2.0 * (i as f32 + 0.5) / 2000.0;
        let r = (1.0 - y * y).sqrt();
        let d = Vec3::new(
            r * (golden * i as f32).cos(),
            y,
            r * (golden * i as f32).sin(),
        );
        let root = Vec3::new(0.0, 50.0, 0.0) + d * Vec3::new(15.0, 15.0, 30.0);
        for k in 0..4 {
            f.points.push(root + d * k as f32);
        }
        f.strand_points.push(4);
    }
    f
}

#[test]
fn fur_is_not_put_on_a_head_but_kept_where_it_was_authored_on_request() {
    let files = vec![("fur.ply".to_string(), fur())];
    let base = Hairstyle::default_smooth();
    let refused = build_groom(&files, &base, &GroomOptions::default()).expect_err("not a scalp");
    // Fitted to the head, its roots are off it (16% over 3 cm); the CLI adds the flag that
    // keeps it as authored to either refusal.
    assert!(
        matches!(
            refused,
            GroomError::RootsOffHead { .. } | GroomError::NotOnAHead { .. }
        ),
        "{refused}"
    );
    let opts = GroomOptions {
        as_authored: true,
        ..GroomOptions::default()
    };
    let g = build_groom(&files, &base, &opts).expect("kept as authored");
    // The body spans 60 units: centimetres, guessed.
    assert_eq!(g.report.as_authored_unit_m, Some((0.01, true)));
    // Every guide root is a file root in metres, in place: on the body, 0.5 m up.
    for k in 0..g.guides.count() {
        let root = g.guides.rest[k * g.guides.points_per_guide];
        let q = (root - Vec3::new(0.0, 0.5, 0.0)) / Vec3::new(0.15, 0.15, 0.30);
        assert!(
            (q.length() - 1.0).abs() < 1e-3,
            "guide {k}'s root {root} is off the body"
        );
    }
    // No head ellipsoid under it: the smallest the hairstyle allows.
    assert_eq!(
        g.style.head.radii_m,
        [wisp::hairstyle::MIN_HEAD_RADIUS_M; 3]
    );
    let given = GroomOptions {
        unit_m: Some(0.001),
        ..opts
    };
    let g = build_groom(&files, &base, &given).expect("kept as authored");
    assert_eq!(g.report.as_authored_unit_m, Some((0.001, false)));
}
