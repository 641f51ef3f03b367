//! The fluence per unit flux of the forward-scattered light (Zinke 2008 Eq. 7's window,
//! "flux is not fluence" in the `dual` module doc): what the shader multiplies the forward
//! share T_f − direct by, w / sin w for a light in the fibre's normal plane and 1 along the
//! fibre, and its table over sin²θi ([`ScatteredGain`]).

/// The fluence the forward-scattered light brings per unit of the flux T_f that the map
/// carries along the shadow path, for light spread uniformly in azimuth over Eq. 7's window of
/// half-width `window_rad` about the light's direction (in the fibres' normal plane), for a
/// light in the fibre's normal plane: [`window_fluence_inclined`] at θi = 0.
///
/// A direction at azimuth ψ from the shadow path (and any inclination θ) carries flux L cos θ
/// cos ψ dω along the path and delivers L cos θ dω to a fibre's projected width, so over the
/// window fluence ÷ flux = ∫ dψ / ∫ cos ψ dψ = w / sin w: 1 for a beam (w → 0), π/2 for Zinke's
/// front half circle (w = 90°). Windows wider than 90° hold light travelling back along the
/// path, which a forward flux cannot carry; there the flux is counted both ways (|cos ψ|),
/// w / (2 − sin w), which is continuous at 90° and π/2 again for isotropic light (180°).
pub fn window_fluence(window_rad: f64) -> f64 {
    window_fluence_inclined(window_rad, 0.0)
}

/// [`window_fluence`] for a light at inclination θi to the fibre's normal plane
/// (`sin2_theta_i` = sin²θi), with Eq. 7's window where Zinke puts it: in the shading fibre's
/// own azimuth, about the light's, at the light's inclination.
///
/// The window's direction at azimuth ψ from the light's is (sin θi, cos θi cos ψ, cos θi sin ψ)
/// in the fibre's frame (axis first); its flux along the shadow path is L |sin²θi + cos²θi
/// cos ψ| and it delivers L cos θi to the fibre's projected width at every ψ, as the path's
/// own beam does. So fluence ÷ flux = 2w / ∫ |a + b cos ψ| dψ with a = sin²θi, b = cos²θi:
/// w / (a w + b sin w) while a + b cos w ≥ 0, and 2w / (2[a(2ψ0 − w) + b(2 sin ψ0 − sin w)])
/// past the zero ψ0 = acos(−a/b). It falls from w / sin w at θi = 0 to 1 at |θi| → 90°: a
/// fibre lying along the light sees a window in its azimuth as a narrow cone about the path,
/// nearly a beam. (Taken at θi = 0 for every fibre, curly hair's forward light read 1.14 side-
/// and 1.26 back-lit of a path tracer, against 1.06 and 1.15 with it; ACCURACY.md section 2.)
pub fn window_fluence_inclined(window_rad: f64, sin2_theta_i: f64) -> f64 {
    let w = window_rad.clamp(1e-6, std::f64::consts::PI);
    let a = sin2_theta_i.clamp(0.0, 1.0);
    let b = 1.0 - a;
    let integral = if a + b * w.cos() >= 0.0 {
        2.0 * (a * w + b * w.sin())
    } else {
        let psi0 = (-a / b).clamp(-1.0, 1.0).acos();
        2.0 * (a * (2.0 * psi0 - w) + b * (2.0 * psi0.sin() - w.sin()))
    };
    2.0 * w / integral
}

/// Nodes of [`ScatteredGain`]'s table, uniform in sin²θi over [0, 1].
const GAIN_NODES: usize = 65;

/// d_f times [`window_fluence_inclined`], tabulated once per fibre over sin²θi so the shader
/// pays a lerp per vertex. The function is smooth and convex in sin²θi (between 1 and π/2 for
/// Zinke's window): linear interpolation over 64 intervals is within 3e-5 of it (1e-3 for
/// windows wider than 90°; `the_gain_table_follows_the_closed_form`).
#[derive(Clone, Debug)]
pub struct ScatteredGain {
    table: [f32; GAIN_NODES],
}

impl ScatteredGain {
    pub fn new(d_f: f64, window_rad: f64) -> Self {
        let step = 1.0 / (GAIN_NODES - 1) as f64;
        Self {
            table: std::array::from_fn(|i| {
                (d_f * window_fluence_inclined(window_rad, i as f64 * step)) as f32
            }),
        }
    }

    /// The gain for a light at sin θi = `sin_theta_i` (finite; clamped to the table).
    #[inline]
    pub fn at(&self, sin_theta_i: f32) -> f32 {
        let x = (sin_theta_i * sin_theta_i).clamp(0.0, 1.0) * (GAIN_NODES - 1) as f32;
        let i = (x as usize).min(GAIN_NODES - 2);
        let t = x - i as f32;
        self.table[i] + t * (self.table[i + 1] - self.table[i])
    }
}
