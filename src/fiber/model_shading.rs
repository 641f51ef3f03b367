//! The chosen fibre model's shading data, built once per fibre: its lobes' tables interleaved
//! on one grid so the shader fetches every lobe of a vertex with one bilinear lookup, and its
//! longitudinal constants. Marschner: N_R, N_TT and the three N^G on (|θd|, |φ|), N_TRT apart
//! (it also depends on cos 2φh through η*), the Gaussians' 1/√(2π v) and −1/(2v) per lobe.
//! Chiang: N̄_0..3 and N^G_0..2 on (|θo|, |φ|), d'Eon's lobes (`longitudinal.rs`).

use super::chiang::ChiangConstants;
use super::chiang_tables::ChiangTables;
use super::dual::DualTables;
use super::longitudinal::DeonLobes;
use super::params::{Lobe, LobeConstants};
use super::tables::{self, NTables, TableResolution};

/// The Marschner model's shading data: N tables and the Gaussian lobes' constants.
#[derive(Clone, Debug)]
pub(crate) struct MarschnerShading {
    pub(crate) n_tables: NTables,
    /// [N_R, N_TT, N^G_R, N^G_TT, N^G_TRT] interleaved on one (|θd|, |φ|) grid.
    pub(crate) lobes: tables::Table2x<5>,
    /// Lobe means 2α_p and variances (2β_p)² in x = θi + θo (radians, rad²).
    pub(crate) mean_x: [f32; 3],
    pub(crate) var_x: [f32; 3],
    /// 1/√(2π var_x) and −1/(2 var_x): the unbroadened lobes' Gaussian constants.
    pub(crate) m_norm: [f32; 3],
    pub(crate) m_exp: [f32; 3],
}

/// The Chiang model's shading data: N̄ and N^G tables and the d'Eon lobes' constants.
#[derive(Clone, Debug)]
pub(crate) struct ChiangShading {
    pub(crate) tables: ChiangTables,
    /// [N̄_R, N̄_TT, N̄_TRT, N̄_3, N^G_R, N^G_TT, N^G_TRT] interleaved on one (|θo|, |φ|) grid
    /// (N^G_3 = N̄_3: the residual is uniform in φ).
    pub(crate) lobes: tables::Table2x<7>,
    pub(crate) deon: DeonLobes,
}

impl MarschnerShading {
    /// The Marschner model's N tables and dual tables (forward window of half-width `window`,
    /// radians), with its lobes interleaved for one fetch and the Gaussians' constants.
    pub(super) fn build(
        consts: &LobeConstants,
        resolution: &TableResolution,
        window: f64,
    ) -> (MarschnerShading, DualTables) {
        let n_tables = NTables::build(consts, resolution);
        let dual = DualTables::build(consts, resolution, window);
        let lobes = tables::Table2x::zip([
            &n_tables.r,
            &n_tables.tt,
            &dual.n_g[0],
            &dual.n_g[1],
            &dual.n_g[2],
        ]);
        let lobe = |f: &dyn Fn(Lobe) -> f64| Lobe::ALL.map(|l| f(l) as f32);
        let m = MarschnerShading {
            mean_x: lobe(&|l| consts.mean_x(l)),
            var_x: lobe(&|l| consts.std_x(l).powi(2)),
            m_norm: lobe(&|l| 1.0 / (2.0 * std::f64::consts::PI * consts.std_x(l).powi(2)).sqrt()),
            m_exp: lobe(&|l| -0.5 / consts.std_x(l).powi(2)),
            n_tables,
            lobes,
        };
        (m, dual)
    }
}

impl ChiangShading {
    /// The Chiang model's N̄ tables and dual tables (forward window of half-width `window`,
    /// radians), with its lobes interleaved for one fetch and d'Eon's lobes.
    pub(super) fn build(
        chiang: &ChiangConstants,
        resolution: &TableResolution,
        window: f64,
    ) -> (ChiangShading, DualTables) {
        let tables = ChiangTables::build(chiang, resolution);
        let dual = DualTables::build(chiang, resolution, window);
        let lobes = tables::Table2x::zip([
            &tables.n_bar[0],
            &tables.n_bar[1],
            &tables.n_bar[2],
            &tables.n_bar[3],
            &dual.n_g[0],
            &dual.n_g[1],
            &dual.n_g[2],
        ]);
        let deon = DeonLobes::new(chiang);
        (
            ChiangShading {
                tables,
                lobes,
                deon,
            },
            dual,
        )
    }
}

/// The chosen model's shading data (matched once per `shade` call).
#[derive(Clone, Debug)]
pub(crate) enum ModelShading {
    Marschner(MarschnerShading),
    Chiang(ChiangShading),
}
