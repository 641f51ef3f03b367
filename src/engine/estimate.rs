//! What a run will use, before anything large exists: the hair's own buffers, the sum of what
//! each pass reports for its buffers ([`RunSizes`] gives the counts), the export and the
//! simulation cache; and the work before the first frame. `crate::budget` checks it.

use super::animation::AnimationPass;
use super::config::EngineConfig;
use super::hair_map::{HairMapPass, map_geometry};
use super::interpolation::InterpolationPass;
use super::occluders::OccluderPass;
use super::raster::RasterPass;
use super::setup::fit_style_to_character;
use super::shading::ShadingPass;
use super::simulation::SimulationPass;
use super::sizes::{RunSizes, SizedBy};
use super::skin_texture::SkinTexturePass;
use crate::budget::{Budget, CacheUse, Estimate, MemoryPart, RunPlan, WorkPart, cost_ns, grouped};
use crate::hairstyle::Hairstyle;
use crate::motion::Motion;
use crate::output::FrameWriter;
use glam::Vec3;

/// Memory and work of running `style` on `motion` under `config` and `plan`. Pure arithmetic:
/// nothing is allocated beyond the returned lists.
pub fn estimate(
    style: &Hairstyle,
    motion: &Motion,
    config: &EngineConfig,
    plan: &RunPlan,
) -> Estimate {
    let style = &fit_style_to_character(style, motion);
    let by = SizedBy {
        scene: &config.scene,
        segment_pieces: config.interpolation.segment_pieces,
        strand_fraction: config.interpolation.strand_fraction,
        step_s: config.simulation.step_s(style),
        geom: map_geometry(style, &config.hair_map),
        settle_s: config.simulation.settle_s,
    };
    let sizes = RunSizes::of(style, motion, by, plan);
    let mut memory = hair_parts(&sizes);
    memory.extend(SimulationPass::estimate(&sizes));
    memory.extend(InterpolationPass::estimate(&sizes));
    memory.extend(HairMapPass::estimate(&config.hair_map, &sizes));
    memory.extend(OccluderPass::estimate(&sizes));
    memory.extend(SkinTexturePass::estimate(
        &config.skin_texture,
        &sizes,
        config.scene.draw_solids,
    ));
    memory.extend(ShadingPass::estimate(&config.shading, &sizes));
    memory.extend(RasterPass::estimate(&config.raster, &sizes));
    memory.extend(AnimationPass::estimate(motion, &sizes));
    if plan.export_png {
        memory.push(FrameWriter::estimate(sizes.width, sizes.height));
    }
    if plan.cache != CacheUse::None {
        memory.push(cache_part(&sizes, plan.cache));
    }
    let work = vec![
        SimulationPass::work_before_first_frame(&config.simulation, &sizes),
        InterpolationPass::work_before_first_frame(&sizes),
        first_frame(&sizes),
    ];
    Estimate { memory, work }
}

/// The hair itself: the guides at rest, the strand layout and the fibre's tables.
fn hair_parts(sizes: &RunSizes) -> Vec<MemoryPart> {
    let (particles, guides, strands) = (sizes.particles, sizes.guides, sizes.strands);
    let vec3 = size_of::<Vec3>() as u64;
    // Wisp, weights, curl phase, length.
    let strand_bytes = size_of::<u32>() + size_of::<[f32; 3]>() + 2 * size_of::<f32>();
    vec![
        MemoryPart {
            what: "guides at rest",
            product: format!(
                "{} guide particles × {vec3} B + {} guides × {} B",
                grouped(particles),
                grouped(guides),
                vec3 + 4
            ),
            bytes: particles * vec3 + guides * (vec3 + size_of::<f32>() as u64),
            set_by: "wisps.count × guides.links",
        },
        MemoryPart {
            what: "strand layout",
            product: format!("{} render strands × {strand_bytes} B", grouped(strands)),
            bytes: strands * strand_bytes as u64 + sizes.wisps * size_of::<[u32; 3]>() as u64,
            set_by: "wisps.count × wisps.strands_per_wisp",
        },
        MemoryPart {
            what: "fibre tables",
            product: "one fibre's scattering and dual-scattering tables".into(),
            // Measured peak heap of `Fiber::new` (tests' budget harness): 2.6 MB Marschner,
            // 2.0 MB Chiang, at the default table resolution; 4 MB holds either.
            bytes: 4_000_000,
            set_by: "fiber.model (the table sizes are fixed)",
        },
    ]
}

/// One cache record's bytes and, reading, its decoded positions; writing, the file buffer.
fn cache_part(sizes: &RunSizes, cache: CacheUse) -> MemoryPart {
    let particles = sizes.particles;
    let record = crate::cache::format::record_bytes(particles);
    let (second, what_else) = match cache {
        CacheUse::Read => (particles * size_of::<Vec3>() as u64, "its positions"),
        _ => (8 * 1024, "an 8 KiB file buffer"),
    };
    MemoryPart {
        what: "simulation cache",
        product: format!(
            "one record of {} guide particles × {} B, and {what_else}",
            grouped(particles),
            crate::cache::format::POSITION_BYTES
        ),
        bytes: record + second,
        set_by: "wisps.count × guides.links",
    }
}

/// The first frame: every render point through the passes, and every pixel.
fn first_frame(sizes: &RunSizes) -> WorkPart {
    WorkPart {
        what: "first frame",
        product: format!(
            "{} render points and {}×{} pixels",
            grouped(sizes.points),
            sizes.width,
            sizes.height
        ),
        cpu_s: (sizes.points as f64 * cost_ns::POINT + sizes.pixels as f64 * cost_ns::PIXEL) * 1e-9,
        set_by: "render strands × strands.points (× --segment-pieces), --width × --height",
    }
}

/// When the map resolution is automatic (`config.hair_map.map_res` is `None`) and the run is
/// over the memory budget, the largest resolution below the automatic one that brings it
/// within the budget: `Some((automatic N, chosen N))`. The map's worst case grows as N³ (its
/// per-column slot tables), so a scene whose automatic cells are very fine (a 1 cm head:
/// strands 0.1 mm apart at the scalp, N = 930) is better drawn with coarser cells than
/// refused. `None` when the resolution is given, the run already fits, or no resolution down
/// to 8 fits.
pub fn fit_map_resolution(
    style: &Hairstyle,
    motion: &Motion,
    config: &EngineConfig,
    plan: &RunPlan,
    budget: &Budget,
) -> Option<(u32, u32)> {
    if config.hair_map.map_res.is_some() {
        return None;
    }
    let fitted = fit_style_to_character(style, motion);
    let style = &fitted;
    let fits = |n: u32| {
        let mut c = config.clone();
        c.hair_map.map_res = Some(n);
        estimate(style, motion, &c, plan).memory_bytes() <= budget.memory_bytes
    };
    let auto = map_geometry(style, &config.hair_map).n;
    if estimate(style, motion, config, plan).memory_bytes() <= budget.memory_bytes || !fits(8) {
        return None;
    }
    // The estimate grows with N: binary search for the largest N that fits.
    let (mut lo, mut hi) = (8u32, auto);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if fits(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some((auto, lo))
}

#[cfg(test)]
mod tests;
