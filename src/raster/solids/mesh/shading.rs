//! Mesh shading, per band: a pixel whose samples hit the mesh is shaded once, at its first
//! covered sample, with perspective-correct barycentrics (λᵢ ∝ eᵢ/zᵢ) of that sample's
//! triangle interpolating position, normal and texture coordinates. The colour is blended by
//! the covered fraction (silhouettes get 1/4 steps; edges between two triangles of the mesh
//! are fully covered and show no seam), the coverage channel composites the same fraction
//! with "over", and depth is written where at least half the samples are covered.

use glam::{Vec2, Vec3};

use super::model::Mesh;
use super::screen_tri::{ScreenTri, edges};
use super::visibility::{Band, NONE, SAMPLE_OFFSETS, SAMPLES};

/// One band's pixels in the framebuffer, whole rows.
pub(super) struct Pixels<'a> {
    pub(super) color: &'a mut [Vec3],
    pub(super) depth: &'a mut [f32],
    pub(super) coverage: &'a mut [f32],
}

/// The band's visibility samples: each sample's depth and triangle ([`NONE`] where none).
#[derive(Clone, Copy)]
pub(super) struct Samples<'a> {
    pub(super) depth: &'a [f32],
    pub(super) tri: &'a [u32],
}

/// Shades every pixel of `band`'s span that the mesh covers, once (`shade(position, normal,
/// albedo)`), and composites it into `px`.
pub(super) fn shade_band(
    band: &Band,
    tris: &[ScreenTri],
    mesh: &Mesh,
    shade: &(impl Fn(Vec3, Vec3, Vec3) -> Vec3 + Sync),
    samples: Samples,
    px: Pixels,
) {
    let (x_lo, x_hi) = band.span;
    for i in (0..band.rows).flat_map(|row| row * band.w + x_lo..row * band.w + x_hi) {
        let hits = &samples.tri[i * SAMPLES..(i + 1) * SAMPLES];
        let covered = hits.iter().filter(|&&t| t != NONE).count();
        let Some(first) = hits.iter().position(|&t| t != NONE) else {
            continue;
        };
        let t = &tris[hits[first] as usize];
        let (x, y) = (i % band.w, band.y0 + i / band.w);
        let (ox, oy) = SAMPLE_OFFSETS[first];
        let Some((p, n, albedo)) = surface_at(t, mesh, Vec2::new(x as f32 + ox, y as f32 + oy))
        else {
            continue;
        };
        let c = shade(p, n, albedo);
        let c = if c.is_finite() { c } else { Vec3::ZERO };
        let a = covered as f32 / SAMPLES as f32;
        px.color[i] += (c - px.color[i]) * a;
        px.coverage[i] += (1.0 - px.coverage[i]) * a;
        if 2 * covered >= SAMPLES {
            px.depth[i] = samples.depth[i * SAMPLES + first];
        }
    }
}

/// The surface of triangle `t` of `mesh` at screen point `q`: world position, unit normal
/// (flipped on a back face) and albedo (the surface's, times its texture's); `None` where the
/// perspective-correct barycentrics do not exist.
#[inline]
fn surface_at(t: &ScreenTri, mesh: &Mesh, q: Vec2) -> Option<(Vec3, Vec3, Vec3)> {
    let e = edges(t, q);
    // Perspective-correct barycentrics: screen weights divided by depth.
    let wts = [e[0] * t.inv_z[0], e[1] * t.inv_z[1], e[2] * t.inv_z[2]];
    let sum = wts[0] + wts[1] + wts[2];
    if !(sum.abs() > 0.0) || !sum.is_finite() {
        return None;
    }
    let l = wts.map(|v| v / sum);
    let p = t.world[0] * l[0] + t.world[1] * l[1] + t.world[2] * l[2];
    let mut n =
        (t.normal[0] * l[0] + t.normal[1] * l[1] + t.normal[2] * l[2]).normalize_or(Vec3::Y);
    let surf = &mesh.surfaces[t.surface as usize];
    if !t.front {
        n = -n;
    }
    let albedo = match surf.texture.and_then(|i| mesh.textures.get(i as usize)) {
        Some(tex) => surf.albedo * tex.sample(t.uv[0] * l[0] + t.uv[1] * l[1] + t.uv[2] * l[2]),
        None => surf.albedo,
    };
    Some((p, n, albedo))
}
