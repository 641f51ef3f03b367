//! Fibre scattering: the Marschner 2003 and Chiang 2016 fibre models and the Zinke 2008
//! dual-scattering quantities built from either.
//!
//! This module knows nothing of grids, strands or pixels. The rest of the engine uses only:
//! - [`FiberParams`] (serde, from hairstyle JSON; `validate`), whose `model` picks the model,
//! - [`Fiber::new`] (precomputes everything, tables included),
//! - [`Fiber::forward_scatter`] (per-crossing quantities for the map fill),
//! - [`Fiber::shade`] with a [`ShadingMode`] and a [`LightAtPoint`] from the map.
//!
//! Layout: `params` (JSON parameters, per-lobe constants), `fresnel` (Bravais indices,
//! generalised Fresnel), `marschner` (exact M, N, A, roots of Eq. 3, caustics), `chiang` (exact
//! d'Eon M, A_p, logistic N_p, far-field N̄), `tables` (tabulated Marschner N_p, lerp tables),
//! `chiang_tables` (tabulated N̄_p), `azimuthal` (integrals of N_p over φ in h-space, N^G),
//! `dual` (Zinke's ā_f, ā_b and their tables, for either model), `backscatter` (Ā_b, Δ̄_b, σ̄_b²
//! and their truncation by the local density), `longitudinal` (the shader's f32 lobes),
//! `model_shading` (the chosen model's interleaved tables), `shader` (Figure 5 and single
//! scattering), `kajiya_kay`, `chiang_sample` (sampling Chiang's model for light paths).
//!
//! Conventions: radians and SI inside; θ from the normal plane (sin θ = ω·u), ωi toward the
//! light, ωo toward the camera. Marschner's longitudinal Gaussians live in x = θi + θo (= 2θh)
//! and have unit area in θo ("m_normalization": "theta_o", trap 1); Chiang's d'Eon lobes have
//! unit area under cos θo dθo. σ̄_f², β̄_f² are variances of x.
//!
//! **Two models, one interface.** [`Fiber`] holds the chosen model's tables; `shade` matches on
//! the model once per call and runs the same Figure 5 composition on either (no dynamic
//! dispatch): Marschner reads N_p(|θd|, |φ|) and Gaussians over cos²θd, Chiang reads
//! N̄_p(|θo|, |φ|) and d'Eon lobes. The dual tables (ā_f, ā_b, β̄_f², ᾱ, Ā_b, Δ̄_b, σ̄_b², N^G) are
//! built from the chosen model by the same code (`dual::DualModel`), so the map and the shader
//! use them unchanged.
//!
//! The ten traps of DESIGN.md and where each is resolved (doc comment + pinning test):
//! 1. M normalisation (unit area in θo): `marschner::longitudinal_m`.
//! 2. Gaussians in radians; Eq. 17's mixed units (series, not the fit): `dual`.
//! 3. Eq. 16's sign (+, derived): `backscatter::delta_b`.
//! 4. Eq. 6's cosine (outgoing, the energy fraction): `dual`.
//! 5. Eq. 25 as a convolution over φ': `azimuthal::LobeSamples::n_g`.
//! 6. 1 − ā_f² guard: `backscatter::A_F_MAX`.
//! 7. Caustic ∞·0, merge, bracketed roots, reversed smoothstep: `marschner`.
//! 8. No path gives 0: `marschner::Azimuth::roots`.
//! 9. 1/cos²θd and θ = ±90°: `marschner::COS_THETA_D_MIN`, `shader::HairAngles`.
//! 10. η'' is not a refraction index: `fresnel`.

pub mod azimuthal;
pub mod backscatter;
pub mod chiang;
pub mod chiang_sample;
pub mod chiang_tables;
pub mod dual;
pub mod fresnel;
pub mod kajiya_kay;
pub mod longitudinal;
pub mod marschner;
mod model_shading;
mod params;
pub mod shader;
pub mod tables;

pub(crate) use model_shading::{ChiangShading, MarschnerShading, ModelShading};
pub use params::{
    ECCENTRICITY_MIN, FiberModel, FiberParams, Lobe, LobeConstants, roughness_for_std,
    std_for_roughness,
};
pub use shader::HairAngles;
use shader::Trig;
pub use tables::TableResolution;

use chiang::ChiangConstants;
use dual::DualTables;
use glam::Vec3;
use kajiya_kay::KajiyaKay;

