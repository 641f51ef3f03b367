//! The light on a fibre the camera sees, and on a vertex of one-fibre-per-strand hair with its
//! contact shadows.
//!
//! With the light near the camera, the ray toward the light and the ray toward the eye pass
//! through the same fibres for a while: their tubes of width 2r overlap over
//!
//!   s_c = 2r / (sin g · |sin φ|),
//!
//! g the angle between them and φ the angle between their separation and the hair. Given that
//! the view ray is clear (the fibre is seen), the light ray is clear where they overlap, so
//! the light crosses only the fibres outside the shared part: P(lit | seen) = exp(−n̄), n̄ the
//! crossings in front of the point averaged over shifts s ∈ [0, s_c] toward the light (the
//! opposition effect, or "hot spot", of fibre media). The average is a two-point Gauss rule.
//! With contact shadows the fibres of a window in front of the vertex are taken exactly
//! (`contact`), and the map is read at the window's far end.

use super::occluders::NO_SOLIDS;
use super::{LightMap, OccluderGrid};
use crate::fiber::LightAtPoint;
use glam::Vec3;

/// T_f below which a point is dark enough that contact shadows are not computed.
const DARK: f32 = 1e-3;

/// Expected crossings (the map's) a contact window holds at most.
/// Measured on smooth × 12 strands of one fibre, 3000 vertices: T_f MAE 0.0066 at 16, 0.0067
/// at 8, 0.0070 at 4; shading smooth × 4 on 2 threads 6.9, 7.1 and 5.4 s.
const CONTACT_CROSSINGS: f32 = 4.0;

impl LightMap {
    /// The light reaching world point `p` *on a fibre the camera sees* from direction
    /// `to_eye` (from `p` toward the eye), for fibres of radius `fibre_radius_m`.
    ///
    /// When the light comes from near the camera, the ray toward the light and the ray toward
    /// the eye pass through the same fibres for a while: the two tubes of width 2r around them
    /// overlap over a length s_c = 2r / sin g (g: the angle between them), the overlap falling
    /// linearly from full at the point to none at s_c. Given that the view ray is clear (the
    /// fibre is seen), the light ray is clear where they overlap, so the light crosses only the
    /// fibres outside the shared part: P(lit | seen) = exp(−n̄) with n̄ the crossings in front
    /// of the point *averaged over shifts s ∈ [0, s_c] toward the light* (integrating the
    /// linear overlap by parts). This is the opposition effect ("hot spot") of fibre media:
    /// with the light exactly behind the camera every seen fibre is lit (g = 0: s_c = ∞), and it
    /// fades within a few degrees (r = 40 µm: s_c = 0.46 mm at 10°). The average is a
    /// two-point Gauss rule; beyond g where s_c is under a twentieth of a sub-slice, this is
    /// [`Self::light_at`] exactly (no extra lookups). `crossings_behind` is unconditional.
    pub fn light_at_seen(
        &self,
        p: Vec3,
        to_eye: Vec3,
        tangent: Vec3,
        fiber_radius_m: f32,
    ) -> LightAtPoint {
        self.light_at_seen_past(&NO_SOLIDS, p, to_eye, tangent, fiber_radius_m)
    }

    /// [`Self::light_at_seen`] past the opaque `solids` too.
    pub(crate) fn light_at_seen_past(
        &self,
        solids: &OccluderGrid,
        p: Vec3,
        to_eye: Vec3,
        tangent: Vec3,
        fiber_radius_m: f32,
    ) -> LightAtPoint {
        let s_c = self.shared_tube_m(p, to_eye, tangent, fiber_radius_m);
        let min_shift = 0.05 * self.geom.ds_m / crate::map::DEPTH_BINS as f32;
        if s_c <= min_shift {
            return self.light_past(solids, p);
        }
        // Gauss–Legendre nodes on [0, s_c]: s_c (1/2 ∓ 1/(2√3)), in cells.
        let h = 0.5 / 3f32.sqrt();
        let sc = s_c * self.inv_ds;
        self.light_with_taps(solids, p, &[(0.5, sc * (0.5 - h)), (0.5, sc * (0.5 + h))])
    }

