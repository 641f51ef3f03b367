use super::raster::{RASTER_BAND_ROWS, TriangleSetup};
use super::*;

fn sphere(c: Vec3, r: f32) -> Solid {
    Solid {
        unit_sphere_to_world: Affine3A::from_scale_rotation_translation(
            Vec3::splat(r),
            glam::Quat::IDENTITY,
            c,
        ),
    }
}

/// A sphere of radius 5 cm lit along +X: points behind it (x > 0 inside its shadow
/// cylinder) are dark, points beside or in front are lit, and its lit surface does not
/// shadow itself.
#[test]
fn sphere_shadow_is_its_cylinder() {
    let frame = LightFrame::new(Vec3::X);
    let mut g = OccluderGrid::default();
    g.build(&frame, 0.002, &[sphere(Vec3::ZERO, 0.05)]);
    let vis = |p: Vec3| g.visibility(frame.to_map(p));
    assert!(vis(Vec3::new(0.2, 0.0, 0.0)) < 1e-6, "behind the centre");
    assert!(vis(Vec3::new(0.2, 0.03, 0.02)) < 1e-6, "behind, off-centre");
    assert_eq!(vis(Vec3::new(-0.2, 0.0, 0.0)), 1.0, "in front");
    assert_eq!(vis(Vec3::new(0.2, 0.06, 0.0)), 1.0, "beside the shadow");
    // Lit hemisphere: points on the surface facing the light.
    for a in [0.0f32, 0.5, 1.0, 1.3] {
        let p = Vec3::new(-a.cos(), a.sin(), 0.0) * 0.05;
        assert!(
            vis(p) > 0.99,
            "lit surface at {a} rad self-shadows: {}",
            vis(p)
        );
    }
}

/// Shadow edge: visibility rises from 0 to 1 within about a texel of the silhouette.
#[test]
fn shadow_edge_is_one_texel_wide() {
    let frame = LightFrame::new(Vec3::X);
    let mut g = OccluderGrid::default();
    let texel = 0.002;
    g.build(&frame, texel, &[sphere(Vec3::ZERO, 0.05)]);
    let vis = |y: f32| g.visibility(frame.to_map(Vec3::new(0.2, y, 0.0)));
    assert!(
        vis(0.05 - 1.5 * texel) < 0.02,
        "{}",
        vis(0.05 - 1.5 * texel)
    );
    assert!(
        vis(0.05 + 1.5 * texel) > 0.98,
        "{}",
        vis(0.05 + 1.5 * texel)
    );
    let mut last = 0.0;
    for k in 0..40 {
        let v = vis(0.05 - 2.0 * texel + k as f32 * 0.1 * texel);
        assert!(v + 1e-6 >= last, "visibility must rise across the edge");
        last = v;
    }
}

#[test]
fn degenerate_solids_and_points_are_harmless() {
    let frame = LightFrame::new(Vec3::new(0.3, -1.0, 0.2));
    let mut g = OccluderGrid::default();
    g.build(
        &frame,
        0.002,
        &[
            sphere(Vec3::ZERO, 0.0),
            sphere(Vec3::splat(f32::NAN), 0.1),
            sphere(Vec3::splat(1e30), 1e30),
        ],
    );
    for p in [Vec3::ZERO, Vec3::NAN, Vec3::splat(1e30)] {
        let v = g.visibility(p);
        assert!((0.0..=1.0).contains(&v), "{v}");
    }
    g.build(&frame, 0.0, &[sphere(Vec3::ZERO, 0.1)]);
    assert_eq!(g.visibility(Vec3::new(0.0, 1.0, 0.0)), 1.0);
}

