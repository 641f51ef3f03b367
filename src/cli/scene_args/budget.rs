//! The run's budget (`wisp::budget`): the most memory and set-up work a run may take. A run
//! estimated over it is refused (exit code 2) before the engine allocates anything large.

use crate::cli::{AppError, parse_budget};
use wisp::budget::{Budget, BudgetError, RunPlan};
use wisp::engine::EngineConfig;
use wisp::hairstyle::Hairstyle;
use wisp::motion::Motion;

#[derive(clap::Args, Debug, Clone)]
#[command(next_help_heading = "Budget")]
pub struct BudgetArgs {
    /// Refuse a run estimated to need more memory, GB
    #[arg(long, value_name = "GB", default_value_t = 4.0, value_parser = parse_budget, allow_hyphen_values = true)]
    pub max_memory_gb: f64,
    /// Refuse a run whose set-up is estimated longer, CPU-min
    #[arg(long, value_name = "MIN", default_value_t = 20.0, value_parser = parse_budget, allow_hyphen_values = true)]
    pub max_work_cpu_min: f64,
}

impl BudgetArgs {
    /// The budget the flags set.
    pub fn budget(&self) -> Budget {
        Budget {
            memory_bytes: (self.max_memory_gb * 1e9) as u64,
            work_cpu_s: self.max_work_cpu_min * 60.0,
        }
    }

    /// Refuses a run over the budget (exit code 2), before the engine allocates. An automatic
    /// map resolution is lowered first, with a warning, when that brings the run within the
    /// memory budget.
    pub fn check(
        &self,
        style: &Hairstyle,
        motion: &Motion,
        config: &mut EngineConfig,
        plan: &RunPlan,
    ) -> Result<(), AppError> {
        if let Some((auto, n)) =
            wisp::engine::fit_map_resolution(style, motion, config, plan, &self.budget())
        {
            eprintln!(
                "wisp: warning: the automatic map resolution {auto} (cells of 1.5 strand spacings at the scalp) could need more memory than --max-memory-gb {}; using {n}",
                self.max_memory_gb
            );
            config.hair_map.map_res = Some(n);
        }
        wisp::engine::estimate(style, motion, config, plan)
            .check(&self.budget())
            .map_err(|e| {
                let flag = match e {
                    BudgetError::Memory { .. } => "--max-memory-gb",
                    BudgetError::Work { .. } => "--max-work-cpu-min",
                };
                AppError::input(anyhow::anyhow!(
                    "{e}. Lower it, or raise the budget with {flag}"
                ))
            })
    }
}
