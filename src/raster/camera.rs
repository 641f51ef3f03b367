//! A pinhole camera: world points to pixel coordinates and view depth.
//!
//! What: `Camera` holds the user-facing description (eye, target, up, vertical field of view,
//! image size, near plane); [`Camera::view`] turns it once per frame into a [`View`], an
//! orthonormal basis plus the focal length in pixels, which is what the hot loops use.
//!
//! How: view space has `right`, `up` and `forward` axes; a point's depth is its distance along
//! `forward` in metres (not the distance to the eye, and not a non-linear z-buffer value), so
//! the depth stored in the framebuffer, the ray parameter of the head's ray caster and the
//! hair's interpolated depth are one and the same quantity. Pixel `(i, j)` covers
//! `[i, i+1) x [j, j+1)`, its centre is `(i + 0.5, j + 0.5)`, x grows right and y grows down;
//! the optical axis meets the image at `(width / 2, height / 2)`.
//!
//! Why a separate `View`: the public fields stay plain data (others build cameras with struct
//! literals), while normalising and crossing the basis vectors once per frame instead of once
//! per point keeps projection at 9 multiply-adds and one division per point.
//!
//! Degenerate cameras (eye == target, `up` parallel to the view direction, non-finite fields)
//! never panic: the basis falls back to a fixed frame and a non-finite focal length makes
//! [`View::project`] return `None`.

use glam::Vec3;

/// Default near-plane distance of [`Camera::look_at`], in metres (1 cm).
pub const DEFAULT_NEAR_M: f32 = 0.01;

/// A pinhole camera. All lengths in metres, angles in radians.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Position of the eye (centre of projection), world metres.
    pub eye: Vec3,
    /// A point the camera looks at (on the optical axis), world metres.
    pub target: Vec3,
    /// Approximate world "up"; the image's up is its component orthogonal to the view direction.
    pub up: Vec3,
    /// Vertical field of view in radians, in (0, π).
    pub fov_y_rad: f32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Near-plane distance along the view direction in metres; geometry nearer than this is
    /// clipped (default [`DEFAULT_NEAR_M`]).
    pub near_m: f32,
}

impl Camera {
    /// A camera at `eye` looking at `target`, with the default near plane.
    pub fn look_at(
        eye: Vec3,
        target: Vec3,
        up: Vec3,
        fov_y_rad: f32,
        width: u32,
        height: u32,
    ) -> Camera {
        Camera {
            eye,
            target,
            up,
            fov_y_rad,
            width,
            height,
            near_m: DEFAULT_NEAR_M,
        }
    }

    /// Frames a bounding sphere (`center`, `radius_m` in metres) seen from direction `view_dir`
    /// (from the target toward the eye), so that the sphere fills about 80% of the smaller of
    /// the two fields of view. World +Y is up unless `view_dir` is (nearly) vertical, then +Z.
    /// A zero or non-finite `view_dir` is replaced by +Z.
    pub fn framing(
        center: Vec3,
        radius_m: f32,
        view_dir: Vec3,
        fov_y_rad: f32,
        width: u32,
        height: u32,
    ) -> Camera {
        /// Fraction of the half field of view the sphere's silhouette fills.
        const FILL: f32 = 0.8;
        let dir = view_dir.try_normalize().unwrap_or(Vec3::Z);
        let aspect = if height > 0 {
            width as f32 / height as f32
        } else {
            1.0
        };
        let half_y = 0.5 * fov_y_rad;
        let half_x = (half_y.tan() * aspect).atan();
        let half = half_y.min(half_x) * FILL;
        // The silhouette cone of a sphere at distance d has half-angle asin(r / d).
        let radius = radius_m.abs();
        let dist = if half > 0.0 && half.is_finite() {
            radius / half.sin()
        } else {
            radius * 3.0
        };
        let dist = if dist.is_finite() && dist > 0.0 {
            dist
        } else {
            1.0
        };
        let up = if dir.y.abs() > 0.99 { Vec3::Z } else { Vec3::Y };
        let mut cam = Camera::look_at(center + dir * dist, center, up, fov_y_rad, width, height);
        // Keep the near plane in front of the sphere but small against it.
        cam.near_m = (0.01 * dist).clamp(1e-4, DEFAULT_NEAR_M);
        cam
    }

