//! What a level's map rate costs (`HairMapConfig::rebuild_interval_s`): the frames a window
//! draws at [`WINDOW_FPS`] through the dance's fastest head motion, lit by maps built at the
//! level's rate, against the same frames lit by maps built for every frame. Both runs simulate
//! the same guides and share the camera, so the difference is the late shadows alone: the
//! relative luminance error over the hair's pixels (mean and 95th percentile, means over the
//! frames) and the mean ꟻLIP over the whole frame (every [`FLIP_EVERY`]th frame; a ꟻLIP of a
//! 1280 × 720 frame takes about half a second).

use super::BenchScene;
use wisp::accuracy::image::{flip_mean, hair_mask, image_error};
use wisp::engine::{CameraPass, EngineConfig};

/// The window's frame rate, frames a second.
pub const WINDOW_FPS: f64 = 60.0;

/// The stretch of the dance compared, seconds: its fastest head motions.
pub const SPAN_S: (f64, f64) = (4.2, 4.9);

/// ꟻLIP is taken on one frame in this many.
const FLIP_EVERY: usize = 6;

/// The map rate's error, means over the frames compared.
#[derive(Clone, Copy, Debug)]
pub struct MapRateError {
    pub frames: usize,
    pub mean_rel_luminance: f64,
    pub p95_rel_luminance: f64,
    pub flip: f64,
}

/// The error of `config`'s map rate (the module doc), seen by `camera`; `None` when the level
/// builds its maps for every frame.
pub fn map_rate_error(
    scene: &BenchScene,
    config: &EngineConfig,
    camera: &CameraPass,
) -> Option<MapRateError> {
    if config.hair_map.rebuild_interval_s <= 0.0 {
        return None;
    }
    let mut every_frame = config.clone();
    every_frame.hair_map.rebuild_interval_s = 0.0;
    let mut hair_only = every_frame.clone();
    hair_only.scene.draw_solids = false;
    let mut engines = [config.clone(), every_frame, hair_only].map(|c| {
        let mut engine = scene.engine_with(c);
        engine.camera = camera.clone();
        engine.run_up_to(SPAN_S.0);
        engine
    });
    let frames = ((SPAN_S.1 - SPAN_S.0) * WINDOW_FPS).round() as usize;
    let (mut mean, mut p95, mut flip, mut compared, mut flips) = (0.0, 0.0, 0.0, 0, 0);
    for k in 1..=frames {
        let t_s = SPAN_S.0 + k as f64 / WINDOW_FPS;
        for engine in &mut engines {
            engine.frame(t_s);
        }
        let [at_rate, every, hair] = &engines;
        let mask = hair_mask(hair.framebuffer());
        if let Some(e) = image_error(at_rate.framebuffer(), every.framebuffer(), &mask) {
            (mean, p95, compared) = (
                mean + e.mean_rel_luminance,
                p95 + e.p95_rel_luminance,
                compared + 1,
            );
        }
        if k % FLIP_EVERY == 0
            && let Some(f) = flip_mean(at_rate.framebuffer(), every.framebuffer())
        {
            (flip, flips) = (flip + f, flips + 1);
        }
    }
    let n = compared.max(1) as f64;
    Some(MapRateError {
        frames: compared,
        mean_rel_luminance: mean / n,
        p95_rel_luminance: p95 / n,
        flip: flip / flips.max(1) as f64,
    })
}
