use super::*;
use proptest::prelude::*;

fn quad_mesh(z: f32, half: f32) -> (Vec<Vec3>, Vec<Vec3>, Vec<[u32; 3]>) {
    let p = vec![
        Vec3::new(-half, -half, z),
        Vec3::new(half, -half, z),
        Vec3::new(half, half, z),
        Vec3::new(-half, half, z),
    ];
    (p, vec![Vec3::Z; 4], vec![[0, 1, 2], [0, 2, 3]])
}

fn draw(fb: &mut Framebuffer, cam: &Camera, p: &[Vec3], n: &[Vec3], t: &[[u32; 3]], sided: bool) {
    let surfaces = [Surface {
        albedo: Vec3::ONE,
        texture: None,
        double_sided: sided,
    }];
    let ts = vec![0u16; t.len()];
    let mesh = Mesh {
        positions: p,
        normals: n,
        uv: &[],
        triangles: t,
        triangle_surface: &ts,
        surfaces: &surfaces,
        textures: &[],
    };
    draw_mesh(
        fb,
        cam,
        &mesh,
        |_, n, a| a * n.z.max(0.0),
        &mut MeshScratch::default(),
    );
}

/// A square facing the camera covers its projected area (the diagonal seam between its two
/// triangles is fully covered), its depth is the plane's, and its back face is culled.
#[test]
fn square_covers_its_projection_without_a_seam() {
    let cam = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, Vec3::Y, 0.8, 200, 200);
    let (p, n, t) = quad_mesh(0.0, 0.5);
    let mut fb = Framebuffer::new(200, 200, Vec3::ZERO);
    draw(&mut fb, &cam, &p, &n, &t, false);
    // Projected side: 2·f·0.5/3 pixels.
    let side = 2.0 * cam.focal_px() * 0.5 / 3.0;
    let area: f32 = fb.coverage.iter().sum();
    assert!(
        (area - side * side).abs() < 4.0 * side * 0.25,
        "{area} vs {}",
        side * side
    );
    let centre = 100 * 200 + 100;
    assert!((fb.depth[centre] - 3.0).abs() < 1e-4);
    assert_eq!(fb.color[centre], Vec3::ONE);
    // Along the diagonal seam every pixel well inside is fully covered.
    for k in 80..120 {
        assert_eq!(fb.coverage[k * 200 + k], 1.0, "seam pixel {k}");
    }
    // Seen from behind: culled, unless double-sided (then lit from its flipped normal).
    let back = Camera::look_at(
        Vec3::new(0.0, 0.0, -3.0),
        Vec3::ZERO,
        Vec3::Y,
        0.8,
        200,
        200,
    );
    let mut fb = Framebuffer::new(200, 200, Vec3::ZERO);
    draw(&mut fb, &back, &p, &n, &t, false);
    assert!(fb.coverage.iter().all(|a| *a == 0.0));
    let mut fb = Framebuffer::new(200, 200, Vec3::ZERO);
    draw(&mut fb, &back, &p, &n, &t, true);
    assert!(fb.coverage[centre] == 1.0 && fb.color[centre] == Vec3::ZERO);
}

/// Two squares at different depths: the nearer one wins whatever the order, and an opaque
/// depth already in the buffer hides the mesh behind it.
#[test]
fn depth_test_keeps_the_nearest_surface() {
    let cam = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, Vec3::Y, 0.8, 64, 64);
    let (mut p, mut n, mut t) = quad_mesh(0.5, 0.3);
    let (p2, n2, t2) = quad_mesh(0.0, 0.6);
    let base = p.len() as u32;
    p.extend(p2);
    n.extend(n2);
    t.extend(t2.iter().map(|tri| tri.map(|i| i + base)));
    let mut fb = Framebuffer::new(64, 64, Vec3::ZERO);
    draw(&mut fb, &cam, &p, &n, &t, false);
    let centre = 32 * 64 + 32;
    assert!(
        (fb.depth[centre] - 2.5).abs() < 1e-4,
        "{}",
        fb.depth[centre]
    );
    let mut fb = Framebuffer::new(64, 64, Vec3::ZERO);
    fb.depth[centre] = 1.0;
    draw(&mut fb, &cam, &p, &n, &t, false);
    assert_eq!(fb.depth[centre], 1.0);
    assert_eq!(fb.coverage[centre], 0.0);
}

/// A triangle crossing the near plane and one behind the eye: clipped and dropped, finite
/// output; degenerate and non-finite input draws nothing.
#[test]
fn near_plane_and_hostile_input() {
    let cam = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, Vec3::Y, 0.8, 50, 40);
    let p = vec![
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(0.0, 1.0, 5.0),
        Vec3::new(0.0, 0.0, 10.0),
        Vec3::new(1.0, 0.0, 10.0),
        Vec3::new(0.0, 1.0, 10.0),
        Vec3::NAN,
    ];
    let n = vec![Vec3::Z; p.len()];
    let t = vec![[0, 1, 2], [3, 4, 5], [0, 1, 6], [0, 0, 1], [0, 1, 99]];
    let mut fb = Framebuffer::new(50, 40, Vec3::ZERO);
    draw(&mut fb, &cam, &p, &n, &t, true);
    assert!(fb.color.iter().all(|c| c.is_finite()));
    assert!(fb.coverage.iter().any(|a| *a > 0.0));
    let mut fb = Framebuffer::new(50, 40, Vec3::ZERO);
    draw(&mut fb, &cam, &p, &n[..3], &t, true);
    assert!(fb.coverage.iter().all(|a| *a == 0.0));
}

#[test]
fn texture_sampling_is_bilinear_and_wraps() {
    let t = Texture {
        width: 2,
        height: 2,
        texels: vec![Vec3::ZERO, Vec3::ONE, Vec3::ONE, Vec3::ZERO],
    };
    // Texel centres.
    assert_eq!(t.sample(Vec2::new(0.25, 0.25)), Vec3::ZERO);
    assert_eq!(t.sample(Vec2::new(0.75, 0.25)), Vec3::ONE);
    // Half-way between the four: the mean; one period further: the same.
    assert!((t.sample(Vec2::new(0.5, 0.5)) - Vec3::splat(0.5)).length() < 1e-6);
    assert!((t.sample(Vec2::new(1.5, -0.5)) - Vec3::splat(0.5)).length() < 1e-6);
    // Non-finite coordinates read at (0, 0), between the four texels.
    assert!((t.sample(Vec2::NAN) - Vec3::splat(0.5)).length() < 1e-6);
}

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
