//! The light a shaded point receives, as Figure 5 reads it from the map: the direct fraction,
//! the forward-scattered share max(T_f − direct, 0), and the longitudinal spread σ̄f² of the
//! forward-scattered light that *arrives* there ([`arriving_spread`]), sanitised so that any
//! input gives finite shading.

use super::super::LightAtPoint;
use super::{finite_or_zero, unit_or_zero};
use glam::Vec3;

/// The map's light, sanitised: direct fraction in [0, 1], T_f in [0, 1], the spread of the
/// light that arrives ([`arriving_spread`], ≥ 0), and the forward-scattered share
/// max(T_f − direct, 0).
pub(super) struct DualLight {
    pub(super) direct: f32,
    pub(super) sigma_f2: Vec3,
    pub(super) scattered: Vec3,
    pub(super) any_scattered: bool,
}

impl DualLight {
    #[inline]
    pub(super) fn new(light: &LightAtPoint) -> Self {
        let direct = unit_or_zero(light.direct_fraction);
        let tf = finite_or_zero(light.tf).clamp(Vec3::ZERO, Vec3::ONE);
        let scattered = (tf - Vec3::splat(direct)).max(Vec3::ZERO);
        Self {
            direct,
            sigma_f2: arriving_spread(finite_or_zero(light.sigma_f2), direct, tf),
            scattered,
            any_scattered: scattered.max_element() > 0.0,
        }
    }
}

/// Direct fraction below which the crossings in front are read as this many (f32's `exp`
/// underflows near 1e-38; what arrives there is below 1e-13 of the light).
const MIN_DIRECT: f32 = 1e-30;

/// The longitudinal spread σ̄f² (rad², RGB) of the forward-scattered light that *arrives* at a
/// point, from the map's path sum `path_var` = Σ n β_f² over the crossings in front (Zinke 2008
/// Eq. 8, averaged over rays), its direct fraction e^(−n̄) and its T_f = e^(−n̄(1 − ā_f)).
///
/// Zinke's sum is the spread of a ray that crosses every fibre in front, each scattering it
/// forward. With crossings counted as the map counts them (Poisson, mean n̄) a ray of N
/// crossings arrives with weight ā_f^N, so the light that arrives has crossed fewer fibres than
/// the average ray: among the forward-scattered light (N ≥ 1) the mean count is
/// E[N ā^N; N ≥ 1] / E[ā^N; N ≥ 1] = λ / (1 − e^(−λ)), λ = n̄ā_f = n̄ + ln T_f, per channel (1 for
/// a single crossing, n̄ā_f deep in the hair). The spread is that count times the mean β_f² per
/// crossing, Σ n β_f² / n̄. The path sum over-spread the arriving light by 1/ā_f deep in the
/// hair (1.6–2.6 × for blond), which flattened the forward lobe: back-lit dense hair showed
/// under half of the path tracer's multiply scattered light (ACCURACY.md §2).
///
/// A solid's shadow (`LightMap::light_at`) scales direct and T_f alike, which leaves λ exact
/// and n̄ read too high by −ln V; where direct underflows, n̄ reads −ln(1e-30), and the light
/// there is negligible.
#[inline]
pub(super) fn arriving_spread(path_var: Vec3, direct: f32, tf: Vec3) -> Vec3 {
    let path_var = path_var.max(Vec3::ZERO);
    let n_bar = -direct.max(MIN_DIRECT).ln();
    if n_bar <= 1e-6 {
        return path_var;
    }
    let order = |t: f32| {
        let lambda = (n_bar + t.max(MIN_DIRECT).ln()).max(0.0);
        if lambda < 1e-4 {
            1.0 + 0.5 * lambda
        } else {
            lambda / -(-lambda).exp_m1()
        }
    };
    path_var / n_bar * Vec3::new(order(tf.x), order(tf.y), order(tf.z))
}