    /// Eye position, world metres.
    pub fn eye(&self) -> Vec3 {
        self.eye
    }

    /// Unit view direction (from the eye toward the target).
    pub fn forward(&self) -> Vec3 {
        self.view().forward
    }

    /// Focal length in pixels: `(height / 2) / tan(fov_y / 2)`.
    pub fn focal_px(&self) -> f32 {
        self.view().focal_px
    }

    /// The per-frame projection data.
    pub fn view(&self) -> View {
        View::new(self)
    }

    /// The view onto an image of `width` × `height` pixels, whatever size the camera says
    /// (the rasters draw at their framebuffer's size), or `None` when it cannot project
    /// anything: a focal length that is not positive and finite, or an eye not finite.
    pub fn view_for(&self, width: u32, height: u32) -> Option<View> {
        let view = Camera {
            width,
            height,
            ..*self
        }
        .view();
        (view.focal_px > 0.0 && view.focal_px.is_finite() && view.eye.is_finite()).then_some(view)
    }

    /// World point -> `(x_px, y_px, depth_m)`, x right, y down, pixel centres at +0.5, depth
    /// along the view direction in metres. `None` when the point is nearer than the near plane
    /// (or behind the eye) or the result is not finite.
    pub fn project(&self, p: Vec3) -> Option<Vec3> {
        self.view().project(p)
    }
}

/// Per-frame projection data derived from a [`Camera`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    pub eye: Vec3,
    /// Unit image-right axis in world space.
    pub right: Vec3,
    /// Unit image-up axis in world space (image y grows the other way).
    pub up: Vec3,
    /// Unit view direction in world space.
    pub forward: Vec3,
    /// Focal length in pixels.
    pub focal_px: f32,
    /// Principal point (where the optical axis meets the image), pixels.
    pub cx: f32,
    pub cy: f32,
    /// Near-plane depth in metres (at least a tiny positive value, so 1/depth is finite).
    pub near_m: f32,
    pub width: u32,
    pub height: u32,
}

impl View {
    fn new(cam: &Camera) -> View {
        let forward = (cam.target - cam.eye)
            .try_normalize()
            .unwrap_or(Vec3::NEG_Z);
        let right = forward
            .cross(cam.up)
            .try_normalize()
            .or_else(|| forward.cross(Vec3::Y).try_normalize())
            .or_else(|| forward.cross(Vec3::X).try_normalize())
            .unwrap_or(Vec3::X);
        let up = right.cross(forward);
        let focal_px = 0.5 * cam.height as f32 / (0.5 * cam.fov_y_rad).tan();
        let near_m = if cam.near_m.is_finite() {
            cam.near_m.max(1e-6)
        } else {
            DEFAULT_NEAR_M
        };
        View {
            eye: cam.eye,
            right,
            up,
            forward,
            focal_px,
            cx: 0.5 * cam.width as f32,
            cy: 0.5 * cam.height as f32,
            near_m,
            width: cam.width,
            height: cam.height,
        }
    }

    /// World point -> view space `(right, up, depth)` in metres.
    #[inline]
    pub fn to_view(&self, p: Vec3) -> Vec3 {
        let d = p - self.eye;
        Vec3::new(d.dot(self.right), d.dot(self.up), d.dot(self.forward))
    }

    /// View-space point with depth > 0 -> `(x_px, y_px)`.
    #[inline]
    pub fn view_to_pixel(&self, v: Vec3) -> (f32, f32) {
        let s = self.focal_px / v.z;
        (self.cx + v.x * s, self.cy - v.y * s)
    }

    /// See [`Camera::project`].
    pub fn project(&self, p: Vec3) -> Option<Vec3> {
        let v = self.to_view(p);
        // `!(a >= b)` also rejects NaN.
        if !(v.z >= self.near_m) {
            return None;
        }
        let (x, y) = self.view_to_pixel(v);
        let r = Vec3::new(x, y, v.z);
        r.is_finite().then_some(r)
    }

