//! Opaque triangle meshes (a character's body): depth-tested, anti-aliased, shaded once per
//! pixel by a caller's closure.
//!
//! What: [`draw_mesh`] draws every triangle nearer than what the depth buffer holds, shades each
//! covered pixel once (`shade(world position, unit normal, albedo)`) and anti-aliases the
//! silhouette; it writes depth where the mesh covers at least half of a pixel, so hair behind
//! the body is hidden and hair in front is drawn over it.
//!
//! How, per frame:
//! 1. **Set-up** (serial, in input order): vertices go to view space; triangles behind the near
//!    plane are dropped, those crossing it are clipped there in view space (before the
//!    perspective division, which would flip points behind the eye), back faces of
//!    single-sided surfaces are culled, and each remaining triangle is binned into the 16-row
//!    bands its screen box touches.
//! 2. **Visibility** (parallel over bands): four samples per pixel in a rotated grid (offsets
//!    1/8, 3/8, 5/8, 7/8, the pattern of 4× multisampling) keep the nearest triangle and its
//!    depth (1/z interpolated linearly on screen, exact under perspective). Samples start at the
//!    framebuffer's depth, so solids drawn before (the head ellipsoid) hide what is behind them.
//!    Each row of a triangle visits only the columns its strip can reach (not its whole screen
//!    box: half of it for a typical triangle, nearly all of it for a sliver), and a pixel's
//!    four samples are tested side by side in one vector, lane by lane the same arithmetic as
//!    one sample at a time: the same bits (the tests hold the per-sample loop as reference),
//!    the frame's raster stage 13.9 → 12.4 ms on 2 threads at 1280×720 (BENCHMARKS.md).
//! 3. **Shading** (same band task): a pixel whose samples hit the mesh is shaded once, at its
//!    first covered sample, with perspective-correct barycentrics (λᵢ ∝ eᵢ/zᵢ) of that
//!    sample's triangle interpolating position, normal and texture coordinates; the colour is
//!    blended by the covered fraction (silhouettes get 1/4 steps; edges between two triangles
//!    of the mesh are fully covered and show no seam), and the coverage channel composites the
//!    same fraction with "over", as for ellipsoids.
//!
//! Deterministic for any thread count: a band is drawn by one task, its triangles in input
//! order, with strict depth tests (the first triangle wins a tie).
//!
//! Why this design: shading dominates (each pixel of skin reads the light map, about 100 ns),
//! so visibility first and one shade per pixel costs the least; multisampling only the
//! visibility buys anti-aliased silhouettes for four depth tests per pixel. Rejected: shading
//! in the raster loop (overdraw shades hidden pixels: a body has 2–3 layers where arms cross it)
//! and per-vertex (Gouraud) lighting, which blurs hair shadows over the 2–5 cm between a
//! low-poly mesh's vertices.

use glam::{Vec2, Vec3, Vec4};
use rayon::prelude::*;

use crate::raster::camera::{Camera, View};
use crate::raster::framebuffer::Framebuffer;
use crate::tri_span;

/// Image rows per band.
const BAND_ROWS: usize = 16;
/// Samples per pixel, and their offsets inside the pixel (rotated grid).
const SAMPLES: usize = 4;
const SAMPLE_OFFSETS: [(f32, f32); SAMPLES] = [
    (0.375, 0.125),
    (0.875, 0.375),
    (0.125, 0.625),
    (0.625, 0.875),
];
/// A sample that no triangle covers.
const NONE: u32 = u32::MAX;

/// A texture: linear RGB texels, rows top to bottom.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Texture {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<Vec3>,
}

impl Texture {
    /// Bilinear sample at `uv` with repeat wrapping; texel centres at half-integers (glTF's
    /// default sampler). A malformed texture or non-finite coordinates read white / texel 0.
    #[inline]
    pub fn sample(&self, uv: Vec2) -> Vec3 {
        let (w, h) = (self.width as i64, self.height as i64);
        if w == 0 || h == 0 || self.texels.len() as i64 != w * h {
            return Vec3::ONE;
        }
        let uv = if uv.is_finite() && uv.abs().max_element() < 1e6 {
            uv - uv.floor()
        } else {
            Vec2::ZERO
        };
        let (x, y) = (uv.x * w as f32 - 0.5, uv.y * h as f32 - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let at = |i: i64, j: i64| self.texels[(j.rem_euclid(h) * w + i.rem_euclid(w)) as usize];
        let (i, j) = (x0 as i64, y0 as i64);
        let top = at(i, j).lerp(at(i + 1, j), fx);
        let bottom = at(i, j + 1).lerp(at(i + 1, j + 1), fx);
        top.lerp(bottom, fy)
    }
}

/// How a group of triangles looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// Linear RGB albedo (multiplied by the texture when there is one).
    pub albedo: Vec3,
    /// Index into [`Mesh::textures`].
    pub texture: Option<u32>,
    /// Draw back faces too (their normal is flipped toward the eye).
    pub double_sided: bool,
}

