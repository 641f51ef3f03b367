use super::*;
use crate::map::LightFrame;
use crate::map::occluders::Solid;
use glam::Affine3A;

proptest::proptest! {
    /// Read from a window, the entry depth is `entry_depth`'s to the bit, at points
    /// inside the window, on its edges, beyond it and beyond the grid, for solids of
    /// any place and size (a window larger than the grid included).
    #[test]
    fn the_window_reads_the_bits_of_entry_depth(
        centres in proptest::collection::vec((-0.1f32..0.1, -0.1f32..0.1, -0.1f32..0.1, 0.005f32..0.06), 1..4),
        (wy, wz, half) in (-0.2f32..0.2, -0.2f32..0.2, 0.0f32..0.3),
        points in proptest::collection::vec((-0.4f32..0.4, -0.4f32..0.4), 64),
    ) {
        let frame = LightFrame::new(Vec3::new(0.3, -1.0, 0.2).normalize());
        let solids: Vec<Solid> = centres
            .iter()
            .map(|&(x, y, z, r)| Solid {
                unit_sphere_to_world: Affine3A::from_scale_rotation_translation(
                    Vec3::splat(r),
                    glam::Quat::IDENTITY,
                    Vec3::new(x, y, z),
                ),
            })
            .collect();
        let mut grid = OccluderGrid::default();
        grid.build(&frame, 0.004, &solids);
        let (lo, hi) = (Vec2::new(wy, wz) - half, Vec2::new(wy, wz) + half);
        let mut window = EntryDepths::default();
        window.fill(&grid, lo, hi);
        let corners = [lo, hi, Vec2::new(lo.x, hi.y), Vec2::new(hi.x, lo.y)];
        for p in points.iter().map(|&(y, z)| Vec2::new(y, z)).chain(corners) {
            let m = Vec3::new(0.0, p.x, p.y);
            let (want, got) = (grid.entry_depth(m), window.at(&grid, m));
            proptest::prop_assert_eq!(want.to_bits(), got.to_bits(), "at {}", p);
        }
    }
}

#[test]
fn the_window_holds_what_it_is_asked_for_and_a_solid_is_in_it() {
    // A 5 cm sphere, a window over its shadow: points across the window are read from it
    // (not from the fallback) and some of them meet the sphere.
    let frame = LightFrame::new(Vec3::X);
    let mut grid = OccluderGrid::default();
    let sphere = Solid {
        unit_sphere_to_world: Affine3A::from_scale(Vec3::splat(0.05)),
    };
    grid.build(&frame, 0.002, &[sphere]);
    let mut window = EntryDepths::default();
    window.fill(&grid, Vec2::splat(-0.04), Vec2::splat(0.04));
    assert!(
        window.rows >= 40 && window.cols >= 40,
        "{} × {}",
        window.rows,
        window.cols
    );
    let finite = window.shallowest.iter().filter(|d| d.is_finite()).count();
    assert!(
        finite > window.rows * window.cols / 2,
        "{finite} texels meet the sphere"
    );
    let centre = window.at(&grid, Vec3::ZERO);
    assert!(
        (centre + 0.05).abs() < 0.003,
        "entry depth at the centre {centre}"
    );
}
