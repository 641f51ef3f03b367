//! Dual-scattering fibre quantities (Zinke et al. 2008 §3 and Table 1), tabulated over the
//! light's inclination θ ∈ [−π/2, π/2] (radians; the tables are not even in θ because the
//! cuticle tilt α shifts the lobes), plus N^G(key, φ) (Eq. 25), for either fibre model
//! ([`DualModel`]: Marschner 2003 or Chiang 2016; the key of the azimuthal tables is |θd| for
//! Marschner and |θo| for Chiang).
//!
//! How: every azimuthal integral of N_p is done in h (Eq. 8's bookkeeping: ∫ N_p w(φ) dφ =
//! ∫ A(p, h) w(φ(p, h)) dh / 2), which needs no root solving and has a smooth integrand; only
//! the TRT glints are integrated in φ (Marschner) and Chiang's logistic is convolved in closed
//! form (`chiang_tables`). Then one longitudinal quadrature over θo per table entry. Building
//! every table for the default fibre takes tens of milliseconds (see `benches/fiber.rs`).
//!
//! Readings chosen (each pinned by a test in `tests/lib/fiber_tables.rs`, `backscatter.rs` or
//! `tests/lib/fiber_energy.rs`):
//! - **Eq. 6/12, which hemisphere.** The incident azimuth is averaged over the half circle
//!   facing the light and the outgoing one is split into the world-fixed front (away from the
//!   light) and back halves, as the double integral prints; for a relative azimuth φ the
//!   weights are w_f(φ) = |φ|/π and w_b = 1 − |φ|/π. The alternative (split by relative azimuth,
//!   w_f = [|φ| > π/2]) ignores the (1/π)∫dφ average of the printed formula.
//! - **Trap 4, Eq. 6's cosine.** Eq. 6 prints cos θd of the *incident* direction. We weight by
//!   cos θ of the *outgoing* direction instead: ā_f(θi) = (1/π)∫∫ f_s cos θo dωo (dωo = cos θo
//!   dθo dφo), the fraction of the power the fibre intercepts that leaves through the front half,
//!   so ā_f + ā_b is the fibre's hemispherical albedo (checked against a brute-force quadrature
//!   of S in tests/lib/fiber_energy.rs). Why: ā_f is used as a per-crossing transmittance, and the
//!   map already weights grazing crossings by their projected width. The two readings agree
//!   for narrow lobes (θo ≈ −θi) but not at grazing incidence: the incident reading carries
//!   cos θi cos θo / cos²θd = 1 − sin²θh/cos²θd, which goes to 0 across the lobe as |θi| → 90°,
//!   so a grazing crossing would become opaque (σa = 0, θ = 80°: ā_f = 0.33 against 0.57;
//!   pinned by `trap4_outgoing_cosine` in tests/lib/fiber_tables.rs).
//! - **White-furnace normalisation.** Marschner's S is not energy conserving: with σa = 0 its
//!   albedo ρ_w(θ) reaches 1.02 at θ = 60° and 1.84 at θ = −90° (its 1/cos²θd with lobes cut at
//!   θo = ±90°; tests/lib/fiber_energy.rs). ā_f and ā_b are fractions of the intercepted power, so
//!   both are divided by max(1, ρ_w(θ)), the same geometric factor for every absorption: this
//!   keeps ā_f + ā_b ≤ 1 and keeps lighter fibres' ā_f larger (a per-fibre clamp to 1 would not).
//! - **Trap 1** is resolved in `marschner::longitudinal_m` (unit area in θo).
//! - **Trap 2.** Every Gaussian is in radians; shifts/variances are in x = θi + θo. Eq. 17's
//!   fit adds a number (ā_b) to an angle (ā_b³(2β̄_f + 3β̄_b)), so its value depends on the unit;
//!   we evaluate the series printed above Eqs. 16–17 instead (closed form by counting: the triple
//!   sum has n(n+1)/2 terms with i − j − 1 + k = n), which is unit-consistent.
//! - **Trap 3.** Deriving that series to second order in ā_b gives
//!   Δ̄_b ≈ ᾱ_b(1 **+** 2ā_b²/(1 − ā_f²)²) + ᾱ_f(2(1 − ā_f²)² + 4ā_f²ā_b²)/(1 − ā_f²)³: the printed
//!   minus sign is wrong (its ᾱ_f coefficient is right). We use the exact closed form.
//! - **Trap 6.** 1 − ā_f² divides A_b, Δ_b and σ_b; ā_f is clamped to [`A_F_MAX`] before them.
//! - **Trap 5, Eq. 25** is read as the convolution N^G(θ, φ) = ∫ s̃_f(φ') N(θ, φ − φ') dφ' over
//!   φ' ∈ [−w, w] with s̃_f = 1/(2w), w = π/2 (Zinke's 1/π; `FiberParams::forward_spread_deg`):
//!   light arriving isotropically from the front half circle around the light direction. The printed form (N(θ, φ') with no φ) would be a constant in φ,
//!   making forward-scattered light look the same from every side; the convolution keeps TT's
//!   preference for φ ≈ π (more than 5× its φ = 0 value, `trap5_n_g_is_a_convolution`).
//! - Lobe shifts/variances of the front and back halves: ᾱ = Σ_p w_p μ_p, β̄² = Σ_p w_p
//!   (v_p + μ_p²) − ᾱ² (moment matching the mixture), w_p the lobe's share of ā, μ_p and v_p the
//!   lobe's mean and variance in x = θi + θo (Marschner: 2α_p, (2β_p)²; Chiang: the tilt and
//!   d'Eon's v_p, whose true spread is slightly wider than √v_p for v_p ≳ 0.1).
//! - **Chiang's forward albedo** ∫ S cos θo dωo exceeds 1 at grazing incidence (S = ḡ/cos θi,
//!   `chiang.rs`: 1.40 at 80° for β_R = 7.5°) although a white fibre in a white furnace looks
//!   exactly white; the same max(1, ρ_w) normalisation keeps ā_f + ā_b ≤ 1 (a path tracer with
//!   this model would let grazing light gain energy per crossing; wisp does not).
//! - Tables ignore eccentricity (circular fibre of index η), as Zinke §4.2 does for N^G.
//! - **Flux is not fluence** ([`window_fluence`]). T_f = ∏ ā_f counts the *power* that keeps
//!   going forward past each crossing of the shadow path (a flux along it), but Eq. 7 spreads
//!   T_f as a unit-fluence distribution (∫ S_f dω = 1). Light that has left the path's
//!   direction crosses the hair's layers obliquely: a fibre intercepts its fluence, which is
//!   the flux times w/sin w for Eq. 7's window. Read literally, Eq. 5 feeds a shadowed fibre
//!   2/π of the forward light the window spreads; the shader multiplies by the factor, taken
//!   at the light's inclination to the fibre ([`window_fluence_inclined`]: 1 along the fibre).

