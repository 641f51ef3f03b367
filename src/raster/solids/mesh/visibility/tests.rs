use glam::{Vec2, Vec3};
use proptest::prelude::*;

use super::*;
use crate::raster::solids::mesh::screen_tri::edges;

/// The one-sample-at-a-time loop `Band::rasterise` replaced (every sample of the screen box,
/// `edges` per sample): its reference.
fn rasterise_per_sample(
    band: &Band,
    t: &ScreenTri,
    index: u32,
    s_depth: &mut [f32],
    s_tri: &mut [u32],
) {
    let (lo, hi) = screen_box(t);
    let (x0, x1) = band.columns((lo, hi));
    let r0 = (lo.y.max(band.y0 as f32).floor() as usize).max(band.y0);
    let r1 = (hi.y.min((band.y0 + band.rows) as f32).ceil() as usize).min(band.y0 + band.rows);
    let inv_area = 1.0 / t.area2;
    for y in r0..r1 {
        let row = (y - band.y0) * band.w;
        for x in x0..x1 {
            for (s, (ox, oy)) in SAMPLE_OFFSETS.iter().enumerate() {
                let e = edges(t, Vec2::new(x as f32 + ox, y as f32 + oy));
                let l = [e[0] * inv_area, e[1] * inv_area, e[2] * inv_area];
                if !(l[0] >= 0.0 && l[1] >= 0.0 && l[2] >= 0.0) {
                    continue;
                }
                let inv_z = l[0] * t.inv_z[0] + l[1] * t.inv_z[1] + l[2] * t.inv_z[2];
                let k = (row + x) * SAMPLES + s;
                if inv_z > 0.0 && inv_z * s_depth[k] > 1.0 {
                    s_depth[k] = 1.0 / inv_z;
                    s_tri[k] = index;
                }
            }
        }
    }
}

/// A screen triangle with corners `p` (pixels) and depths `z`, as `set_up` makes them.
fn screen_tri(p: [Vec2; 3], z: [f32; 3]) -> ScreenTri {
    let area2 = (p[1] - p[0]).perp_dot(p[2] - p[0]);
    ScreenTri {
        p,
        inv_z: z.map(|z| 1.0 / z),
        world: [Vec3::ZERO; 3],
        normal: [Vec3::Z; 3],
        uv: [Vec2::ZERO; 3],
        surface: 0,
        front: area2 < 0.0,
        area2,
    }
}

/// Both loops over a 48 × 32 band of rows 16..48 (starting from a depth buffer holding `far`
/// everywhere): the same depth and triangle bits at every sample.
fn same_samples(t: &ScreenTri, far: f32) -> Result<(), TestCaseError> {
    let band = Band {
        y0: 16,
        rows: 32,
        w: 48,
        span: (0, 48),
    };
    let n = band.rows * band.w * SAMPLES;
    let (mut d0, mut t0) = (vec![far; n], vec![NONE; n]);
    let (mut d1, mut t1) = (d0.clone(), t0.clone());
    rasterise_per_sample(&band, t, 7, &mut d0, &mut t0);
    band.rasterise(t, 7, &mut d1, &mut t1);
    for k in 0..n {
        prop_assert_eq!(t0[k], t1[k], "sample {} of {:?}", k, t.p);
        prop_assert_eq!(
            d0[k].to_bits(),
            d1[k].to_bits(),
            "sample {} of {:?}",
            k,
            t.p
        );
    }
    Ok(())
}

fn corner() -> impl Strategy<Value = Vec2> {
    (-20.0f32..70.0, 0.0f32..64.0).prop_map(|(x, y)| Vec2::new(x, y))
}

proptest! {
    /// Rows narrowed to their spans and samples tested side by side give what testing every
    /// sample of the screen box gave, to the bit: triangles of any shape about the band,
    /// either winding, at any depths.
    #[test]
    fn rows_by_their_spans_are_the_per_sample_loop(
        a in corner(), b in corner(), c in corner(),
        z in (0.5f32..5.0, 0.5f32..5.0, 0.5f32..5.0),
        far in prop_oneof![Just(f32::INFINITY), 0.5f32..5.0],
    ) {
        let t = screen_tri([a, b, c], [z.0, z.1, z.2]);
        prop_assume!(t.area2.abs() > 1e-12);
        same_samples(&t, far)?;
    }

    /// Slivers (a corner a hair's breadth off the opposite edge), nearly level or upright
    /// edges and corners far off screen: the spans still hold every covered sample.
    #[test]
    fn slivers_and_far_corners_keep_every_sample(
        a in corner(), b in corner(),
        off in prop_oneof![-1e-3f32..1e-3, -0.3f32..0.3],
        along in -2.0f32..3.0,
        far_x in prop_oneof![Just(0.0f32), -1e5f32..1e5],
    ) {
        let d = b - a;
        let normal = Vec2::new(-d.y, d.x).normalize_or_zero();
        let c = a + d * along + normal * off + Vec2::new(far_x, 0.0);
        let t = screen_tri([a, b, c], [1.0, 2.0, 3.0]);
        prop_assume!(t.area2.abs() > 1e-12 && t.area2.is_finite());
        same_samples(&t, f32::INFINITY)?;
        let level = screen_tri([a, Vec2::new(b.x, a.y + off), c], [1.0, 1.0, 1.0]);
        if level.area2.abs() > 1e-12 && level.area2.is_finite() {
            same_samples(&level, f32::INFINITY)?;
        }
    }
}
