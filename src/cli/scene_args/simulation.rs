//! The simulation pass's flags ([`SimulationConfig`]).

use wisp::engine::SimulationConfig;

#[derive(clap::Args, Debug, Clone)]
#[command(next_help_heading = "Simulation")]
pub struct SimulationArgs {
    /// Do not simulate: the hair keeps its rest shape, riding on the head
    #[arg(long)]
    pub no_sim: bool,
    /// Turn off density-based self-collision
    #[arg(long)]
    pub no_self_collision: bool,
}

impl SimulationArgs {
    /// Writes the flags into the simulation's config.
    pub fn apply(&self, config: &mut SimulationConfig) {
        config.self_collision = !self.no_self_collision;
        config.simulate = !self.no_sim;
    }
}