/// Which fibre shader to use (for comparison and benchmarks).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ShadingMode {
    /// Zinke 2008 Figure 5: the fibre's BCSDF + global and local multiple scattering.
    #[default]
    DualScattering,
    /// Single scattering with hard shadows: S cos θi · direct_fraction, the light that reaches
    /// the point through no fibre at all (what a path tracer computes with one scattering
    /// event). Not S cos θi · T_f: T_f already holds forward-scattered light, so that would
    /// not be single scattering; `DualScattering` with d_b = 0 is its physical form.
    SingleScattering,
    /// Kajiya-Kay diffuse + specular scaled by transmittance (Bertails 2005 §3.3).
    KajiyaKay,
    /// The shadows alone, no fibre model: the share of the light that reaches the point
    /// through no fibre (`direct_fraction`), so a pixel shows the irradiance that arrives
    /// directly at the hair it sees. It is what single scattering multiplies its BCSDF by, and
    /// what `tools/reference/visibility.py` path-traces, so shadows can be checked apart from
    /// the fibre model (ACCURACY.md §2, "Where the side-lit deficit comes from").
    Visibility,
    /// Single scattering with hard shadows (as [`ShadingMode::SingleScattering`]) plus the
    /// multiply scattered light of paths traced through the hair volume (`crate::light_paths`,
    /// Moon, Walter & Marschner 2008's split): all orders without dual scattering's
    /// assumptions, at seconds per frame.
    Volume,
}

/// What the light-oriented map knows about the light reaching a point (all dimensionless).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightAtPoint {
    /// Fraction of rays reaching the point with no fibre crossing, in [0, 1].
    pub direct_fraction: f32,
    /// Forward-scattering transmittance T_f (Zinke 2008 Eq. 5 averaged over rays), RGB, in
    /// [0, 1]. Rays with no crossing count as 1, so T_f ≥ direct_fraction; the shader uses
    /// max(T_f − direct_fraction, 0) as the forward-scattered share (see `shader`).
    pub tf: Vec3,
    /// Accumulated forward-scattering variance σ̄f² in rad² (Zinke 2008 Eq. 8), RGB, >= 0.
    pub sigma_f2: Vec3,
    /// Local hair density behind the point: the expected number of fibre crossings a light ray
    /// still makes after the point, continuing along the light direction until it leaves the
    /// hair (dimensionless, >= 0). It truncates the local back-scattering Ā_b, which Zinke
    /// derives for infinitely many fibres behind the point (`backscatter::big_a_b_behind`): 0
    /// (an isolated fibre, or the far side of the hair) gives none, a few crossings give most of
    /// it (x^{D−1} weights decay fast), +∞ gives Zinke's full term. [`LightAtPoint::DENSE`]
    /// (= +∞, Zinke's assumption) where the map does not provide it.
    pub crossings_behind: f32,
}

impl LightAtPoint {
    /// `crossings_behind` of dense hair (Zinke's assumption): +∞.
    pub const DENSE: f32 = f32::INFINITY;

    /// Light that crossed no fibre at all, at a point in dense hair.
    pub const UNSHADOWED: Self = Self {
        direct_fraction: 1.0,
        tf: Vec3::ONE,
        sigma_f2: Vec3::ZERO,
        crossings_behind: Self::DENSE,
    };
}

/// Per-crossing forward-scattering quantities at one fibre inclination.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForwardScatter {
    /// Mean forward attenuation ā_f (Zinke 2008 Eq. 6), RGB, in [0, 1).
    pub a_f: Vec3,
    /// Mean forward variance β̄_f² in rad² (Zinke 2008 Table 1), RGB.
    pub beta_f2: Vec3,
}

/// A fibre with everything precomputed (tables of the dual-scattering quantities).
#[derive(Clone, Debug)]
pub struct Fiber {
    params: FiberParams,
    consts: LobeConstants,
    chiang: ChiangConstants,
    resolution: TableResolution,
    pub(crate) model: ModelShading,
    pub(crate) dual: DualTables,
    kk: KajiyaKay,
    /// d_f times the window's fluence per unit flux at the light's inclination
    /// ([`dual::window_fluence_inclined`]): what multiplies the forward-scattered share
    /// T_f − direct (Figure 5's d_f).
    pub(crate) scattered_gain: dual::ScatteredGain,
    pub(crate) d_b: f32,
}

impl Fiber {
    /// Precomputes the fibre's tables. `params` must have passed `validate` (out-of-range
    /// values are not checked again here; they give finite but meaningless tables).
    pub fn new(params: &FiberParams) -> Self {
        Self::with_resolution(params, &TableResolution::DEFAULT)
    }