mod model;
mod shares;
mod window;

pub use super::azimuthal::{
    AzimuthalSamples, LobeSamples, lobe_integral, n_g_direct, w_backward, w_forward,
};
pub use super::backscatter::{
    A_F_MAX, big_a_b, delta_b, delta_b_printed, sigma_b_printed, sigma_b2,
};
use super::params::Lobe;
use super::tables::{Table1, Table2, TableResolution};
pub use model::DualModel;
pub use shares::{CosineReading, LobeShares, shares_direct, white_albedo};
use shares::{SplitTable, shares_at};
pub use window::{ScatteredGain, window_fluence, window_fluence_inclined};

use glam::Vec3;
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// Most lobes of any model: Marschner's R, TT, TRT and Chiang's p ≥ 3 residual.
pub const MAX_LOBES: usize = 4;

/// Every dual-scattering quantity at one light inclination, RGB (angles in radians of x =
/// θi + θo, variances in rad²).
#[derive(Clone, Copy, Debug, Default)]
pub struct DualQuantities {
    pub a_f: [f64; 3],
    pub a_b: [f64; 3],
    pub alpha_f: [f64; 3],
    pub alpha_b: [f64; 3],
    pub beta_f2: [f64; 3],
    pub beta_b2: [f64; 3],
    pub big_a_b: [f64; 3],
    pub delta_b: [f64; 3],
    pub sigma_b2: [f64; 3],
}