/// A triangle mesh in world space.
#[derive(Clone, Copy, Debug)]
pub struct Mesh<'a> {
    pub positions: &'a [Vec3],
    /// Unit vertex normals.
    pub normals: &'a [Vec3],
    /// Texture coordinates per vertex (may be empty when no surface has a texture).
    pub uv: &'a [Vec2],
    /// Vertex indices; counter-clockwise seen from the front.
    pub triangles: &'a [[u32; 3]],
    /// Index into `surfaces` per triangle.
    pub triangle_surface: &'a [u16],
    pub surfaces: &'a [Surface],
    pub textures: &'a [Texture],
}

/// A triangle ready to rasterise: screen positions, 1/depth and the attributes at its corners.
#[derive(Clone, Copy, Debug)]
struct ScreenTri {
    p: [Vec2; 3],
    inv_z: [f32; 3],
    world: [Vec3; 3],
    normal: [Vec3; 3],
    uv: [Vec2; 3],
    surface: u16,
    /// Front-facing (for double-sided surfaces seen from behind, normals are flipped).
    front: bool,
    /// Twice the signed screen area (non-zero).
    area2: f32,
}

/// Buffers reused across frames (allocation-free once sized).
#[derive(Debug, Default)]
pub struct MeshScratch {
    tris: Vec<ScreenTri>,
    bins: Vec<Vec<u32>>,
    sample_depth: Vec<f32>,
    sample_tri: Vec<u32>,
}

impl MeshScratch {
    /// Bytes held for an image of `width` × `height` and `triangles` triangles (each may be
    /// clipped into two and binned into a few bands).
    pub fn estimated_bytes(width: u32, height: u32, triangles: u64) -> u64 {
        let samples = width as u64 * height as u64 * SAMPLES as u64;
        samples * (size_of::<f32>() + size_of::<u32>()) as u64
            + triangles * (2 * size_of::<ScreenTri>() as u64 + 4 * size_of::<u32>() as u64)
    }
}

/// Draws `mesh` (see the module doc). `shade(position, normal, albedo)` gives a pixel's linear
/// RGB colour; it is called once per covered pixel, from several threads. Inconsistent input
/// (index out of range, lists of different lengths, non-finite vertices) draws the triangles
/// it concerns as nothing, never panics. As for lines, the framebuffer's size overrides the
/// camera's.
pub fn draw_mesh(
    fb: &mut Framebuffer,
    cam: &Camera,
    mesh: &Mesh,
    shade: impl Fn(Vec3, Vec3, Vec3) -> Vec3 + Sync,
    scratch: &mut MeshScratch,
) {
    let (w, h) = (fb.width as usize, fb.height as usize);
    if w == 0 || h == 0 || !fb.is_consistent() {
        return;
    }
    let Some(view) = cam.view_for(fb.width, fb.height) else {
        return;
    };
    set_up(&view, mesh, scratch);
    let bands = h.div_ceil(BAND_ROWS);
    let n = w * h * SAMPLES;
    scratch.sample_depth.resize(n, f32::INFINITY);
    scratch.sample_tri.resize(n, NONE);
    let tris = &scratch.tris;
    let bins = &scratch.bins;
    let rows = BAND_ROWS * w;
    fb.color
        .par_chunks_mut(rows)
        .zip(fb.depth.par_chunks_mut(rows))
        .zip(fb.coverage.par_chunks_mut(rows))
        .zip(scratch.sample_depth.par_chunks_mut(rows * SAMPLES))
        .zip(scratch.sample_tri.par_chunks_mut(rows * SAMPLES))
        .enumerate()
        .take(bands)
        // One job per band: the character's bands cost unevenly (`lines.rs` says why).
        .with_max_len(1)
        .for_each(|(b, ((((color, depth), coverage), s_depth), s_tri))| {
            let band = Band {
                y0: b * BAND_ROWS,
                rows: depth.len() / w,
                w,
                span: (0, w),
            };
            if bins[b].is_empty() {
                return;
            }
            // Only the columns the band's triangles can touch (the union of their boxes) are
            // set up and shaded: the rest of the band keeps what is there, as it would with
            // every sample missed (the character fills about a third of a frame's width).
            let span = bins[b]
                .iter()
                .map(|&t| band.columns(screen_box(&tris[t as usize])))
                .fold((w, 0), |(lo, hi), (x0, x1)| (lo.min(x0), hi.max(x1)));
            let band = Band { span, ..band };
            // Samples start at the opaque depth already there.
            for row in 0..band.rows {
                for px in row * w + span.0..row * w + span.1 {
                    s_depth[px * SAMPLES..(px + 1) * SAMPLES].fill(depth[px]);
                    s_tri[px * SAMPLES..(px + 1) * SAMPLES].fill(NONE);
                }
            }
            for &t in &bins[b] {
                band.rasterise(&tris[t as usize], t, s_depth, s_tri);
            }
            band.shade(tris, mesh, &shade, s_depth, s_tri, color, depth, coverage);
        });
}

