//! The light paths at a lower rate than the frames: built once per slot of
//! `ShadingConfig::paths_interval_s` seconds of motion, from the hair of the first frame in
//! the slot, and gathered by the slot's later frames where each point was at the build (the
//! head's motion since then undone, as `map_rate` reads the hair maps).
//!
//! Multiply scattered light is smooth: it diffuses over centimetres of hair, and the hair
//! moves with the head. Tracing the paths is most of the light-path shader's time and the
//! gather a tenth of it, so building them every few frames divides the shader's cost by
//! about that many; what it costs is light late by up to one slot, measured on the dance
//! (BENCHMARKS.md, "`final`'s paths").
//!
//! Slots are aligned to the motion's clock (slot k holds the times [k·I, (k+1)·I)), not counted
//! from the first frame rendered: a frame's colours then depend only on the times asked for,
//! so a run that starts inside a slot (a shard of a cache, `--first-frame`) builds from the
//! slot's first frame as a run from the start does, and gets the same bytes. Lights that
//! changed (the window turns them), other path parameters or another fibre build at once.

use crate::fiber::FiberParams;
use crate::light::Light;
use crate::light_paths::LightPathParams;
use glam::Affine3A;

/// Tolerance on a time's slot, so that the frame at exactly k·I (k/10 s at 30 frames a
/// second, rounded) falls in slot k.
const SLOT_TOLERANCE: f64 = 1e-6;

/// The slot of `t_s` for builds every `interval_s` seconds (> 0).
pub(crate) fn slot_of(t_s: f64, interval_s: f64) -> i64 {
    (t_s / interval_s + SLOT_TOLERANCE).floor() as i64
}

/// What the light paths were built from, and when.
#[derive(Clone, Debug, Default)]
pub(crate) struct PathsSchedule {
    /// Motion time of the last build, `None` before the first or after [`Self::forget`].
    built_at_s: Option<f64>,
    lights: Vec<Light>,
    params: Option<(LightPathParams, FiberParams)>,
    /// The head's pose at the build (world from head).
    head_at_build: Affine3A,
}

/// What a build is made with besides the hair: compared with the last build's.
pub(crate) struct PathsKey<'a> {
    pub lights: &'a [Light],
    pub params: &'a LightPathParams,
    pub fiber: &'a FiberParams,
}

impl PathsSchedule {
    /// Whether the light paths must be built for the frame at `t_s`: none yet, every frame
    /// (`interval_s` 0 or less), a new slot, or other lights, parameters or fibre.
    pub fn due(&self, t_s: f64, interval_s: f64, key: &PathsKey) -> bool {
        let Some(last_s) = self.built_at_s else {
            return true;
        };
        interval_s <= 0.0
            || !t_s.is_finite()
            || slot_of(t_s, interval_s) != slot_of(last_s, interval_s)
            || self.lights != key.lights
            || self
                .params
                .as_ref()
                .is_none_or(|(p, f)| p != key.params || f != key.fiber)
    }

    /// Records a build for the frame at `t_s`, with the head at `head`.
    pub fn built(&mut self, t_s: f64, key: &PathsKey, head: Affine3A) {
        self.built_at_s = Some(t_s);
        self.lights.clear();
        self.lights.extend_from_slice(key.lights);
        self.params = Some((*key.params, key.fiber.clone()));
        self.head_at_build = head;
    }

    /// Motion time of the last build.
    pub fn built_at_s(&self) -> Option<f64> {
        self.built_at_s
    }

    /// World now → world at the build, for a frame at `t_s` with the head at `head`; `None`
    /// when the paths were built for this very frame. A head that has not moved gives the
    /// identity, which carries vectors back to the bit (a still head does not flicker).
    pub fn head_back(&self, t_s: f64, head: Affine3A) -> Option<Affine3A> {
        match self.built_at_s {
            Some(b) if b != t_s => Some(if head == self.head_at_build {
                Affine3A::IDENTITY
            } else {
                self.head_at_build * head.inverse()
            }),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests;
