//! One budget for what a run may allocate and compute, checked before anything large exists.
//!
//! A hairstyle's fields are each bounded (`hairstyle::MAX_*`), but their products are not: a
//! file at the documented maxima would ask for tens of gigabytes, or hours of simulation. The
//! engine therefore estimates, from the hairstyle, the motion, the configuration and the run's
//! plan (frames, warm-up, export), what the run will use ([`crate::engine::estimate`]):
//!
//! - **memory**: every buffer the engine's passes and the export hold, each pass reporting its
//!   own as [`MemoryPart`]s: a product of item counts and per-item sizes taken from the real
//!   structs with `size_of`;
//! - **work before the first frame**: the settle and warm-up simulation and the first frame, in
//!   CPU-seconds from per-item costs measured on one core of a 2-core machine ([`cost_ns`]). A
//!   frame costs less than this set-up, so the bound also holds for every later frame: no run
//!   sits for long without output.
//!
//! [`Estimate::check`] refuses an estimate over a [`Budget`], naming the largest part, the
//! product it comes from and the inputs that set it.

use crate::input::human_bytes;

/// Default memory budget: 4 GB.
pub const DEFAULT_MEMORY_BYTES: u64 = 4_000_000_000;
/// Default work budget before the first frame: 20 CPU-minutes (10 minutes on 2 cores).
pub const DEFAULT_WORK_CPU_S: f64 = 1200.0;

/// Measured single-core costs (release build, one core of a 2-core machine, `wisp --threads 1
/// render` stage timings of the presets; docs/DESIGN.md, "Hostile input and the budget"). Estimates, good to
/// about 2×.
pub(crate) mod cost_ns {
    /// One simulation step of one guide particle, self-collision on (smooth: 8.6 ms for 8
    /// steps of 6,432 particles).
    pub const PARTICLE_STEP: f64 = 200.0;
    /// Interpolation, map and shading of one render point, plus drawing its segment (smooth:
    /// 108 ms for 103,850 points; curly: 280 ms for 207,700).
    pub const POINT: f64 = 1_500.0;
    /// Interpolation only, as in each 0.2 s slice of the warm-up (curly: 11 ms).
    pub const POINT_INTERP: f64 = 60.0;
    /// Clearing, the head and body, sRGB conversion and PNG encoding of one pixel.
    pub const PIXEL: f64 = 150.0;
}

/// How much a run may use.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    /// Bytes of memory.
    pub memory_bytes: u64,
    /// Estimated CPU-seconds before the first frame (and so per frame).
    pub work_cpu_s: f64,
}

impl Default for Budget {
    fn default() -> Self {
        Self {
            memory_bytes: DEFAULT_MEMORY_BYTES,
            work_cpu_s: DEFAULT_WORK_CPU_S,
        }
    }
}

/// What the run does beyond building the engine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunPlan {
    /// Seconds between frames (1 / fps).
    pub frame_interval_s: f64,
    /// Seconds simulated after the settle and before the first frame (the first frame's time).
    pub warm_up_s: f64,
    /// The frames are exported as PNG (sRGB buffers in flight and the encoder).
    pub export_png: bool,
    /// How the run uses a simulation cache.
    pub cache: CacheUse,
}

/// How a run uses a simulation cache (`wisp::cache`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CacheUse {
    /// No cache.
    #[default]
    None,
    /// `wisp simulate`: the guides are simulated and each frame's record written.
    Write,
    /// `wisp render --cache`: each frame's record is read; nothing is simulated, so there is
    /// no settle or warm-up.
    Read,
}

impl Default for RunPlan {
    fn default() -> Self {
        Self {
            frame_interval_s: 1.0 / 30.0,
            warm_up_s: 0.0,
            export_png: true,
            cache: CacheUse::None,
        }
    }
}

/// One buffer (or group of buffers) of the run.
#[derive(Clone, Debug, PartialEq)]
pub struct MemoryPart {
    /// What it is ("light map").
    pub what: &'static str,
    /// The product it comes from ("103,850 samples × 2 pieces × 96 B + ...").
    pub product: String,
    /// Bytes.
    pub bytes: u64,
    /// The inputs that set it.
    pub set_by: &'static str,
}

/// One stage of the work before the first frame.
#[derive(Clone, Debug, PartialEq)]
pub struct WorkPart {
    /// What it is ("settle and warm-up simulation").
    pub what: &'static str,
    /// The product it comes from.
    pub product: String,
    /// Estimated CPU-seconds.
    pub cpu_s: f64,
    /// The inputs that set it.
    pub set_by: &'static str,
}

/// What a run will use, part by part.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    pub memory: Vec<MemoryPart>,
    pub work: Vec<WorkPart>,
}

/// A run over its budget.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BudgetError {
    #[error(
        "this run needs about {} of memory, over the budget of {}; the largest part is the {what}: {product} = {} (set by {set_by})",
        human_bytes(*total_bytes), human_bytes(*budget_bytes), human_bytes(*part_bytes)
    )]
    Memory {
        total_bytes: u64,
        budget_bytes: u64,
        what: &'static str,
        product: String,
        part_bytes: u64,
        set_by: &'static str,
    },
    #[error(
        "this run needs about {} before its first frame, over the budget of {}; the largest part is the {what}: {product} = {} (set by {set_by})",
        cpu_time(*total_cpu_s), cpu_time(*budget_cpu_s), cpu_time(*part_cpu_s)
    )]
    Work {
        total_cpu_s: f64,
        budget_cpu_s: f64,
        what: &'static str,
        product: String,
        part_cpu_s: f64,
        set_by: &'static str,
    },
}

impl Estimate {
    /// Total bytes.
    pub fn memory_bytes(&self) -> u64 {
        self.memory
            .iter()
            .map(|p| p.bytes)
            .fold(0, u64::saturating_add)
    }

    /// Total CPU-seconds before the first frame.
    pub fn work_cpu_s(&self) -> f64 {
        self.work.iter().map(|p| p.cpu_s).sum()
    }

    /// Refuses an estimate over `budget`, naming its largest part.
    pub fn check(&self, budget: &Budget) -> Result<(), BudgetError> {
        let total_bytes = self.memory_bytes();
        if total_bytes > budget.memory_bytes
            && let Some(p) = self.memory.iter().max_by_key(|p| p.bytes)
        {
            return Err(BudgetError::Memory {
                total_bytes,
                budget_bytes: budget.memory_bytes,
                what: p.what,
                product: p.product.clone(),
                part_bytes: p.bytes,
                set_by: p.set_by,
            });
        }
        let total_cpu_s = self.work_cpu_s();
        // A NaN estimate is refused too.
        if (total_cpu_s.is_nan() || total_cpu_s > budget.work_cpu_s)
            && let Some(p) = self.work.iter().max_by(|a, b| a.cpu_s.total_cmp(&b.cpu_s))
        {
            return Err(BudgetError::Work {
                total_cpu_s,
                budget_cpu_s: budget.work_cpu_s,
                what: p.what,
                product: p.product.clone(),
                part_cpu_s: p.cpu_s,
                set_by: p.set_by,
            });
        }
        Ok(())
    }
}

/// "0.25 CPU-seconds", "37 CPU-minutes", "3.1 CPU-hours".
fn cpu_time(s: f64) -> String {
    if s < 120.0 {
        format!("{s:.2} CPU-seconds")
    } else if s < 7200.0 {
        format!("{:.0} CPU-minutes", s / 60.0)
    } else {
        format!("{:.1} CPU-hours", s / 3600.0)
    }
}

/// "1,234,567".
pub(crate) fn grouped(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests;