    /// [`Fiber::new`] with explicit table sizes (for measuring table error).
    pub fn with_resolution(params: &FiberParams, resolution: &TableResolution) -> Self {
        let consts = LobeConstants::from_params(params);
        let chiang = ChiangConstants::from_params(params);
        let window = (params.forward_spread_deg as f64).to_radians();
        let (model, dual) = match params.model {
            FiberModel::Marschner => {
                let (m, dual) = MarschnerShading::build(&consts, resolution, window);
                (ModelShading::Marschner(m), dual)
            }
            FiberModel::Chiang => {
                let (c, dual) = ChiangShading::build(&chiang, resolution, window);
                (ModelShading::Chiang(c), dual)
            }
        };
        let kk = KajiyaKay::new(&consts, &dual);
        Self {
            params: params.clone(),
            scattered_gain: dual::ScatteredGain::new(params.d_f as f64, window),
            d_b: params.d_b,
            consts,
            chiang,
            resolution: *resolution,
            model,
            dual,
            kk,
        }
    }

    pub fn params(&self) -> &FiberParams {
        &self.params
    }

    /// The fibre's model.
    pub fn model(&self) -> FiberModel {
        self.params.model
    }

    /// Marschner's per-lobe constants in radians (also built for a Chiang fibre: the shared
    /// parameters β_R, α_R, η, σa in radians).
    pub fn lobe_constants(&self) -> &LobeConstants {
        &self.consts
    }

    /// Chiang's constants (also built for a Marschner fibre).
    pub fn chiang_constants(&self) -> &ChiangConstants {
        &self.chiang
    }

    pub fn resolution(&self) -> &TableResolution {
        &self.resolution
    }

    /// The renderer's tabulated Marschner N_p at |θd|, |φ| (radians) and cos 2φh, RGB, 1/rad;
    /// None for a Chiang fibre (see [`Fiber::n_bar_table`]).
    pub fn n_table(
        &self,
        lobe: Lobe,
        abs_theta_d: f32,
        abs_phi: f32,
        cos_2phi_h: f32,
    ) -> Option<Vec3> {
        match &self.model {
            ModelShading::Marschner(m) => {
                Some(m.n_tables.lookup(lobe, abs_theta_d, abs_phi, cos_2phi_h))
            }
            ModelShading::Chiang(_) => None,
        }
    }

    /// The renderer's tabulated Chiang N̄_p (p = 0..3, 3 the p ≥ 3 residual) at |θo|, |φ|
    /// (radians), RGB, 1/rad; None for a Marschner fibre.
    pub fn n_bar_table(&self, lobe: usize, abs_theta_o: f32, abs_phi: f32) -> Option<Vec3> {
        match &self.model {
            ModelShading::Chiang(c) if lobe < chiang::N_LOBES => {
                Some(c.tables.lookup(lobe, abs_theta_o, abs_phi))
            }
            _ => None,
        }
    }

    /// The dual-scattering tables (grid values and per-lobe shares).
    pub fn dual_tables(&self) -> &DualTables {
        &self.dual
    }

    /// Per-crossing forward scattering for light whose direction makes `sin_theta` (= ωi·u)
    /// with the fibre tangent: a table lerp (no allocation). ωi points toward the light, so for
    /// light travelling along L, `sin_theta = −L·u` (the tables are not even in θ: the cuticle
    /// tilt α makes root-ward and tip-ward light differ). Out-of-range or NaN input is clamped.
    #[inline]
    pub fn forward_scatter(&self, sin_theta: f32) -> ForwardScatter {
        let s = if sin_theta.is_nan() {
            0.0
        } else {
            sin_theta.clamp(-1.0, 1.0)
        };
        let (a_f, beta_f2) = self.dual.forward_at(s.asin());
        ForwardScatter { a_f, beta_f2 }
    }

    /// Outgoing radiance toward `wo` per unit irradiance arriving from `wi` (both unit, away
    /// from the fibre), for a fibre with unit tangent `u`, given what the map says of the light.
    /// Always finite; zero for degenerate vectors.
    #[inline]
    pub fn shade(
        &self,
        mode: ShadingMode,
        u: Vec3,
        wi: Vec3,
        wo: Vec3,
        light: &LightAtPoint,
    ) -> Vec3 {
        // The shadows alone need no angles (a degenerate tangent still has its shadow).
        let visibility = || Vec3::splat(shader::unit_or_zero(light.direct_fraction));
        if mode == ShadingMode::Visibility {
            return visibility();
        }
        let Some((a, sines)) = HairAngles::from_vectors_trig(u, wi, wo) else {
            return Vec3::ZERO;
        };
        let v = match mode {
            ShadingMode::DualScattering => self.shade_dual(&a, &Trig::from_sines(sines), light),
            ShadingMode::SingleScattering | ShadingMode::Volume => {
                self.shade_single(&a, &Trig::from_sines(sines), light)
            }
            ShadingMode::KajiyaKay => self.kk.shade(&a, light),
            ShadingMode::Visibility => visibility(),
        };
        if v.is_finite() { v } else { Vec3::ZERO }
    }
}
