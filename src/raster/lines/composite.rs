//! Compositing a band's pixels: each pixel's fragments front to back, each of its
//! [`SAMPLE_COUNT`] sub-samples with its own transmittance.
//!
//! What: a fragment of opacity α adds `colour · α · Σ T_k / 16` over the sub-samples k in its
//! mask and multiplies their T_k by 1 − α; what was in the pixel before (the background, the
//! solids) is seen through the mean T, and the coverage channel composites one minus it with
//! "over". A pixel stops where every T_k is under [`HIDDEN`] (1/1024: what is behind would add
//! under 1/1024 of itself), and then counts as fully covered.
//!
//! Why per sub-sample: one α over the whole pixel treats fibres as covering it independently,
//! so fibres side by side (a wisp's layer) let through as much of the darker hair behind as
//! crossing ones. Against a path tracer's first-hit fibres, one α a pixel read 0.93–0.96 of
//! the raster's own vertex values side- and front-lit, sub-samples 0.98 (ACCURACY.md §2), for
//! about 4 ms more on smooth and 12 on curly at 1280×720; dense is 6% faster, its pixels stop
//! early (BENCHMARKS.md).

use glam::{Vec3, Vec4};

use super::pixel_runs::{Layer, sort_run};
use super::samples::{HIDDEN, NIBBLE_LANES, SAMPLE_COUNT};

/// One band's pixels (whole rows of the framebuffer).
pub(super) struct Band<'a> {
    pub(super) color: &'a mut [Vec3],
    pub(super) depth: &'a [f32],
    pub(super) coverage: &'a mut [f32],
}

/// Composites every pixel's run of `sorted` (`starts[p]..starts[p + 1]`, far to near by
/// mid-point depth as `pixel_runs::sort_by_pixel` leaves them) into `band`: each run put in
/// depth order (`sort_run`, with `run_keys` and `key_tmp` its scratch), then composited
/// nearest first (by 1/depth descending; equal depths in reverse emission order).
pub(super) fn composite(
    sorted: &mut [Layer],
    starts: &[u32],
    run_keys: &mut Vec<u64>,
    key_tmp: &mut Vec<u64>,
    band: Band,
) {
    let pixels = band.color.len();
    for p in 0..pixels {
        let (a, b) = (starts[p] as usize, starts[p + 1] as usize);
        let Some(run) = sorted.get_mut(a..b) else {
            continue;
        };
        if run.is_empty() {
            continue;
        }
        sort_run(run, run_keys, key_tmp);
        let (acc, t_mean) = front_to_back(run);
        band.color[p] = acc + band.color[p] * t_mean;
        band.coverage[p] = 1.0 - (1.0 - band.coverage[p]) * t_mean;
    }
}

/// One pixel's `run` (in depth order, far first) composited front to back, each sub-sample
/// with its own transmittance, four lanes at a time: the colour it adds, and the mean
/// transmittance what is behind it is seen through (0 once every sub-sample is hidden).
#[inline(always)]
fn front_to_back(run: &[Layer]) -> (Vec3, f32) {
    let mut trans = [Vec4::ONE; 4];
    let mut acc = Vec3::ZERO;
    for f in run.iter().rev() {
        let mut seen = Vec4::ZERO;
        let alpha = f.alpha;
        let a = Vec4::splat(alpha);
        for (g, t) in trans.iter_mut().enumerate() {
            let m = NIBBLE_LANES[usize::from((f.mask >> (4 * g)) & 15)];
            seen += m * *t;
            *t -= *t * (m * a);
        }
        acc += f.color * (alpha * seen.element_sum() * (1.0 / SAMPLE_COUNT as f32));
        // Stop where every sub-sample is hidden: what is behind (farther hair, and the
        // background) would add under 1/1024 of itself, and the pixel counts as covered.
        let most = trans[0]
            .max(trans[1])
            .max(trans[2].max(trans[3]))
            .max_element();
        if most < HIDDEN {
            trans = [Vec4::ZERO; 4];
            break;
        }
    }
    let t_mean =
        (trans[0] + trans[1] + trans[2] + trans[3]).element_sum() * (1.0 / SAMPLE_COUNT as f32);
    (acc, t_mean)
}