/// Transforms, clips, culls and bins every triangle into `scratch.tris` / `scratch.bins`.
fn set_up(view: &View, mesh: &Mesh, scratch: &mut MeshScratch) {
    let h = view.height as usize;
    let bands = h.div_ceil(BAND_ROWS);
    scratch.tris.clear();
    scratch.bins.resize_with(bands, Vec::new);
    scratch.bins.iter_mut().for_each(Vec::clear);
    let nv = mesh.positions.len();
    if mesh.normals.len() != nv {
        return;
    }
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if tri.iter().any(|&i| i as usize >= nv) {
            continue;
        }
        let Some(&surface) = mesh.triangle_surface.get(t) else {
            continue;
        };
        let Some(surf) = mesh.surfaces.get(surface as usize) else {
            continue;
        };
        let world = tri.map(|i| mesh.positions[i as usize]);
        if world.iter().any(|p| !p.is_finite()) {
            continue;
        }
        let normal = tri.map(|i| mesh.normals[i as usize]);
        let uv = tri.map(|i| mesh.uv.get(i as usize).copied().unwrap_or(Vec2::ZERO));
        let v = world.map(|p| view.to_view(p));
        // Clip against the near plane in view space: a polygon of up to 4 corners, each a
        // blend of the triangle's corners (weights over the 3 originals).
        let mut poly: [(Vec3, [f32; 3]); 4] = [(Vec3::ZERO, [0.0; 3]); 4];
        let mut count = 0;
        for i in 0..3 {
            let j = (i + 1) % 3;
            let (a, b) = (v[i], v[j]);
            let a_in = a.z >= view.near_m;
            let b_in = b.z >= view.near_m;
            if a_in {
                let mut wts = [0.0; 3];
                wts[i] = 1.0;
                poly[count] = (a, wts);
                count += 1;
            }
            if a_in != b_in {
                let s = (view.near_m - a.z) / (b.z - a.z);
                let mut wts = [0.0; 3];
                wts[i] = 1.0 - s;
                wts[j] = s;
                poly[count] = (a.lerp(b, s), wts);
                count += 1;
            }
        }
        for k in 1..count.saturating_sub(1) {
            let corners = [poly[0], poly[k], poly[k + 1]];
            let mut st = ScreenTri {
                p: [Vec2::ZERO; 3],
                inv_z: [0.0; 3],
                world: [Vec3::ZERO; 3],
                normal: [Vec3::ZERO; 3],
                uv: [Vec2::ZERO; 3],
                surface,
                front: true,
                area2: 0.0,
            };
            for (c, (pv, wts)) in corners.iter().enumerate() {
                let (x, y) = view.view_to_pixel(*pv);
                st.p[c] = Vec2::new(x, y);
                st.inv_z[c] = 1.0 / pv.z;
                st.world[c] = world[0] * wts[0] + world[1] * wts[1] + world[2] * wts[2];
                st.normal[c] = normal[0] * wts[0] + normal[1] * wts[1] + normal[2] * wts[2];
                st.uv[c] = uv[0] * wts[0] + uv[1] * wts[1] + uv[2] * wts[2];
            }
            let [p0, p1, p2] = st.p;
            st.area2 = (p1 - p0).perp_dot(p2 - p0);
            // Screen y grows down, so a counter-clockwise (front) face has a negative area.
            st.front = st.area2 < 0.0;
            if !(st.area2.abs() > 1e-12)
                || !st.area2.is_finite()
                || (!st.front && !surf.double_sided)
            {
                continue;
            }
            let (lo, hi) = screen_box(&st);
            if !(hi.x >= 0.0 && lo.x <= view.width as f32 && hi.y >= 0.0 && lo.y <= h as f32) {
                continue;
            }
            let y0 = lo.y.max(0.0) as usize;
            let y1 = (hi.y.min(h as f32 - 1.0).max(0.0) as usize).min(h - 1);
            let index = scratch.tris.len() as u32;
            scratch.tris.push(st);
            for b in y0 / BAND_ROWS..=y1 / BAND_ROWS {
                scratch.bins[b].push(index);
            }
        }
    }
}

