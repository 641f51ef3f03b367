//! Opaque solids: an ellipsoid (the head, body spheres) ray cast per pixel.
//!
//! What: [`draw_ellipsoid`] shades every pixel whose ray hits the ellipsoid in front of what the
//! depth buffer already holds, writes the hit's view depth, and anti-aliases the silhouette.
//!
//! How: the ellipsoid is the image of the unit sphere under an affine map `M`. Each pixel's
//! ray `eye + t·d` (with `d` scaled so `t` is the view depth) is mapped by `M⁻¹` into
//! unit-sphere space, where the hit is the smaller root of `a t² + 2 b t + c = 0`. The
//! discriminant `disc = b² − a c` is a quadratic function of the pixel position and is zero on
//! the silhouette, so `disc / |∇disc|` is (to first order) the signed distance in pixels from
//! the pixel centre to the silhouette; coverage is `clamp(0.5 + distance, 0, 1)`, the exact
//! box-filter coverage of a straight edge crossing the pixel along an axis. Pixels just outside
//! shade the ray's closest point to the surface (`t = −b/a`). Depth is written only where the
//! pixel centre is inside the silhouette; colour is blended by coverage, and the coverage
//! channel composites it with "over".
//!
//! Only the ellipsoid's screen bounding box is visited. The box is exact: the silhouette is the
//! conic whose dual is `C* = K (A Aᵀ − t tᵀ) Kᵀ` (A, t: the unit-sphere-to-view map, K: the
//! intrinsics), and its vertical/horizontal tangent lines come from a quadratic each. The
//! rejected alternative, projecting the 8 corners of the ellipsoid's bounding box, visits about
//! 2.9× the disc area for a sphere 3 radii away (corner boxes grow with perspective), against
//! 1.27× for the exact box. When the ellipsoid crosses the near plane the conic is not an
//! ellipse and the whole screen is visited; when the eye is inside the ellipsoid nothing is
//! drawn (there is no front surface to see).
//!
//! Rows are shaded in parallel; each pixel depends only on its own inputs, so the output is
//! identical for any thread count.

use glam::{Affine3A, DMat3, DVec3, Mat3, Vec3};
use rayon::prelude::*;

use crate::raster::camera::{Camera, View};
use crate::raster::framebuffer::Framebuffer;

/// Pixels of margin around the exact bounding box (anti-aliased edge plus float error).
const BOX_MARGIN_PX: f64 = 2.0;

/// Draws the ellipsoid `unit_sphere_to_world(unit sphere)` as an opaque solid.
///
/// `shade(world_position, unit_world_normal)` gives the linear RGB colour of a surface point;
/// it is called once per covered pixel, from several threads. Colour and depth are written
/// where the surface is nearer than the depth already stored; the silhouette is anti-aliased.
/// A singular or non-finite transform, an eye inside the ellipsoid, an empty or inconsistent
/// framebuffer draw nothing. As for lines, the framebuffer's size overrides the camera's.
pub fn draw_ellipsoid(
    fb: &mut Framebuffer,
    cam: &Camera,
    unit_sphere_to_world: Affine3A,
    shade: impl Fn(Vec3, Vec3) -> Vec3 + Sync,
) {
    let (w, h) = (fb.width as usize, fb.height as usize);
    if w == 0 || h == 0 || !fb.is_consistent() {
        return;
    }
    let Some(view) = cam.view_for(fb.width, fb.height) else {
        return;
    };
    let m = unit_sphere_to_world;
    let lin = Mat3::from(m.matrix3);
    let det = lin.determinant();
    if !(det.abs() > 1e-30) || !det.is_finite() || !m.translation.is_finite() {
        return;
    }
    let Some(setup) = RaySetup::new(&view, m) else {
        return;
    };
    if setup.c <= 0.0 {
        return; // eye inside (or on) the ellipsoid
    }
    let (x0, x1, y0, y1) = screen_box(&view, m).unwrap_or((0, w, 0, h));
    if x0 >= x1 || y0 >= y1 {
        return;
    }
    let rows = y0 * w..y1 * w;
    fb.color[rows.clone()]
        .par_chunks_mut(w)
        .zip(fb.depth[rows.clone()].par_chunks_mut(w))
        .zip(fb.coverage[rows].par_chunks_mut(w))
        .enumerate()
        .for_each(|(r, ((color_row, depth_row), coverage_row))| {
            let y = (y0 + r) as f32 + 0.5;
            for x in x0..x1 {
                let xf = x as f32 + 0.5;
                let Some(hit) = setup.hit(&view, xf, y) else {
                    continue;
                };
                if !(hit.t < depth_row[x]) {
                    continue;
                }
                let c = shade(hit.position, hit.normal);
                let dst = &mut color_row[x];
                // Weighted, not `dst + (c − dst)·coverage`, which loses `c` to rounding
                // against a far brighter background (the mesh's shading says more).
                *dst = *dst * (1.0 - hit.coverage) + c * hit.coverage;
                let a = &mut coverage_row[x];
                *a += (1.0 - *a) * hit.coverage;
                if hit.centre_inside {
                    depth_row[x] = hit.t;
                }
            }
        });
}

/// Per-frame constants of the ray-ellipsoid intersection, in unit-sphere space.
struct RaySetup {
    /// Eye in unit-sphere space.
    o: Vec3,
    /// Unit-sphere-space ray direction at pixel (x, y) is `d0 + dx·x + dy·y`.
    d0: Vec3,
    dx: Vec3,
    dy: Vec3,
    /// `|o|² − 1` (> 0 when the eye is outside).
    c: f32,
    /// `o·dx`, `o·dy`: derivatives of `b = o·d` per pixel.
    o_dx: f32,
    o_dy: f32,
    /// Transpose of the inverse linear part: unit-sphere normal -> world normal direction.
    normal_map: Mat3,
}

