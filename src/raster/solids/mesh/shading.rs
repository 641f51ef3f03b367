//! Mesh shading, per band: a pixel whose samples hit the mesh is shaded once per layer its
//! samples see, with perspective-correct barycentrics (λᵢ ∝ eᵢ/zᵢ) of the layer's first
//! sample's triangle interpolating position, normal and texture coordinates.
//!
//! A layer is the samples on one surface (material) at about one depth: a sample joins the
//! layer of an earlier one when it hits the same triangle, or the same surface within
//! [`LAYER_GAP_PX`] pixel footprints of depth. So a pixel inside a triangle, or on an edge
//! between two triangles of one continuous surface, is shaded once (the edge shows no seam);
//! a pixel where an arm passes in front of the trunk, or where the shirt meets the neck's skin,
//! is shaded once for each, and the layers are averaged by their samples: those edges are
//! anti-aliased as the silhouette is, instead of taking the colour of one sample. The colour
//! is blended by the covered fraction (1/4 steps at a silhouette), the coverage channel
//! composites the same fraction with "over", and depth (the nearest covered sample's) is
//! written where at least half the samples are covered.

use glam::{Vec2, Vec3};

use super::model::Mesh;
use super::screen_tri::{ScreenTri, edges};
use super::visibility::{Band, NONE, SAMPLE_OFFSETS, SAMPLES};

/// Depth difference, in pixel footprints at the sample's depth (`depth / focal_px`), beyond
/// which two samples of one surface are different layers. A continuous surface changes depth
/// by less than that across a pixel unless it is seen within about 27° of edge-on
/// (tan⁻¹(1/2)), where shading its layers apart only costs a shade; an arm 1 cm in front of
/// the trunk, 2.5 m away at 360 px of 30°, is 5.5 footprints apart.
pub(super) const LAYER_GAP_PX: f32 = 2.0;

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

/// Shades every pixel of `band`'s span that the mesh covers, once per layer
/// (`shade(position, normal, albedo)`), and composites it into `px`. `inv_focal_px` is the
/// camera's 1 / focal length in pixels (a pixel's footprint per metre of depth).
pub(super) fn shade_band(
    band: &Band,
    tris: &[ScreenTri],
    mesh: &Mesh,
    shade: &(impl Fn(Vec3, Vec3, Vec3) -> Vec3 + Sync),
    samples: Samples,
    (px, inv_focal_px): (Pixels, f32),
) {
    let (x_lo, x_hi) = band.span;
    for i in (0..band.rows).flat_map(|row| row * band.w + x_lo..row * band.w + x_hi) {
        let hits = &samples.tri[i * SAMPLES..(i + 1) * SAMPLES];
        let depths = &samples.depth[i * SAMPLES..(i + 1) * SAMPLES];
        // Most pixels are missed by every sample or inside one triangle.
        let (layers, count) = if hits.iter().all(|&t| t == hits[0]) {
            if hits[0] == NONE {
                continue;
            }
            ([(0, SAMPLES); SAMPLES], 1)
        } else {
            layers_of(hits, depths, tris, LAYER_GAP_PX * inv_focal_px)
        };
        if count == 0 {
            continue;
        }
        let (x, y) = (i % band.w, band.y0 + i / band.w);
        let (mut sum, mut last, mut shaded) = (Vec3::ZERO, Vec3::ZERO, 0);
        for &(first, n) in &layers[..count] {
            let t = &tris[hits[first] as usize];
            let (ox, oy) = SAMPLE_OFFSETS[first];
            let q = Vec2::new(x as f32 + ox, y as f32 + oy);
            let Some((p, nrm, albedo)) = surface_at(t, mesh, q) else {
                continue;
            };
            let c = shade(p, nrm, albedo);
            last = if c.is_finite() { c } else { Vec3::ZERO };
            sum += last * n as f32;
            shaded += n;
        }
        if shaded == 0 {
            continue;
        }
        // One layer: its colour as it is (no product and quotient to round).
        let c = if count == 1 {
            last
        } else {
            sum / shaded as f32
        };
        let a = shaded as f32 / SAMPLES as f32;
        // Weighted, not `dst + (c − dst)·a`: against a background 1e7 times brighter, the
        // difference loses `c` to rounding and a fully covered pixel came out black.
        px.color[i] = px.color[i] * (1.0 - a) + c * a;
        px.coverage[i] += (1.0 - px.coverage[i]) * a;
        if 2 * shaded >= SAMPLES {
            px.depth[i] = depths[layers[0].0];
        }
    }
}

/// The layers a pixel's samples see (see the module doc): for each, its first sample and
/// how many samples it has, in the order of their first samples; and how many layers.
/// `gap_per_m` is the depth difference per metre of depth beyond which samples of one surface
/// are apart.
#[inline]
fn layers_of(
    hits: &[u32],
    depths: &[f32],
    tris: &[ScreenTri],
    gap_per_m: f32,
) -> ([(usize, usize); SAMPLES], usize) {
    let mut layers = [(0, 0); SAMPLES];
    let mut count = 0;
    for s in 0..SAMPLES {
        let t = hits[s];
        if t == NONE {
            continue;
        }
        let joins = layers[..count].iter().position(|&(f, _)| {
            let u = hits[f];
            u == t
                || (tris[u as usize].surface == tris[t as usize].surface
                    && (depths[s] - depths[f]).abs() <= gap_per_m * depths[f])
        });
        match joins {
            Some(k) => layers[k].1 += 1,
            None => {
                layers[count] = (s, 1);
                count += 1;
            }
        }
    }
    (layers, count)
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