/// One band of rows of the image.
struct Band {
    y0: usize,
    rows: usize,
    w: usize,
    /// The columns `span.0 .. span.1` that its triangles can touch.
    span: (usize, usize),
}

/// A triangle's screen box: its corners' minimum and maximum.
#[inline]
fn screen_box(t: &ScreenTri) -> (Vec2, Vec2) {
    (
        t.p[0].min(t.p[1]).min(t.p[2]),
        t.p[0].max(t.p[1]).max(t.p[2]),
    )
}

/// Screen-space edge functions of a triangle at `q`: e[i] is twice the signed area of the
/// sub-triangle opposite corner i, so e / area2 are the screen barycentrics.
#[inline]
fn edges(t: &ScreenTri, q: Vec2) -> [f32; 3] {
    let [p0, p1, p2] = t.p;
    [
        (p1 - q).perp_dot(p2 - q),
        (p2 - q).perp_dot(p0 - q),
        (p0 - q).perp_dot(p1 - q),
    ]
}

/// The columns of pixel row `y` (within `x0..x1`) whose samples the triangle with corners
/// `p` (as (y, x)) can cover: the pixels meeting its span over the row's strip
/// (`crate::tri_span::span`); the whole `x0..x1` when it cannot narrow.
fn row_columns(p: [Vec2; 3], narrow: bool, y: usize, (x0, x1): (usize, usize)) -> (usize, usize) {
    if !narrow {
        return (x0, x1);
    }
    let Some((lo, hi)) = tri_span::span(p, (y as f32, y as f32 + 1.0)) else {
        return (x0, x0);
    };
    let xa = (lo.floor().max(x0 as f32) as usize).max(x0);
    let xb = ((hi.floor() + 1.0).max(0.0) as usize).min(x1);
    (xa, xb.max(xa))
}

impl Band {
    /// The columns `x0 .. x1` whose samples a triangle with screen box `(lo, hi)` can cover.
    #[inline]
    fn columns(&self, (lo, hi): (Vec2, Vec2)) -> (usize, usize) {
        let x0 = lo.x.max(0.0).floor() as usize;
        let x1 = (hi.x.min(self.w as f32).max(0.0).ceil() as usize).min(self.w);
        (x0, x1)
    }