impl DualQuantities {
    /// Combines lobe shares into the Zinke quantities (module doc for the readings).
    /// `white_albedo` is ρ_w(θ), the σa = 0 albedo at the same θ ([`white_albedo`]).
    pub fn from_shares<M: DualModel>(c: &M, s: &LobeShares, white_albedo: f64) -> Self {
        let mut q = Self::default();
        let lobes = c.lobes();
        let moments = |shares: &[[f64; 3]; MAX_LOBES], ch: usize| {
            let total: f64 = (0..lobes).map(|p| shares[p][ch]).sum();
            if total <= 0.0 {
                return (0.0, 0.0, 0.0);
            }
            let mean: f64 = (0..lobes)
                .map(|l| shares[l][ch] * c.lobe_mean_x(l))
                .sum::<f64>()
                / total;
            let second: f64 = (0..lobes)
                .map(|l| shares[l][ch] * (c.lobe_var_x(l) + c.lobe_mean_x(l).powi(2)))
                .sum::<f64>()
                / total;
            (total, mean, (second - mean * mean).max(0.0))
        };
        for ch in 0..3 {
            let (a_f, alpha_f, beta_f2) = moments(&s.forward, ch);
            let (a_b, alpha_b, beta_b2) = moments(&s.backward, ch);
            // White-furnace normalisation (module doc), then a guard for rounding.
            let (a_f, a_b) = (a_f / white_albedo.max(1.0), a_b / white_albedo.max(1.0));
            let sum = a_f + a_b;
            let (a_f, a_b) = if sum > 1.0 {
                (a_f / sum, a_b / sum)
            } else {
                (a_f, a_b)
            };
            let a_f = a_f.min(A_F_MAX);
            q.a_f[ch] = a_f;
            q.a_b[ch] = a_b;
            q.alpha_f[ch] = alpha_f;
            q.alpha_b[ch] = alpha_b;
            q.beta_f2[ch] = beta_f2;
            q.beta_b2[ch] = beta_b2;
            q.big_a_b[ch] = big_a_b(a_f, a_b);
            q.delta_b[ch] = delta_b(a_f, a_b, alpha_f, alpha_b);
            q.sigma_b2[ch] = sigma_b2(a_f, a_b, beta_f2, beta_b2);
        }
        q
    }
}

/// All dual-scattering tables of one fibre.
#[derive(Clone, Debug)]
pub struct DualTables {
    /// Grid of light inclinations θ (radians), uniform over [−π/2, π/2].
    pub theta: Vec<f64>,
    /// Quantities at each grid θ.
    pub at: Vec<DualQuantities>,
    /// Lobe shares at each grid θ.
    pub shares: Vec<LobeShares>,
    pub(crate) a_f: Table1,
    pub(crate) a_b: Table1,
    pub(crate) beta_f2: Table1,
    pub(crate) big_a_b: Table1,
    pub(crate) delta_b: Table1,
    pub(crate) sigma_b2: Table1,
    /// N^G_p(key, φ) (Eq. 25) per lobe [R, TT, TRT (, p ≥ 3)], keyed like the model's N.
    pub(crate) n_g: Vec<Table2>,
}

