//! The light paths' starts against brute force: every point of every cell holding fibre must
//! lie where paths are sent.

use super::*;
use crate::light_paths::StrandPoints;
use crate::rng::SplitMix64;

/// A tilted sheet of 3,000 pieces, thin along one axis so the grid's box is mostly empty, in
/// cells of 4 mm; and the cells that hold fibre.
fn sheet(rng: &mut SplitMix64) -> (Cells, Vec<usize>) {
    let n = 3_000;
    let positions: Vec<Vec3> = (0..n)
        .map(|_| {
            let (s, t) = (rng.unit(), rng.unit());
            Vec3::new(0.1 * s, 0.05 * t + 0.02 * s, 0.003 * rng.unit())
        })
        .collect();
    let tangents: Vec<Vec3> = (0..n)
        .map(|_| Vec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5))
        .collect();
    let points = StrandPoints {
        positions: &positions,
        tangents: &tangents,
        lengths_m: &vec![0.003; n],
        fibers_per_strand: 1.0,
    };
    let cells = Cells::build(&points, 0.004).expect("cells");
    let filled = cells.filled().collect();
    (cells, filled)
}

/// Cell `i`'s eight corners, then 32 random points inside it (unit cell coordinates and the
/// point, metres).
fn points_of(cells: &Cells, i: usize, rng: &mut SplitMix64) -> Vec<(Vec3, Vec3)> {
    let corner = cells.origin + cells.coords(i).as_vec3() * cells.cell_m;
    (0..40)
        .map(|k| {
            let f = if k < 8 {
                Vec3::new((k & 1) as f32, ((k >> 1) & 1) as f32, (k >> 2) as f32)
            } else {
                Vec3::new(rng.unit(), rng.unit(), rng.unit())
            };
            (f, corner + f * cells.cell_m)
        })
        .collect()
}

/// Every point of every cell holding fibre lies in a marked column, whatever the light's
/// direction (so no path that could hit fibre is left unsent and the estimate keeps its
/// expectation), while the columns cover much less than the rectangle across the grid
/// (what the footprint saves, seen obliquely). The paths' powers sum to the irradiance
/// over the columns.
#[test]
fn the_footprint_holds_every_cell_with_fiber() {
    let mut rng = SplitMix64::new(21);
    let (cells, filled) = sheet(&mut rng);
    let directions = [
        Vec3::Z,
        -Vec3::X,
        Vec3::new(0.3, -0.5, -1.0),
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(-0.01, 1.0, 0.002),
    ];
    for travel in directions {
        let light = Light::directional(travel, Vec3::splat(2.0)).expect("light");
        let paths = 1_000;
        let emitter = Emitter::new(&cells, &light, paths).expect("emitter");
        let Kind::Plane {
            a, b, footprint, ..
        } = &emitter.kind
        else {
            panic!("a directional light sends from a plane");
        };
        for &i in &filled {
            for (f, p) in points_of(&cells, i, &mut rng) {
                let p = p - emitter.origin;
                let q = (Vec2::new(p.dot(*a), p.dot(*b)) - footprint.lo) / footprint.tile_m;
                assert!(
                    footprint
                        .columns
                        .holds(q.x.floor() as u32, q.y.floor() as u32),
                    "travel {travel}: cell {i} point {f} in unmarked column {q}"
                );
            }
        }
        let size = cells.dims.as_vec3() * cells.cell_m;
        let rectangle_m2 = {
            let (mut lo, mut hi) = (Vec2::INFINITY, Vec2::NEG_INFINITY);
            for k in 0..8 {
                let c = size * Vec3::new((k & 1) as f32, ((k >> 1) & 1) as f32, (k >> 2) as f32)
                    - 0.5 * size;
                lo = lo.min(Vec2::new(c.dot(*a), c.dot(*b)));
                hi = hi.max(Vec2::new(c.dot(*a), c.dot(*b)));
            }
            (hi - lo).element_product()
        };
        let area = footprint.area_m2();
        // Seen obliquely the sheet covers under half the rectangle (0.42 when written).
        if travel == Vec3::ONE {
            assert!(
                area < 0.5 * rectangle_m2,
                "travel {travel}: {area} m² of columns against {rectangle_m2} m²"
            );
        }
        let flux = emitter.power * paths as f32;
        assert!((flux / (2.0 * area) - Vec3::ONE).abs().max_element() < 1e-5);
    }
}

