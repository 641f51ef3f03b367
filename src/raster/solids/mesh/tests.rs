use super::*;

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

/// Where a nearer part of the mesh passes in front of a farther part (an arm before the trunk),
/// the edge is anti-aliased as a silhouette is: a triangle at z = 0.5 with a sloped edge over a
/// square at z = 0, one surface, shaded by depth (0.5 in front, 0 behind). Every pixel is fully
/// covered, and the pixels the sloped edge crosses take the average of the samples' layers:
/// strictly between 0 and 0.5 (with one shade per pixel each would be exactly 0 or 0.5). The
/// sloped edges cross every row of the triangle's projected height (about 24 of the 64 × 64
/// image), each row with at least one intermediate pixel; interior pixels keep exactly their
/// layer's shade.
#[test]
fn an_inner_edge_between_two_depths_is_anti_aliased() {
    let cam = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, Vec3::Y, 0.8, 64, 64);
    let (mut p, mut n, mut t) = quad_mesh(0.0, 0.8);
    let base = p.len() as u32;
    p.extend([
        Vec3::new(-0.3, -0.4, 0.5),
        Vec3::new(0.3, -0.35, 0.5),
        Vec3::new(-0.05, 0.4, 0.5),
    ]);
    n.extend([Vec3::Z; 3]);
    t.push([base, base + 1, base + 2]);
    let surfaces = [Surface {
        albedo: Vec3::ONE,
        texture: None,
        double_sided: false,
    }];
    let ts = vec![0u16; t.len()];
    let mesh = Mesh {
        positions: &p,
        normals: &n,
        uv: &[],
        triangles: &t,
        triangle_surface: &ts,
        surfaces: &surfaces,
        textures: &[],
    };
    let mut fb = Framebuffer::new(64, 64, Vec3::ZERO);
    let mut scratch = MeshScratch::default();
    draw_mesh(
        &mut fb,
        &cam,
        &mesh,
        |q, _, _| Vec3::splat(q.z),
        &mut scratch,
    );
    let mut rows_with_mix = 0;
    for y in 0..64 {
        let row = &fb.color[y * 64..(y + 1) * 64];
        if row.iter().any(|c| c.x > 0.01 && c.x < 0.49) {
            rows_with_mix += 1;
        }
    }
    // The triangle spans y from −0.4 to 0.4 at depth 2.5: 0.8·f/2.5 ≈ 24.4 pixel rows
    // (f = 32/tan 0.4 ≈ 76.1).
    let f = cam.focal_px();
    let rows = 0.8 * f / 2.5;
    assert!(
        rows_with_mix as f32 >= rows - 2.0,
        "{rows_with_mix} of {rows}"
    );
    assert_eq!(fb.coverage[32 * 64 + 32], 1.0);
    assert!((fb.color[32 * 64 + 30].x - 0.5).abs() < 1e-5);
    assert_eq!(fb.color[5 * 64 + 5].x, 0.0);
}