    /// [`Self::light_at_seen`] for render-strand point `vertex` at `p`, with the fibres in the
    /// contact window in front of it taken exactly when the map has contact shadows
    /// ([`Self::build_contact`]; `super::contact`): the map is read at the window's far end
    /// (the light that reaches the window) and multiplied by what the real fibres inside the
    /// window let through. The opposition effect (the camera sees the point, and its view ray
    /// shares the light ray's fibres over a length s_c) applies on both sides: a fibre at a
    /// distance s in front counts with weight min(s, s_c)/s_c, inside the window as each real
    /// fibre's probability of being there (`ContactShadows::near_light`), beyond it as the far
    /// sums averaged with weight δ/s_c at the window's end and over shifts in [δ, s_c] (two
    /// Gauss nodes) with the rest. The exact fibres alone would not do it: the view ray crosses the
    /// same fibres near the point as the light ray, so with the light near the camera a seen
    /// point is lit more often than the exact light of an unseen one says (measured, with piece
    /// averages: dense blond, front light, single scattering 0.71 of the path tracer without
    /// this, 0.91 with the map alone).
    /// Points darker than 1e-3 on the map are not queried: they read [`Self::light_at_seen`].
    pub fn light_at_vertex_seen(
        &self,
        vertex: usize,
        p: Vec3,
        to_eye: Vec3,
        tangent: Vec3,
        fiber_radius_m: f32,
    ) -> LightAtPoint {
        self.light_at_vertex_seen_past(&NO_SOLIDS, vertex, p, to_eye, tangent, fiber_radius_m)
    }

    /// [`Self::light_at_vertex_seen`] past the opaque `solids` too.
    pub(crate) fn light_at_vertex_seen_past(
        &self,
        solids: &OccluderGrid,
        vertex: usize,
        p: Vec3,
        to_eye: Vec3,
        tangent: Vec3,
        fiber_radius_m: f32,
    ) -> LightAtPoint {
        let Some(contact) = &self.contact else {
            return self.light_at_seen_past(solids, p, to_eye, tangent, fiber_radius_m);
        };
        // Where the map says the point itself is dark, the exact window cannot make it
        // noticeably brighter (the map is calibrated there, ACCURACY.md §1): the map's value
        // stands, given the camera sees the point as everywhere else.
        let here = self.light_past(solids, p);
        if here.tf.max_element() <= DARK {
            return self.light_at_seen_past(solids, p, to_eye, tangent, fiber_radius_m);
        }
        // The window holds about CONTACT_CROSSINGS of the map's expected crossings in front of
        // the point (all of them up to the full window near the lit surface; a shorter window
        // deeper in, where hundreds of fibres would otherwise be taken one by one).
        let n_here = -here.direct_fraction.max(1e-30).ln();
        let delta = contact.window_m() * (CONTACT_CROSSINGS / n_here.max(CONTACT_CROSSINGS));
        let to_light = self.proj.toward_light(p);
        let far_p = p + to_light * delta;
        let s_c = self.shared_tube_m(p, to_eye, tangent, fiber_radius_m);
        let far = if s_c <= delta {
            self.light_past(solids, far_p)
        } else {
            let h = 0.5 / 3f32.sqrt();
            let rest = (s_c - delta) * self.inv_ds;
            let w = 0.5 * (s_c - delta) / s_c;
            self.light_with_taps(
                solids,
                far_p,
                &[
                    (delta / s_c, 0.0),
                    (w, rest * (0.5 - h)),
                    (w, rest * (0.5 + h)),
                ],
            )
        };
        if far.tf.max_element() <= DARK {
            return far;
        }
        let near = contact.near_light(vertex, delta, s_c);
        LightAtPoint {
            direct_fraction: (far.direct_fraction * near.direct_fraction).clamp(0.0, 1.0),
            tf: (far.tf * near.tf).clamp(Vec3::ZERO, Vec3::ONE),
            sigma_f2: far.sigma_f2 + near.sigma_f2,
            crossings_behind: (far.crossings_behind - near.crossings).max(0.0),
        }
    }

    /// The length s_c over which the ray toward the light and the ray toward the eye share
    /// the fibres they pass (module doc of [`Self::light_at_seen`]), metres; 0 when they
    /// share none.
    fn shared_tube_m(&self, p: Vec3, to_eye: Vec3, tangent: Vec3, fiber_radius_m: f32) -> f32 {
        let to_light = self.proj.toward_light(p);
        let v = to_eye.normalize_or_zero();
        let cos_g = v.dot(to_light);
        // Across the light: the direction in which the view ray leaves the light ray, and the
        // direction of the hair (the vertex's own, as locally the hair runs together).
        let sep = (v - to_light * cos_g).normalize_or_zero();
        let along = (tangent - to_light * tangent.dot(to_light)).normalize_or_zero();
        // A long fibre blocks both rays while their separation across it is under 2r: the
        // separation grows as s·sin g, and only its part across the fibre counts (|sin φ|),
        // floored at 0.1 for the spread of directions around the vertex's own.
        let sin_g = (1.0 - cos_g * cos_g).max(0.0).sqrt();
        let across = sep.cross(along).length().max(0.1);
        let limit = 2.0 * self.geom.n as f32 * self.geom.ds_m;
        // Opposite half-spaces (g ≥ 90°): the rays share only the point itself.
        let s_c = if cos_g > 0.0 {
            (2.0 * fiber_radius_m / (sin_g * across).max(1e-9)).min(limit)
        } else {
            0.0
        };
        if s_c.is_nan() { 0.0 } else { s_c }
    }
}
