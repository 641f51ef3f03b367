//! Sparse grooms densified (`wisp::groom::densify`): a groom of 100 strands gets render strands
//! interpolated among its guides up to a head's density, with a physical total of fibres; a
//! dense groom keeps one render strand per file strand; the light map's span holds the
//! groom's hair wherever it reaches.

use glam::Vec3;
use wisp::engine::{HairMapConfig, map_geometry};
use wisp::groom::{Groom, GroomOptions, ROOT_TOLERANCE_M, build_groom, synthetic_strands};
use wisp::hairstyle::{CurlSpec, Hairstyle};
use wisp::interp::{StrandGeometry, interpolate};

fn smooth() -> Hairstyle {
    Hairstyle::default_smooth()
}

/// `synthetic_strands(count, points)` (roots on the upper 60% of a 9 cm sphere) on smooth.
fn groom(count: usize, points: usize) -> Groom {
    let file = synthetic_strands(count, points);
    build_groom(
        &[("synthetic.hair".into(), file)],
        &smooth(),
        &GroomOptions::default(),
    )
    .expect("the synthetic groom imports")
}

/// The rest pose's render points, strand-major.
fn rest_points(g: &Groom) -> StrandGeometry {
    let mut geo = StrandGeometry::default();
    interpolate(
        &g.guides,
        &g.layout,
        &CurlSpec::default(),
        &g.guides.rest,
        &mut geo,
    );
    geo
}

#[test]
fn a_100_strand_groom_is_densified_among_its_guides() {
    let g = groom(100, 24);
    let base = smooth();
    // smooth renders 134 × 25 = 3,350 strands; the synthetic roots cover the upper 60% of a
    // sphere, more than smooth's scalp cap, so the share is near 1 (0.958 measured): at least
    // 3,000 render strands, the 100 file strands among them.
    let strands = g.layout.count();
    assert!(strands >= 3000, "{strands} render strands");
    assert_eq!(g.report.strands_added, strands - 100);
    // Wisps of about 3 strands (k-means merges wisps under 3): each file strand is near guides.
    assert!(
        (15..=34).contains(&g.report.wisps),
        "{} wisps",
        g.report.wisps
    );
    // Total fibres: smooth's 30 × 3,350 = 100,500 times the share, which lies in [0.9, 1].
    let total = g.style.strands.fibers_per_strand * strands as f32;
    assert!((90_450.0..=100_500.5).contains(&total), "{total} fibres");
    let fibers = g.style.strands.fibers_per_strand;
    assert!(
        (25.0..=35.0).contains(&fibers),
        "{fibers} fibres per strand"
    );
    // Every added strand's root is its weights' blend of its wisp's guide roots (it lies in
    // their triangle) and on the scalp within the import's root tolerance.
    let geo = rest_points(&g);
    let n = geo.points_per_strand;
    let radii = Vec3::from(base.head.radii_m);
    let ppg = g.guides.points_per_guide;
    for s in 100..strands {
        let w = g.layout.strand_weights[s];
        assert!(w.iter().all(|x| *x >= -1e-6), "strand {s}: weights {w:?}");
        assert!(
            (w.iter().sum::<f32>() - 1.0).abs() < 1e-4,
            "strand {s}: {w:?}"
        );
        let gi = g.layout.wisp_guides[g.layout.strand_wisp[s] as usize];
        let blend: Vec3 = (0..3)
            .map(|k| g.guides.rest[gi[k] as usize * ppg] * w[k])
            .sum();
        let root = geo.positions[s * n];
        assert!(
            root.distance(blend) < 1e-4,
            "strand {s}: root {root} vs blend {blend}"
        );
        // Distance from the ellipsoid, to first order: (|p / r| − 1) × the smallest radius.
        let off_m = ((root / radii).length() - 1.0).abs() * radii.min_element();
        assert!(
            off_m <= ROOT_TOLERANCE_M,
            "strand {s}: root {off_m} m off the scalp"
        );
    }
}

#[test]
fn a_dense_groom_keeps_one_render_strand_per_file_strand() {
    // 4,000 strands: more than smooth's 3,350 render strands, so nothing is added.
    let g = groom(4000, 12);
    assert_eq!(g.layout.count(), 4000);
    assert_eq!(g.report.strands_added, 0);
    // 4,000 / 25 = 160 wisps, and smooth's fibres spread over the file's strands.
    assert_eq!(g.report.wisps, 160);
    let expect = 30.0 * 3350.0 / 4000.0;
    assert!((g.style.strands.fibers_per_strand - expect).abs() < 1e-4);
    assert!(g.layout.rest_offset.len() == 4000 * g.layout.points_per_strand);
}

#[test]
fn the_map_span_holds_the_groom_wherever_it_reaches() {
    // Long and short strands (3 points: 3 cm), sparse and dense, roots up to 16 mm off the scalp.
    for (count, points) in [(100, 24), (100, 3), (4000, 3)] {
        let g = groom(count, points);
        let reach = g.style.reach_m();
        let swing = g.style.max_length_m() + 0.5 * g.style.head_size_m();
        let geom = map_geometry(&g.style, &HairMapConfig::default());
        let span = geom.n as f32 * geom.ds_m;
        assert!(
            span >= 2.0 * reach,
            "{count}x{points}: span {span} reach {reach}"
        );
        // At rest every point lies within the reach of the head's centre, and a strand can
        // swing about its root no farther: the map's span holds the hair in every pose.
        let geo = rest_points(&g);
        let far = geo
            .positions
            .iter()
            .map(|p| p.length())
            .fold(0.0f32, f32::max);
        assert!(
            far <= reach + 1e-4,
            "{count}x{points}: {far} > reach {reach}"
        );
        // The style carries the groom's own reach; the map takes the larger of it and the swing.
        let own = g.style.guides.reach_m.expect("an imported groom's reach");
        assert!(
            own >= far - 1e-4 && reach == own.max(swing),
            "{count}x{points}"
        );
    }
}