    /// World direction of the ray through pixel position `(x_px, y_px)`, scaled so that its
    /// component along `forward` is 1: `eye + t * dir` has depth `t`.
    #[inline]
    pub fn ray_dir(&self, x_px: f32, y_px: f32) -> Vec3 {
        let inv_f = 1.0 / self.focal_px;
        self.forward + self.right * ((x_px - self.cx) * inv_f)
            - self.up * ((y_px - self.cy) * inv_f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam() -> Camera {
        // 90° vertical fov: focal length = height / 2.
        Camera::look_at(
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::ZERO,
            Vec3::Y,
            std::f32::consts::FRAC_PI_2,
            200,
            100,
        )
    }

    #[test]
    fn projects_known_points() {
        let c = cam();
        assert!((c.focal_px() - 50.0).abs() < 1e-4);
        // The target is on the optical axis, at the image centre, 2 m deep.
        let p = c.project(Vec3::ZERO).unwrap();
        assert!((p - Vec3::new(100.0, 50.0, 2.0)).length() < 1e-4, "{p}");
        // 0.5 m right and 0.25 m up at depth 1: x = 100 + 50 * 0.5, y = 50 - 50 * 0.25.
        let p = c.project(Vec3::new(0.5, 0.25, 1.0)).unwrap();
        assert!((p - Vec3::new(125.0, 37.5, 1.0)).length() < 1e-4, "{p}");
        // Depth is along the axis, not the Euclidean distance.
        let p = c.project(Vec3::new(2.0, 0.0, 0.0)).unwrap();
        assert!(
            (p.z - 2.0).abs() < 1e-5 && (p.x - 150.0).abs() < 1e-3,
            "{p}"
        );
    }

    #[test]
    fn rejects_points_behind_or_too_near() {
        let c = cam();
        assert!(c.project(Vec3::new(0.0, 0.0, 3.0)).is_none());
        assert!(
            c.project(Vec3::new(0.0, 0.0, 2.0 - 0.5 * DEFAULT_NEAR_M))
                .is_none()
        );
        assert!(c.project(Vec3::new(f32::NAN, 0.0, 0.0)).is_none());
        assert!(c.project(Vec3::new(f32::INFINITY, 0.0, 0.0)).is_none());
    }

    #[test]
    fn ray_dir_hits_the_projected_pixel() {
        let c = cam();
        let v = c.view();
        let p = Vec3::new(0.3, -0.2, -0.4);
        let q = c.project(p).unwrap();
        let hit = v.eye + v.ray_dir(q.x, q.y) * q.z;
        assert!((hit - p).length() < 1e-5, "{hit} vs {p}");
    }

    #[test]
    fn framing_keeps_sphere_inside() {
        let center = Vec3::new(0.1, 1.6, -0.2);
        let r = 0.15;
        let c = Camera::framing(center, r, Vec3::new(1.0, 0.2, 1.0), 0.7, 320, 180);
        let v = c.view();
        // Extreme points of the sphere in the image axes project inside the image.
        for d in [v.right, -v.right, v.up, -v.up] {
            let p = c.project(center + d * r).unwrap();
            assert!(p.x > 0.0 && p.x < 320.0 && p.y > 0.0 && p.y < 180.0, "{p}");
        }
        let p = c.project(center).unwrap();
        assert!((p.x - 160.0).abs() < 1e-3 && (p.y - 90.0).abs() < 1e-3);
        // Degenerate inputs still give a usable camera.
        let c = Camera::framing(center, r, Vec3::ZERO, 0.7, 0, 0);
        assert!(c.eye.is_finite());
        let c = Camera::framing(center, r, Vec3::Y, 0.7, 10, 10);
        assert!(c.project(center).is_some());
    }

    #[test]
    fn degenerate_camera_does_not_panic() {
        let c = Camera::look_at(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, 0.0, 0, 0);
        let _ = c.project(Vec3::ONE);
        let c = Camera::look_at(Vec3::ZERO, Vec3::Y, Vec3::Y, f32::NAN, 10, 10);
        let _ = c.project(Vec3::new(0.0, 5.0, 0.1));
    }
}