/// A tilted square of two triangles, many bands of rows tall, lit along +X: every texel
/// centre inside it holds the plane's depth there (the entry depth), every one outside
/// holds none, on both sides of each band's edge; a second, deeper copy changes nothing
/// (a texel keeps the shallowest).
#[test]
fn a_mesh_fills_each_texel_inside_it_with_its_plane_across_the_bands() {
    let frame = LightFrame::new(Vec3::X);
    // The plane x = 0.1 + 0.5·y − 0.25·z over |y|, |z| ≤ 0.08 (world = map axes here up
    // to the frame's own; built from map coordinates and taken back to world).
    let plane = |y: f32, z: f32| 0.1 + 0.5 * y - 0.25 * z;
    let (h, deeper) = (0.08, 0.05);
    let mut corners = Vec::new();
    for shift in [0.0, deeper] {
        for (y, z) in [(-h, -h), (h, -h), (h, h), (-h, h)] {
            corners.push(frame.to_world(Vec3::new(plane(y, z) + shift, y, z)));
        }
    }
    let triangles = [[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]];
    let mut g = OccluderGrid::default();
    let texel = 0.002;
    g.build_with_mesh(
        &Projection::Parallel { frame },
        texel,
        &[],
        OccluderMesh {
            positions: &corners,
            triangles: &triangles,
        },
    );
    assert!(g.dims[0] > 4 * RASTER_BAND_ROWS, "{:?}", g.dims);
    let (mut inside, mut outside) = (0, 0);
    for i in 0..g.dims[0] {
        for j in 0..g.dims[1] {
            let yz = g.origin + (Vec2::new(i as f32, j as f32) + 0.5) * g.texel_m;
            let d = g.depth[i * g.dims[1] + j];
            let margin = 1e-4;
            if yz.abs().max_element() < h - margin {
                inside += 1;
                assert!((d - plane(yz.x, yz.y)).abs() < 1e-5, "({i}, {j}): {d}");
            } else if yz.abs().max_element() > h + margin {
                outside += 1;
                assert_eq!(d, f32::INFINITY, "({i}, {j})");
            }
        }
    }
    assert!(inside > 5000 && outside > 0, "{inside} {outside}");
}

/// Every texel centre of the triangle's box tested one by one: the reference that
/// `TriangleSetup::rasterise`, which visits only each row's span, must match.
fn rasterise_whole_box(
    t: &TriangleSetup,
    band: std::ops::Range<usize>,
    cols: usize,
    rows: &mut [f32],
) {
    let (i0, i1) = (t.i0.max(band.start as i64), t.i1.min(band.end as i64 - 1));
    let q = &t.q;
    for i in i0..=i1 {
        for j in t.j0..=t.j1 {
            let p = Vec2::new(i as f32, j as f32);
            let l = [
                (q[1] - p).perp_dot(q[2] - p) * t.inv,
                (q[2] - p).perp_dot(q[0] - p) * t.inv,
                (q[0] - p).perp_dot(q[1] - p) * t.inv,
            ];
            if l[0] >= 0.0 && l[1] >= 0.0 && l[2] >= 0.0 {
                let d = l[0] * t.depth[0] + l[1] * t.depth[1] + l[2] * t.depth[2];
                let texel = &mut rows[(i as usize - band.start) * cols + j as usize];
                *texel = texel.min(d);
            }
        }
    }
}

use proptest::prelude::*;

proptest! {
    /// Rows by their spans fill the texels the whole box filled, to the bit: triangles of
    /// any shape (slivers included) over a 40 × 40 grid, in bands of 16 rows, with depths
    /// already there.
    #[test]
    fn rows_by_their_spans_fill_what_the_box_filled(
        c in prop::array::uniform3((-0.5f32..1.5, -0.01f32..0.09, -0.01f32..0.09)),
        sliver in prop_oneof![Just(None), (0.0f32..1.0, -1e-4f32..1e-4).prop_map(Some)],
    ) {
        let mut c = c.map(|(x, y, z)| Vec3::new(x, y, z));
        if let Some((along, off)) = sliver {
            let d = c[1] - c[0];
            c[2] = c[0] + d * along + Vec3::new(0.0, -d.z, d.y).normalize_or_zero() * off;
        }
        let (origin, texel, dims) = (Vec2::ZERO, 0.002, [40, 40]);
        let Some(t) = TriangleSetup::new(c, origin, texel, dims) else { return Ok(()) };
        let start: Vec<f32> = (0..1600).map(|k| if k % 3 == 0 { f32::INFINITY } else { (k % 7) as f32 * 0.1 }).collect();
        for b in 0..3 {
            let band = b * 16..(b * 16 + 16).min(40);
            let n = band.len() * 40;
            let (mut a, mut z) = (start[..n].to_vec(), start[..n].to_vec());
            rasterise_whole_box(&t, band.clone(), 40, &mut a);
            t.rasterise(band.clone(), 40, &mut z);
            for k in 0..n {
                prop_assert_eq!(a[k].to_bits(), z[k].to_bits(), "band {} texel {}", b, k);
            }
        }
    }
}
