//! What a level's lower rates cost: the frames through the dance's fastest head motion with a
//! stage built at the level's rate against the same frames with it built for every frame.
//! Two stages have a rate: the hair maps (`HairMapConfig::rebuild_interval_s`, compared at the
//! window's [`WINDOW_FPS`]) and the light paths (`ShadingConfig::paths_interval_s`, compared
//! at the export's [`EXPORT_FPS`], and both it and a build for every frame against converged
//! paths, since paths built for every frame are noisy themselves: [`paths_rate_error`]). The
//! runs simulate the same guides and share the camera, so the difference is the light alone: the relative luminance error over the hair's
//! pixels (mean and 95th percentile, means over the frames) and the mean ꟻLIP over the whole
//! frame (every [`FLIP_EVERY`]th frame; a ꟻLIP of a 1280 × 720 frame takes about half a
//! second).

use super::BenchScene;
use wisp::accuracy::image::{flip_mean, hair_mask, image_error};
use wisp::engine::{CameraPass, EngineConfig};

/// The window's frame rate, frames a second.
pub const WINDOW_FPS: f64 = 60.0;

/// The export's frame rate, frames a second.
pub const EXPORT_FPS: f64 = 30.0;

/// The stretch of the dance compared, seconds: its fastest head motions.
pub const SPAN_S: (f64, f64) = (4.2, 4.9);

/// The light paths' rate is measured against frames with this many times the level's paths.
pub const CONVERGED_PATHS: u32 = 10;

/// ꟻLIP is taken on one frame in this many: 5, so that it falls on every place in a slot of
/// two or three frames.
const FLIP_EVERY: usize = 5;

/// A rate's error, means over the frames compared.
#[derive(Clone, Copy, Debug)]
pub struct RateError {
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
) -> Option<RateError> {
    if config.hair_map.rebuild_interval_s <= 0.0 {
        return None;
    }
    let mut every_frame = config.clone();
    every_frame.hair_map.rebuild_interval_s = 0.0;
    Some(rate_error(
        scene,
        [config, &every_frame],
        camera,
        WINDOW_FPS,
    ))
}

/// How far `config`'s light-path rate (the module doc) puts the frames from converged light,
/// seen by `camera`: its frames, and the same with the paths built for every frame, each
/// against frames built for every frame with [`CONVERGED_PATHS`] times the paths. A rate
/// costs what the first error exceeds the second by; the second is the paths' own noise.
/// `None` when the level has no light paths or builds them for every frame.
pub fn paths_rate_error(
    scene: &BenchScene,
    config: &EngineConfig,
    camera: &CameraPass,
) -> Option<(RateError, RateError)> {
    if !config.shading.paths_at_rate() {
        return None;
    }
    let mut every_frame = config.clone();
    every_frame.shading.paths_interval_s = 0.0;
    let mut converged = every_frame.clone();
    let paths = &mut converged.shading.light_paths.paths;
    *paths = paths.saturating_mul(CONVERGED_PATHS);
    Some((
        rate_error(scene, [config, &converged], camera, EXPORT_FPS),
        rate_error(scene, [&every_frame, &converged], camera, EXPORT_FPS),
    ))
}

/// The frames of [`SPAN_S`] at `fps` drawn with `at_rate` against `every_frame`, over the hair
/// that `every_frame` draws without the solids.
fn rate_error(
    scene: &BenchScene,
    [at_rate, every_frame]: [&EngineConfig; 2],
    camera: &CameraPass,
    fps: f64,
) -> RateError {
    let mut hair_only = every_frame.clone();
    hair_only.scene.draw_solids = false;
    let mut engines = [at_rate.clone(), every_frame.clone(), hair_only].map(|c| {
        let mut engine = scene.engine_with(c);
        engine.camera = camera.clone();
        engine.run_up_to(SPAN_S.0);
        engine
    });
    let frames = ((SPAN_S.1 - SPAN_S.0) * fps).round() as usize;
    let (mut mean, mut p95, mut flip, mut compared, mut flips) = (0.0, 0.0, 0.0, 0, 0);
    for k in 1..=frames {
        let t_s = SPAN_S.0 + k as f64 / fps;
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
    RateError {
        frames: compared,
        mean_rel_luminance: mean / n,
        p95_rel_luminance: p95 / n,
        flip: flip / flips.max(1) as f64,
    }
}