impl DualTables {
    /// Builds every table of model `c`; `window` is the forward spread's half-width (radians).
    pub fn build<M: DualModel>(c: &M, res: &TableResolution, window: f64) -> Self {
        let (split, n_g) = SplitTable::build_with_n_g(c, res.n_theta_d, res.n_phi, window);
        let n = res.n_theta.max(2);
        let theta: Vec<f64> = (0..n)
            .map(|i| -FRAC_PI_2 + PI * i as f64 / (n - 1) as f64)
            .collect();
        let shares: Vec<LobeShares> = theta
            .par_iter()
            .map(|&t| shares_at(c, t, Some(&split), CosineReading::Outgoing))
            .collect();
        let white = c.white();
        let white_split = SplitTable::build(&white, res.n_theta_d);
        let at: Vec<DualQuantities> = theta
            .par_iter()
            .zip(&shares)
            .map(|(&t, s)| {
                let w = shares_at(&white, t, Some(&white_split), CosineReading::Outgoing);
                DualQuantities::from_shares(c, s, w.albedo())
            })
            .collect();
        let lut = |f: &dyn Fn(&DualQuantities) -> [f64; 3]| {
            Table1::new(
                -FRAC_PI_2,
                FRAC_PI_2,
                at.iter()
                    .map(|q| Vec3::from(f(q).map(|x| x as f32)))
                    .collect(),
            )
        };
        Self {
            a_f: lut(&|q| q.a_f),
            a_b: lut(&|q| q.a_b),
            beta_f2: lut(&|q| q.beta_f2),
            big_a_b: lut(&|q| q.big_a_b),
            delta_b: lut(&|q| q.delta_b),
            sigma_b2: lut(&|q| q.sigma_b2),
            theta,
            at,
            shares,
            n_g,
        }
    }

    /// All quantities at light inclination θ (radians), linearly interpolated between grid
    /// points (what the renderer's lookups return, in f64).
    pub fn quantities_at(&self, theta: f64) -> DualQuantities {
        let n = self.theta.len();
        let f = ((theta + FRAC_PI_2) / PI * (n - 1) as f64).clamp(0.0, (n - 1) as f64);
        let i = (f as usize).min(n - 2);
        let t = f - i as f64;
        let (a, b) = (&self.at[i], &self.at[i + 1]);
        let mix = |x: [f64; 3], y: [f64; 3]| [0, 1, 2].map(|k| x[k] * (1.0 - t) + y[k] * t);
        DualQuantities {
            a_f: mix(a.a_f, b.a_f),
            a_b: mix(a.a_b, b.a_b),
            alpha_f: mix(a.alpha_f, b.alpha_f),
            alpha_b: mix(a.alpha_b, b.alpha_b),
            beta_f2: mix(a.beta_f2, b.beta_f2),
            beta_b2: mix(a.beta_b2, b.beta_b2),
            big_a_b: mix(a.big_a_b, b.big_a_b),
            delta_b: mix(a.delta_b, b.delta_b),
            sigma_b2: mix(a.sigma_b2, b.sigma_b2),
        }
    }

    /// N^G_p(key, |φ|) from the table, RGB, 1/rad; the key is |θd| (Marschner) or |θo|
    /// (Chiang).
    #[inline]
    pub fn n_g(&self, lobe: Lobe, abs_key: f32, abs_phi: f32) -> Vec3 {
        self.n_g[lobe as usize].lookup(abs_key, abs_phi)
    }

    /// N^G of lobe index `lobe` (0 R, 1 TT, 2 TRT, 3 Chiang's p ≥ 3; clamped to the model's
    /// lobes) at (key, |φ|), RGB, 1/rad.
    pub fn n_g_lobe(&self, lobe: usize, abs_key: f32, abs_phi: f32) -> Vec3 {
        self.n_g[lobe.min(self.n_g.len() - 1)].lookup(abs_key, abs_phi)
    }

    /// Number of N^G tables (the model's lobes).
    pub fn n_g_lobes(&self) -> usize {
        self.n_g.len()
    }

    /// (ā_f, ā_b) at light inclination θ (radians), interpolated (for the local-density
    /// truncation of Ā_b, `backscatter::truncation`).
    #[inline]
    pub fn attenuations_at(&self, theta: f32) -> (Vec3, Vec3) {
        (self.a_f.lookup(theta), self.a_b.lookup(theta))
    }

    /// (Ā_b, Δ̄_b, σ̄_b²) at light inclination θ (radians), interpolated.
    #[inline]
    pub fn back_at(&self, theta: f32) -> (Vec3, Vec3, Vec3) {
        (
            self.big_a_b.lookup(theta),
            self.delta_b.lookup(theta),
            self.sigma_b2.lookup(theta),
        )
    }

    /// (ā_f, β̄_f²) at light inclination θ (radians), interpolated.
    #[inline]
    pub fn forward_at(&self, theta: f32) -> (Vec3, Vec3) {
        (self.a_f.lookup(theta), self.beta_f2.lookup(theta))
    }
}
