//! Fibre scattering: Marschner 2003 BCSDF and Zinke 2008 dual-scattering quantities.
//!
//! This module knows nothing of grids, strands or pixels. The rest of the engine uses only:
//! - [`FiberParams`] (serde, from hairstyle JSON; `validate`),
//! - [`Fiber::new`] (precomputes everything, tables included),
//! - [`Fiber::forward_scatter`] (per-crossing quantities for the map fill),
//! - [`Fiber::shade`] with a [`ShadingMode`] and a [`LightAtPoint`] from the map.
//!
//! Layout: `params` (JSON parameters, per-lobe constants), `fresnel` (Bravais indices,
//! generalised Fresnel), `marschner` (exact M, N, A, roots of Eq. 3, caustics), `tables`
//! (tabulated N_p, lerp tables), `azimuthal` (integrals of N_p over φ in h-space, N^G),
//! `dual` (Zinke's ā_f, ā_b and their tables),
//! `backscatter` (Ā_b, Δ̄_b, σ̄_b² from them), `shader`
//! (Figure 5 and single scattering), `kajiya_kay`.
//!
//! Conventions: radians and SI inside; θ from the normal plane (sin θ = ω·u), ωi toward the
//! light, ωo toward the camera. Longitudinal Gaussians live in x = θi + θo (= 2θh) and have
//! unit area in θo ("m_normalization": "theta_o", trap 1); σ̄_f², β̄_f² are variances of x.
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
pub mod dual;
pub mod fresnel;
pub mod kajiya_kay;
pub mod marschner;
mod params;
pub mod shader;
pub mod tables;

pub use params::{ECCENTRICITY_MIN, FiberParams, Lobe, LobeConstants};
pub use shader::HairAngles;
pub use tables::TableResolution;

use dual::DualTables;
use glam::Vec3;
use kajiya_kay::KajiyaKay;
use tables::NTables;

/// Which fibre shader to use (for comparison and benchmarks).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ShadingMode {
    /// Zinke 2008 Figure 5: Marschner BCSDF + global and local multiple scattering.
    #[default]
    DualScattering,
    /// Marschner BCSDF attenuated by the map's forward transmittance only.
    SingleScattering,
    /// Kajiya-Kay diffuse + specular scaled by transmittance (Bertails 2005 §3.3).
    KajiyaKay,
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
}

impl LightAtPoint {
    /// Light that crossed no fibre at all.
    pub const UNSHADOWED: Self = Self {
        direct_fraction: 1.0,
        tf: Vec3::ONE,
        sigma_f2: Vec3::ZERO,
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
    resolution: TableResolution,
    pub(crate) n_tables: NTables,
    /// [N_R, N_TT, N^G_R, N^G_TT, N^G_TRT] interleaved on one grid (the shader's lookups).
    pub(crate) lobes: tables::Table2x<5>,
    pub(crate) dual: DualTables,
    kk: KajiyaKay,
    /// Lobe means 2α_p and variances (2β_p)² in x = θi + θo (radians, rad²).
    pub(crate) mean_x: [f32; 3],
    pub(crate) var_x: [f32; 3],
    /// 1/√(2π var_x) and −1/(2 var_x): the unbroadened lobes' Gaussian constants.
    pub(crate) m_norm: [f32; 3],
    pub(crate) m_exp: [f32; 3],
    pub(crate) d_f: f32,
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
        let n_tables = NTables::build(&consts, resolution);
        let dual = DualTables::build(&consts, resolution);
        let kk = KajiyaKay::new(&consts, &dual);
        let lobes = tables::Table2x::zip([
            &n_tables.r,
            &n_tables.tt,
            &dual.n_g[0],
            &dual.n_g[1],
            &dual.n_g[2],
        ]);
        let lobe = |f: &dyn Fn(Lobe) -> f64| Lobe::ALL.map(|l| f(l) as f32);
        Self {
            params: params.clone(),
            mean_x: lobe(&|l| consts.mean_x(l)),
            var_x: lobe(&|l| consts.std_x(l).powi(2)),
            m_norm: lobe(&|l| 1.0 / (2.0 * std::f64::consts::PI * consts.std_x(l).powi(2)).sqrt()),
            m_exp: lobe(&|l| -0.5 / consts.std_x(l).powi(2)),
            d_f: params.d_f,
            d_b: params.d_b,
            consts,
            resolution: *resolution,
            n_tables,
            lobes,
            dual,
            kk,
        }
    }

    pub fn params(&self) -> &FiberParams {
        &self.params
    }

    /// Per-lobe constants in radians.
    pub fn lobe_constants(&self) -> &LobeConstants {
        &self.consts
    }

    pub fn resolution(&self) -> &TableResolution {
        &self.resolution
    }

    /// The renderer's tabulated N_p at |θd|, |φ| (radians) and cos 2φh, RGB, 1/rad.
    pub fn n_table(&self, lobe: Lobe, abs_theta_d: f32, abs_phi: f32, cos_2phi_h: f32) -> Vec3 {
        self.n_tables.lookup(lobe, abs_theta_d, abs_phi, cos_2phi_h)
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
        let Some(a) = HairAngles::from_vectors(u, wi, wo) else {
            return Vec3::ZERO;
        };
        let v = match mode {
            ShadingMode::DualScattering => self.shade_dual(&a, light),
            ShadingMode::SingleScattering => self.shade_single(&a, light),
            ShadingMode::KajiyaKay => self.kk.shade(&a, light),
        };
        if v.is_finite() { v } else { Vec3::ZERO }
    }
}