struct Hit {
    t: f32,
    position: Vec3,
    normal: Vec3,
    coverage: f32,
    centre_inside: bool,
}

impl RaySetup {
    fn new(view: &View, m: Affine3A) -> Option<RaySetup> {
        let inv = m.inverse();
        let l = Mat3::from(inv.matrix3);
        let o = inv.transform_point3(view.eye);
        let inv_f = 1.0 / view.focal_px;
        // World ray direction: forward + right·(x − cx)/f − up·(y − cy)/f.
        let d0w = view.forward - view.right * (view.cx * inv_f) + view.up * (view.cy * inv_f);
        let (dx, dy) = (l * (view.right * inv_f), l * (-view.up * inv_f));
        let s = RaySetup {
            o,
            d0: l * d0w,
            dx,
            dy,
            c: o.length_squared() - 1.0,
            o_dx: o.dot(dx),
            o_dy: o.dot(dy),
            normal_map: l.transpose(),
        };
        let finite = s.o.is_finite() && s.d0.is_finite() && s.dx.is_finite() && s.dy.is_finite();
        finite.then_some(s)
    }

    /// Intersection (or near miss within half a pixel) of the ray through `(x, y)`.
    #[inline]
    fn hit(&self, view: &View, x: f32, y: f32) -> Option<Hit> {
        let d = self.d0 + self.dx * x + self.dy * y;
        let a = d.length_squared();
        let b = self.o.dot(d);
        let disc = b * b - a * self.c;
        // ∂disc/∂x = 2 b (o·dx) − 2 c (d·dx), likewise for y.
        let gx = 2.0 * (b * self.o_dx - self.c * d.dot(self.dx));
        let gy = 2.0 * (b * self.o_dy - self.c * d.dot(self.dy));
        let grad = (gx * gx + gy * gy).sqrt();
        let coverage = if disc >= 0.0 && !(grad > 0.0) {
            1.0
        } else {
            (0.5 + disc / grad).min(1.0)
        };
        // `!(x > 0)` also rejects NaN.
        if !(coverage > 0.0) || !(a > 0.0) {
            return None;
        }
        let centre_inside = disc >= 0.0;
        let t = (-b - disc.max(0.0).sqrt()) / a;
        if !(t >= view.near_m) || !t.is_finite() {
            return None;
        }
        let q = self.o + d * t;
        let normal = (self.normal_map * q).normalize_or_zero();
        let position = view.eye + view.ray_dir(x, y) * t;
        Some(Hit {
            t,
            position,
            normal,
            coverage,
            centre_inside,
        })
    }
}

/// Exact pixel bounding box `(x0, x1, y0, y1)` (half-open, clamped to the image) of the
/// ellipsoid's silhouette, from its dual conic; `None` when the ellipsoid reaches the near
/// plane (the silhouette is then not a bounded ellipse) or the numbers are not finite.
fn screen_box(view: &View, m: Affine3A) -> Option<(usize, usize, usize, usize)> {
    // Unit sphere -> view space: p_v = A q + t, in f64 (the conic terms cancel heavily).
    let basis = DMat3::from_cols(
        view.right.as_dvec3(),
        view.up.as_dvec3(),
        view.forward.as_dvec3(),
    )
    .transpose();
    let a = basis * Mat3::from(m.matrix3).as_dmat3();
    let t = basis * (DVec3::from(m.translation.to_array().map(f64::from)) - view.eye.as_dvec3());
    // Nearest depth of the ellipsoid: t.z − |row 2 of A|.
    let z_min = t.z - a.row(2).length();
    if !(z_min > f64::from(view.near_m)) {
        return None;
    }
    let s = a * a.transpose() - outer(t, t);
    let f = f64::from(view.focal_px);
    let k = DMat3::from_cols(
        DVec3::new(f, 0.0, 0.0),
        DVec3::new(0.0, -f, 0.0),
        DVec3::new(f64::from(view.cx), f64::from(view.cy), 1.0),
    );
    let c = k * s * k.transpose();
    // Tangent line x = u: C00 − 2u C02 + u² C22 = 0 (C* is symmetric; col(j)[i] = C_ij).
    let roots = |cii: f64, ci2: f64, c22: f64| -> Option<(f64, f64)> {
        let disc = ci2 * ci2 - cii * c22;
        if !(disc >= 0.0) || c22 == 0.0 {
            return None;
        }
        let r = disc.sqrt();
        let (u0, u1) = ((ci2 - r) / c22, (ci2 + r) / c22);
        Some((u0.min(u1), u0.max(u1)))
    };
    let (xa, xb) = roots(c.col(0)[0], c.col(2)[0], c.col(2)[2])?;
    let (ya, yb) = roots(c.col(1)[1], c.col(2)[1], c.col(2)[2])?;
    // Clamp in float before converting: a huge ellipsoid gives values beyond usize.
    let clamp = |v: f64, n: u32| v.clamp(0.0, f64::from(n));
    let x0 = clamp((xa - BOX_MARGIN_PX).floor(), view.width) as usize;
    let x1 = clamp((xb + BOX_MARGIN_PX).ceil(), view.width) as usize;
    let y0 = clamp((ya - BOX_MARGIN_PX).floor(), view.height) as usize;
    let y1 = clamp((yb + BOX_MARGIN_PX).ceil(), view.height) as usize;
    Some((x0, x1, y0, y1))
}

fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

#[cfg(test)]
mod tests;
