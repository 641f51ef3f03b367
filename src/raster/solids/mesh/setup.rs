//! Mesh set-up, serial and in input order: each triangle's corners to view space, clipped to
//! the near plane there (before the perspective division, which would flip points behind the
//! eye), projected, back faces of single-sided surfaces culled, and each remaining triangle
//! binned into the bands of [`BAND_ROWS`] rows its screen box touches.

use glam::{Vec2, Vec3};

use super::model::Mesh;
use super::screen_tri::{ScreenTri, screen_box};
use crate::raster::camera::View;

/// Image rows per band.
pub(super) const BAND_ROWS: usize = 16;

/// Transforms, clips, culls and bins every triangle of `mesh` into `tris` and `bins` (per
/// band, the indices in `tris` of the triangles whose screen box touches it, in input order).
/// Triangles with an index out of range, no surface or a non-finite corner, and every
/// triangle of a mesh whose normals do not match its positions, are left out.
pub(super) fn set_up(
    view: &View,
    mesh: &Mesh,
    tris: &mut Vec<ScreenTri>,
    bins: &mut Vec<Vec<u32>>,
) {
    let bands = (view.height as usize).div_ceil(BAND_ROWS);
    tris.clear();
    bins.resize_with(bands, Vec::new);
    bins.iter_mut().for_each(Vec::clear);
    if mesh.normals.len() != mesh.positions.len() {
        return;
    }
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let Some(c) = Corners::of(mesh, t, tri) else {
            continue;
        };
        let (poly, count) = clip_near(c.world.map(|p| view.to_view(p)), view.near_m);
        for k in 1..count.saturating_sub(1) {
            let st = screen_tri(view, &c, [poly[0], poly[k], poly[k + 1]]);
            if !(st.area2.abs() > 1e-12) || !st.area2.is_finite() || (!st.front && !c.double_sided)
            {
                continue;
            }
            bin(view, st, tris, bins);
        }
    }
}

/// A triangle's corners as the mesh gives them: world position, normal and texture
/// coordinates (0 where the mesh has none), with its surface.
struct Corners {
    world: [Vec3; 3],
    normal: [Vec3; 3],
    uv: [Vec2; 3],
    surface: u16,
    double_sided: bool,
}

impl Corners {
    /// Triangle `t` (vertex indices `tri`) of `mesh`; `None` where an index is out of range,
    /// it has no surface, or a corner is not finite.
    #[inline]
    fn of(mesh: &Mesh, t: usize, tri: &[u32; 3]) -> Option<Corners> {
        if tri.iter().any(|&i| i as usize >= mesh.positions.len()) {
            return None;
        }
        let surface = *mesh.triangle_surface.get(t)?;
        let surf = mesh.surfaces.get(surface as usize)?;
        let world = tri.map(|i| mesh.positions[i as usize]);
        if world.iter().any(|p| !p.is_finite()) {
            return None;
        }
        Some(Corners {
            world,
            normal: tri.map(|i| mesh.normals[i as usize]),
            uv: tri.map(|i| mesh.uv.get(i as usize).copied().unwrap_or(Vec2::ZERO)),
            surface,
            double_sided: surf.double_sided,
        })
    }
}

/// A corner of a clipped triangle: its view-space position and its weights over the
/// triangle's three original corners.
type ClipCorner = (Vec3, [f32; 3]);

/// The triangle with view-space corners `v` clipped to depth ≥ `near`: a polygon of up to 4
/// corners (the first `count` of the array), each a blend of the triangle's corners.
#[inline]
fn clip_near(v: [Vec3; 3], near: f32) -> ([ClipCorner; 4], usize) {
    let mut poly: [ClipCorner; 4] = [(Vec3::ZERO, [0.0; 3]); 4];
    let mut count = 0;
    for i in 0..3 {
        let j = (i + 1) % 3;
        let (a, b) = (v[i], v[j]);
        let a_in = a.z >= near;
        let b_in = b.z >= near;
        if a_in {
            let mut wts = [0.0; 3];
            wts[i] = 1.0;
            poly[count] = (a, wts);
            count += 1;
        }
        if a_in != b_in {
            let s = (near - a.z) / (b.z - a.z);
            let mut wts = [0.0; 3];
            wts[i] = 1.0 - s;
            wts[j] = s;
            poly[count] = (a.lerp(b, s), wts);
            count += 1;
        }
    }
    (poly, count)
}

/// The screen triangle of clipped corners `corners` of `c`: projected, its attributes blended
/// by each corner's weights, its signed area and facing.
#[inline]
fn screen_tri(view: &View, c: &Corners, corners: [ClipCorner; 3]) -> ScreenTri {
    let mut st = ScreenTri {
        p: [Vec2::ZERO; 3],
        inv_z: [0.0; 3],
        world: [Vec3::ZERO; 3],
        normal: [Vec3::ZERO; 3],
        uv: [Vec2::ZERO; 3],
        surface: c.surface,
        front: true,
        area2: 0.0,
    };
    let (world, normal, uv) = (c.world, c.normal, c.uv);
    for (k, (pv, wts)) in corners.iter().enumerate() {
        let (x, y) = view.view_to_pixel(*pv);
        st.p[k] = Vec2::new(x, y);
        st.inv_z[k] = 1.0 / pv.z;
        st.world[k] = world[0] * wts[0] + world[1] * wts[1] + world[2] * wts[2];
        st.normal[k] = normal[0] * wts[0] + normal[1] * wts[1] + normal[2] * wts[2];
        st.uv[k] = uv[0] * wts[0] + uv[1] * wts[1] + uv[2] * wts[2];
    }
    let [p0, p1, p2] = st.p;
    st.area2 = (p1 - p0).perp_dot(p2 - p0);
    // Screen y grows down, so a counter-clockwise (front) face has a negative area.
    st.front = st.area2 < 0.0;
    st
}

/// Appends `st` to `tris` and its index to the bins of the bands its screen box touches,
/// unless the box lies off the image.
#[inline]
fn bin(view: &View, st: ScreenTri, tris: &mut Vec<ScreenTri>, bins: &mut [Vec<u32>]) {
    let h = view.height as usize;
    let (lo, hi) = screen_box(&st);
    if !(hi.x >= 0.0 && lo.x <= view.width as f32 && hi.y >= 0.0 && lo.y <= h as f32) {
        return;
    }
    let y0 = lo.y.max(0.0) as usize;
    let y1 = (hi.y.min(h as f32 - 1.0).max(0.0) as usize).min(h - 1);
    let index = tris.len() as u32;
    tris.push(st);
    for bin in &mut bins[y0 / BAND_ROWS..=y1 / BAND_ROWS] {
        bin.push(index);
    }
}