    /// Keeps, per sample of the band, the nearest triangle.
    ///
    /// Each row visits only the columns its strip of the triangle can reach
    /// ([`row_columns`]), and a pixel's four samples are tested side by side, each lane with
    /// the operations of [`edges`] in the same order, so a sample's verdict and depth are the
    /// bits the one-sample-at-a-time loop gave.
    fn rasterise(&self, t: &ScreenTri, index: u32, s_depth: &mut [f32], s_tri: &mut [u32]) {
        let (lo, hi) = screen_box(t);
        let (x0, x1) = self.columns((lo, hi));
        let r0 = (lo.y.max(self.y0 as f32).floor() as usize).max(self.y0);
        let r1 = (hi.y.min((self.y0 + self.rows) as f32).ceil() as usize).min(self.y0 + self.rows);
        let inv_area = 1.0 / t.area2;
        let [p0, p1, p2] = t.p;
        let p_yx = t.p.map(|q| Vec2::new(q.y, q.x));
        let narrow = tri_span::narrowable(p_yx);
        let (ox, oy) = (
            Vec4::from(SAMPLE_OFFSETS.map(|o| o.0)),
            Vec4::from(SAMPLE_OFFSETS.map(|o| o.1)),
        );
        for y in r0..r1 {
            let row = (y - self.y0) * self.w;
            let (xa, xb) = row_columns(p_yx, narrow, y, (x0, x1));
            let qy = Vec4::splat(y as f32) + oy;
            // (pᵢ − q).y for the three corners, shared by the row.
            let dy = [
                Vec4::splat(p0.y) - qy,
                Vec4::splat(p1.y) - qy,
                Vec4::splat(p2.y) - qy,
            ];
            for x in xa..xb {
                let qx = Vec4::splat(x as f32) + ox;
                let dx = [
                    Vec4::splat(p0.x) - qx,
                    Vec4::splat(p1.x) - qx,
                    Vec4::splat(p2.x) - qx,
                ];
                // `edges` lane-wise: (pa − q).perp_dot(pb − q) = dxa·dyb − dya·dxb.
                let e0 = dx[1] * dy[2] - dy[1] * dx[2];
                let e1 = dx[2] * dy[0] - dy[2] * dx[0];
                let e2 = dx[0] * dy[1] - dy[0] * dx[1];
                let (l0, l1, l2) = (e0 * inv_area, e1 * inv_area, e2 * inv_area);
                let inside = l0.cmpge(Vec4::ZERO) & l1.cmpge(Vec4::ZERO) & l2.cmpge(Vec4::ZERO);
                if !inside.any() {
                    continue;
                }
                let inv_z = l0 * t.inv_z[0] + l1 * t.inv_z[1] + l2 * t.inv_z[2];
                let mask = inside.bitmask();
                let inv_z = inv_z.to_array();
                let k0 = (row + x) * SAMPLES;
                for (s, &iz) in inv_z.iter().enumerate() {
                    let k = k0 + s;
                    // Nearer: 1/z larger. `inv_z·depth > 1` also holds for an infinite depth.
                    if mask & (1 << s) != 0 && iz > 0.0 && iz * s_depth[k] > 1.0 {
                        s_depth[k] = 1.0 / iz;
                        s_tri[k] = index;
                    }
                }
            }
        }
    }

    /// Shades every pixel the mesh covers, once, and composites it.
    #[allow(clippy::too_many_arguments)]
    fn shade(
        &self,
        tris: &[ScreenTri],
        mesh: &Mesh,
        shade: &(impl Fn(Vec3, Vec3, Vec3) -> Vec3 + Sync),
        s_depth: &[f32],
        s_tri: &[u32],
        color: &mut [Vec3],
        depth: &mut [f32],
        coverage: &mut [f32],
    ) {
        let (x_lo, x_hi) = self.span;
        for px in (0..self.rows).flat_map(|row| row * self.w + x_lo..row * self.w + x_hi) {
            let samples = &s_tri[px * SAMPLES..(px + 1) * SAMPLES];
            let covered = samples.iter().filter(|&&t| t != NONE).count();
            let Some(first) = samples.iter().position(|&t| t != NONE) else {
                continue;
            };
            let t = &tris[samples[first] as usize];
            let (x, y) = (px % self.w, self.y0 + px / self.w);
            let (ox, oy) = SAMPLE_OFFSETS[first];
            let e = edges(t, Vec2::new(x as f32 + ox, y as f32 + oy));
            // Perspective-correct barycentrics: screen weights divided by depth.
            let wts = [e[0] * t.inv_z[0], e[1] * t.inv_z[1], e[2] * t.inv_z[2]];
            let sum = wts[0] + wts[1] + wts[2];
            if !(sum.abs() > 0.0) || !sum.is_finite() {
                continue;
            }
            let l = wts.map(|v| v / sum);
            let p = t.world[0] * l[0] + t.world[1] * l[1] + t.world[2] * l[2];
            let mut n = (t.normal[0] * l[0] + t.normal[1] * l[1] + t.normal[2] * l[2])
                .normalize_or(Vec3::Y);
            let surf = &mesh.surfaces[t.surface as usize];
            if !t.front {
                n = -n;
            }
            let albedo = match surf.texture.and_then(|i| mesh.textures.get(i as usize)) {
                Some(tex) => {
                    surf.albedo * tex.sample(t.uv[0] * l[0] + t.uv[1] * l[1] + t.uv[2] * l[2])
                }
                None => surf.albedo,
            };
            let c = shade(p, n, albedo);
            let c = if c.is_finite() { c } else { Vec3::ZERO };
            let a = covered as f32 / SAMPLES as f32;
            color[px] += (c - color[px]) * a;
            coverage[px] += (1.0 - coverage[px]) * a;
            if 2 * covered >= SAMPLES {
                depth[px] = s_depth[px * SAMPLES + first];
            }
        }
    }
}

#[cfg(test)]
mod tests;
