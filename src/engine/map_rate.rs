//! The hair maps at a lower rate than the frames: built at most once per
//! `HairMapConfig::rebuild_interval_s` of motion, the hair of the frames between lit by the
//! last build, each render-strand point read where it was then (`map::BuiltEarlier`). The
//! occluders and the skin texture, which are cheaper and follow the body, are built for every
//! frame in the last build's light frames.
//!
//! Hair moves little in a 60th of a second, and its self-shadowing changes less than its
//! outline: a window drawing 60 frames a second can light its hair from maps built 30 times a
//! second. What it costs is a shadow late by up to one interval, measured on the dance
//! (BENCHMARKS.md, "Quality levels": 1.5% mean relative luminance error over the hair, ꟻLIP
//! 0.002, where reading the old maps where the hair is now cost 15%).
//!
//! The rate counts seconds of motion, not frames or wall time, so the frames of a run depend
//! only on the times asked for (not on the machine or the thread count). A jump back in time,
//! guides set from outside (a cache, a snapshot), an invalidation or lights that changed
//! (the window turns them) build at once.

use crate::light::Light;

/// When the map stage was last built, and from which lights.
#[derive(Clone, Debug, Default)]
pub(crate) struct MapSchedule {
    /// Motion time of the last build, `None` before the first or after [`Self::forget`].
    built_at_s: Option<f64>,
    lights: Vec<Light>,
}

impl MapSchedule {
    /// Whether the map stage must be built for a frame at `t_s` with `lights`, at most one
    /// build every `interval_s` (0 or less: every frame).
    pub fn due(&self, t_s: f64, lights: &[Light], interval_s: f64) -> bool {
        let Some(last_s) = self.built_at_s else {
            return true;
        };
        // A small tolerance so that an interval of exactly two frames (1/30 s at 1/60 s
        // frames) is not missed by the rounding of the frame times.
        let elapsed_s = t_s - last_s;
        interval_s <= 0.0
            || elapsed_s.is_nan()
            || elapsed_s < 0.0
            || elapsed_s >= interval_s * (1.0 - 1e-6)
            || self.lights != lights
    }

    /// Records a build for the frame at `t_s` with `lights`.
    pub fn built(&mut self, t_s: f64, lights: &[Light]) {
        self.built_at_s = Some(t_s);
        self.lights.clear();
        self.lights.extend_from_slice(lights);
    }

    /// Makes the next frame build.
    pub fn forget(&mut self) {
        self.built_at_s = None;
    }
}

#[cfg(test)]
mod tests;