/// The same for a point light's cone: every point of every cell holding fibre lies in a
/// marked bin of directions, for lights near and far, on several sides and among the hair, while the bins
/// cover under half the cone for the sheet seen obliquely; the paths' powers sum to the
/// intensity over the bins' solid angle.
#[test]
fn the_cone_footprint_holds_every_cell_with_fiber() {
    let mut rng = SplitMix64::new(22);
    let (cells, filled) = sheet(&mut rng);
    let centre = cells.origin + cells.dims.as_vec3() * (0.5 * cells.cell_m);
    let mut oblique_share = 1.0;
    for (offset, oblique) in [
        (Vec3::new(0.0, 0.0, 0.5), false),
        (Vec3::new(0.3, 0.3, 0.3), true),
        (Vec3::new(-0.2, 0.01, 0.0), false),
        (Vec3::new(0.0, -3.0, 1.0), false),
        (Vec3::new(0.02, 0.02, 0.2), false),
        // Among the hair: the whole sphere of directions, about +Z, so the sheet's cells lie
        // around the equator and the far pole.
        (Vec3::new(0.01, -0.005, 0.001), false),
        (Vec3::new(0.0, 0.0, 0.004), false),
    ] {
        let light = Light::point(centre + offset, Vec3::splat(3.0)).expect("light");
        let paths = 1_000;
        let emitter = Emitter::new(&cells, &light, paths).expect("emitter");
        let Kind::Cone {
            frame,
            one_minus_cos_max,
            footprint,
        } = &emitter.kind
        else {
            panic!("a point light sends into a cone");
        };
        let cone = Cone {
            light_m: emitter.origin,
            axis: emitter.axis,
            frame: *frame,
            one_minus_cos_max: *one_minus_cos_max,
        };
        let bins = footprint.bins.width;
        for &i in &filled {
            for (f, p) in points_of(&cells, i, &mut rng) {
                let (q, _) = cone.coordinates(p);
                let bin = (q * bins as f32)
                    .floor()
                    .as_uvec2()
                    .min(glam::UVec2::splat(bins - 1));
                assert!(
                    footprint.bins.holds(bin.x, bin.y),
                    "light at {offset}: cell {i} point {f} at {q} in an unmarked bin"
                );
            }
        }
        let share = footprint.share_of_cone();
        if oblique {
            oblique_share = share;
        }
        let omega = std::f32::consts::TAU * one_minus_cos_max * share;
        let flux = emitter.power * paths as f32;
        assert!((flux / (3.0 * omega) - Vec3::ONE).abs().max_element() < 1e-4);
    }
    assert!(
        oblique_share < 0.5,
        "the oblique sheet takes {oblique_share} of its cone"
    );
}

/// A point light's axis points from the light to the grid's centre in every lane, for lights
/// off every axis (each with a y component). The guard on a miscompile (`Emitter::cone`):
/// with the axis and 1 − cos θmax chosen as one tuple, the release build (rustc 1.95,
/// `-C target-cpu=x86-64-v2`) zeroed the axis's y lane; this test, run on the tuple form of
/// the code where it was seen, fails for the first light (axis (0, 0, −0.316) instead of
/// (0, 0.949, −0.316)). The tuple alone in a small function compiles right, so the
/// reproduction is the emitter itself.
#[test]
fn a_point_lights_axis_points_at_the_grid_in_every_lane() {
    let mut rng = SplitMix64::new(23);
    let (cells, _) = sheet(&mut rng);
    let centre = cells.origin + cells.dims.as_vec3() * (0.5 * cells.cell_m);
    for offset in [
        Vec3::new(0.0, -3.0, 1.0),
        Vec3::new(0.3, 0.3, 0.3),
        Vec3::new(-0.2, 0.01, 0.0),
        Vec3::new(0.0, 20.0, 0.0),
    ] {
        let light = Light::point(centre + offset, Vec3::splat(3.0)).expect("light");
        let emitter = Emitter::new(&cells, &light, 1_000).expect("emitter");
        let to = centre - (centre + offset);
        let want = to / to.length();
        assert!(
            (emitter.axis - want).abs().max_element() < 1e-6,
            "light at {offset}: axis {} instead of {want}",
            emitter.axis
        );
    }
}
