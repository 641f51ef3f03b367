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
mod tests;
