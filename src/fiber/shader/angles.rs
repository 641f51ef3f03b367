//! The hair frame of one (u, ωi, ωo) triple (Marschner 2003 §2.2): inclinations θ from the
//! fibre's normal plane, sin θ = ω·u, the relative azimuth φ = φo − φi in [−π, π] and
//! cos 2φh = cos(φi + φo), from world vectors, with one acos and two asin (no atan2: the
//! shader needs only |φ| and cos(φi + φo)).
//!
//! Azimuths are measured from the first vector of a branchless orthonormal basis built from u
//! alone (Duff et al. 2017), so the eccentric cross-section's orientation is a fixed,
//! deterministic function of the tangent. A direction along ±u has no azimuth (trap 9): it
//! takes the other direction's (φ = 0), which is finite and deterministic. Zero or non-finite
//! vectors give no angles.

use glam::Vec3;

/// Hair-frame angles of one (u, ωi, ωo) triple (Marschner 2003 §2.2), radians.
#[derive(Clone, Copy, Debug)]
pub struct HairAngles {
    pub theta_i: f32,
    pub theta_o: f32,
    /// Relative azimuth φ = φo − φi wrapped to [−π, π].
    pub phi: f32,
    /// cos 2φh = cos(φi + φo), with azimuths measured from a frame built from u alone.
    pub cos_2phi_h: f32,
}

impl HairAngles {
    pub fn theta_d(&self) -> f32 {
        0.5 * (self.theta_o - self.theta_i)
    }

    /// Angles from world vectors; None for zero or non-finite input. Uses one acos and two
    /// asin (no atan2): the shader needs only |φ| and cos(φi + φo).
    #[inline]
    pub fn from_vectors(u: Vec3, wi: Vec3, wo: Vec3) -> Option<Self> {
        Self::from_vectors_trig(u, wi, wo).map(|(a, _)| a)
    }

    /// [`Self::from_vectors`] with the sines of θi and θo it computes on the way (the shader
    /// needs them; recomputing them from the angles costs two `sin_cos`).
    #[inline]
    pub(crate) fn from_vectors_trig(u: Vec3, wi: Vec3, wo: Vec3) -> Option<(Self, [f32; 2])> {
        let u = unit(u)?;
        let wi = unit(wi)?;
        let wo = unit(wo)?;
        let sin_i = wi.dot(u).clamp(-1.0, 1.0);
        let sin_o = wo.dot(u).clamp(-1.0, 1.0);
        // Orthonormal basis around u (Duff et al. 2017, branchless).
        let sign = 1.0f32.copysign(u.z);
        let a = -1.0 / (sign + u.z);
        let b = u.x * u.y * a;
        let v = Vec3::new(1.0 + sign * u.x * u.x * a, sign * b, -sign * u.x);
        let w = Vec3::new(b, sign + u.y * u.y * a, -u.y);
        // Unit azimuth vectors (cos φ, sin φ) of the projections on the normal plane.
        let azimuth = |d: Vec3, s: f32| {
            let p = d - u * s;
            let (x, y) = (p.dot(v), p.dot(w));
            let l2 = x * x + y * y;
            (l2 > 1e-12).then(|| {
                let inv = 1.0 / l2.sqrt();
                (x * inv, y * inv)
            })
        };
        let (ai, ao) = match (azimuth(wi, sin_i), azimuth(wo, sin_o)) {
            (Some(i), Some(o)) => (i, o),
            (Some(i), None) => (i, i),
            (None, Some(o)) => (o, o),
            (None, None) => ((1.0, 0.0), (1.0, 0.0)),
        };
        let cos_phi = (ai.0 * ao.0 + ai.1 * ao.1).clamp(-1.0, 1.0);
        let sin_phi = ai.0 * ao.1 - ai.1 * ao.0;
        let phi = cos_phi.acos().copysign(sin_phi);
        Some((
            Self {
                theta_i: sin_i.asin(),
                theta_o: sin_o.asin(),
                phi,
                cos_2phi_h: ai.0 * ao.0 - ai.1 * ao.1,
            },
            [sin_i, sin_o],
        ))
    }
}

/// `v` normalised, or None when it is zero, tiny or not finite. Unit input (the documented
/// case) skips the square root.
#[inline]
fn unit(v: Vec3) -> Option<Vec3> {
    let l2 = v.length_squared();
    if (l2 - 1.0).abs() < 1e-6 {
        Some(v)
    } else if l2.is_finite() && l2 > 1e-30 {
        Some(v / l2.sqrt())
    } else {
        None
    }
}

/// sin and cos (≥ 0) of θi and θo, computed once per call.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Trig {
    pub(crate) si: f32,
    pub(crate) ci: f32,
    pub(crate) so: f32,
    pub(crate) co: f32,
}

impl Trig {
    /// From sin θi and sin θo.
    #[inline]
    pub(crate) fn from_sines([si, so]: [f32; 2]) -> Self {
        Self {
            si,
            ci: (1.0 - si * si).max(0.0).sqrt(),
            so,
            co: (1.0 - so * so).max(0.0).sqrt(),
        }
    }

    #[inline]
    pub(super) fn new(a: &HairAngles) -> Self {
        let (si, ci) = a.theta_i.sin_cos();
        let (so, co) = a.theta_o.sin_cos();
        Self {
            si,
            ci: ci.max(0.0),
            so,
            co: co.max(0.0),
        }
    }
}
