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
    /// Simulation steps per second, 20–50000 [default: the hairstyle's, 480; 240 at
    /// --quality preview, 960 at reference]
    #[arg(long, value_name = "HZ", value_parser = clap::value_parser!(u32).range(20..=50_000), help_heading = "Quality")]
    pub sim_hz: Option<u32>,
}

impl SimulationArgs {
    /// Writes the flags into the simulation's config.
    pub fn apply(&self, config: &mut SimulationConfig) {
        config.self_collision = !self.no_self_collision;
        config.simulate = !self.no_sim;
        if let Some(hz) = self.sim_hz {
            config.step_s = Some(1.0 / hz as f32);
        }
    }
}
