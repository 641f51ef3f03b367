//! One budget for what a run may allocate and compute, checked before anything large exists.
//!
//! A hairstyle's fields are each bounded (`hairstyle::MAX_*`), but their products are not: a
//! file at exactly the documented maxima passed validation, set up for 66 s and then aborted
//! on a 17.9 GB allocation in the map, and one with 100,000 wisps of 256 links ran for more
//! than five minutes at 7 GB. [`estimate`] therefore adds up, from the hairstyle, the motion,
//! the engine configuration and the run's plan (frames, warm-up, export):
//!
//! - **memory**: every buffer the [`Engine`](crate::engine::Engine) and the export hold, each
//!   as a product of item counts and per-item sizes taken from the real structs with
//!   `size_of` (the map, simulation and raster parts come from estimators next to their
//!   private structs: `MapGeometry::estimated_bytes`, `Simulator::estimated_bytes`,
//!   `Framebuffer::estimated_bytes`, `LineScratch::estimated_bytes`);
//! - **work before the first frame**: the settle and warm-up simulation and the first frame,
//!   in CPU-seconds from per-item costs measured on the development machine (one core of a
//!   shared 2-core VM; `docs/notes/hostile-inputs.md`). A frame costs less than this set-up, so the
//!   bound also holds for every later frame: no run sits for long without output.
//!
//! [`Estimate::check`] refuses an estimate over a [`Budget`], naming the largest part, the
//! product it comes from and the inputs that set it. To extend it (a groom, a scene), add one
//! [`MemoryPart`] or [`WorkPart`] per new buffer or stage in [`estimate`], with its count
//! times a `size_of`, as the simulation cache's record buffer ([`CacheUse`]) does.

use crate::engine::EngineConfig;
use crate::hairstyle::Hairstyle;
use crate::input::human_bytes;
use crate::map::MapGeometry;
use crate::motion::Motion;
use crate::raster::{Framebuffer, LineScratch, MeshScratch};
use crate::sim::Simulator;
use glam::Vec3;

/// Bytes per render point: position, tangent and colour, length, fibre share and width, and
/// the shading's order (key, vertex index) and colour in that order.
const RENDER_POINT_BYTES: usize =
    3 * size_of::<Vec3>() + 3 * size_of::<f32>() + 2 * size_of::<u32>() + size_of::<Vec3>();

/// Default memory budget: 4 GB.
pub const DEFAULT_MEMORY_BYTES: u64 = 4_000_000_000;
/// Default work budget before the first frame: 20 CPU-minutes (10 minutes on 2 cores).
pub const DEFAULT_WORK_CPU_S: f64 = 1200.0;

/// Measured single-core costs (release build, shared 2-core VM, `wisp --threads 1 render`
/// stage timings of the presets; see `docs/notes/hostile-inputs.md`). Estimates, good to about 2×.
mod cost_ns {
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
fn grouped(n: u64) -> String {
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

/// The map geometry the engine will choose.
pub fn map_geometry(style: &Hairstyle, config: &EngineConfig) -> MapGeometry {
    crate::engine::map_geometry(style, config)
}

/// When the map resolution is automatic (`config.map_res` is `None`) and the run is over the
/// memory budget, the largest resolution below the automatic one that brings it within the
/// budget: `Some((automatic N, chosen N))`. The map's worst case grows as N³ (its per-column
/// slot tables), so a scene whose automatic cells are very fine (a 1 cm head: strands 0.1 mm
/// apart at the scalp, N = 930) is better drawn with coarser cells than refused. `None` when
/// the resolution is given, the run already fits, or no resolution down to 8 fits.
pub fn fit_map_resolution(
    style: &Hairstyle,
    motion: &Motion,
    config: &EngineConfig,
    plan: &RunPlan,
    budget: &Budget,
) -> Option<(u32, u32)> {
    if config.map_res.is_some() {
        return None;
    }
    let fitted = crate::engine::fit_style_to_character(style, motion);
    let style = &fitted;
    let fits = |n: u32| {
        let c = EngineConfig {
            map_res: Some(n),
            ..config.clone()
        };
        estimate(style, motion, &c, plan).memory_bytes() <= budget.memory_bytes
    };
    let auto = map_geometry(style, config).n;
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

/// Memory and work of a run (see the module doc). Pure arithmetic: nothing is allocated
/// beyond the returned lists.
pub fn estimate(
    style: &Hairstyle,
    motion: &Motion,
    config: &EngineConfig,
    plan: &RunPlan,
) -> Estimate {
    let fitted = crate::engine::fit_style_to_character(style, motion);
    let style = &fitted;
    let wisps = style.wisps.count as u64;
    let guides = 3 * wisps;
    let points_per_guide = style.guides.links as u64 + 1;
    let particles = guides * points_per_guide;
    let strands = wisps * style.wisps.strands_per_wisp as u64;
    // Drawn points: the groom's, with each segment cut into the configured pieces.
    let points_per_strand = crate::interp::subdivided_points(
        style.strands.points as usize,
        config.segment_pieces as usize,
    ) as u64;
    let points = strands * points_per_strand;
    let segments = strands * points_per_strand.saturating_sub(1);
    let pixels = config.width as u64 * config.height as u64;
    let b = |n: usize| n as u64;

    // The longest render sample: the strand's length over its segments, plus the chord a
    // curl can add between two samples.
    let strand_length_m = style.max_length_m() as f64;
    let sample_len_m = strand_length_m / points_per_strand.saturating_sub(1).max(1) as f64
        + 2.0 * style.curl.radius_m as f64;
    let geom = map_geometry(style, config);
    let pieces = geom.pieces_for(sample_len_m as f32);
    let lights = config.lighting.lights.len().max(1) as u64;
    // Rows a segment covers: the camera frames about the hair's extent, lmax + hmax.
    let px_per_m = config.height as f64 / (style.max_length_m() + style.head_size_m()) as f64;

    let mut memory = vec![
        MemoryPart {
            what: "guides at rest",
            product: format!(
                "{} guide particles × {} B + {} guides × {} B",
                grouped(particles),
                size_of::<Vec3>(),
                grouped(guides),
                size_of::<Vec3>() + size_of::<f32>()
            ),
            bytes: particles * b(size_of::<Vec3>())
                + guides * b(size_of::<Vec3>() + size_of::<f32>()),
            set_by: "wisps.count × guides.links",
        },
        MemoryPart {
            what: "simulation",
            product: format!(
                "{} guides × {} particles",
                grouped(guides),
                points_per_guide
            ),
            bytes: Simulator::estimated_bytes(guides, points_per_guide),
            set_by: "wisps.count × guides.links",
        },
        MemoryPart {
            what: "strand layout",
            product: format!(
                "{} render strands × {} B",
                grouped(strands),
                size_of::<u32>() + size_of::<[f32; 3]>() + 2 * size_of::<f32>()
            ),
            // Wisp, weights, curl phase, length.
            bytes: strands * b(size_of::<u32>() + size_of::<[f32; 3]>() + 2 * size_of::<f32>())
                + wisps * b(size_of::<[u32; 3]>()),
            set_by: "wisps.count × wisps.strands_per_wisp",
        },
        MemoryPart {
            what: "render strands",
            product: format!(
                "{} render points × {} B (position, tangent, colour, length, fibre share, width; \
                 shading order and colour)",
                grouped(points),
                RENDER_POINT_BYTES
            ),
            bytes: points * b(RENDER_POINT_BYTES),
            set_by: "wisps.count × wisps.strands_per_wisp × strands.points (× --segment-pieces)",
        },
        MemoryPart {
            what: "map inputs kept for reuse",
            product: format!(
                "{} render points × {} B (position, tangent, length)",
                grouped(points),
                2 * size_of::<Vec3>() + size_of::<f32>()
            ),
            bytes: points * b(2 * size_of::<Vec3>() + size_of::<f32>()),
            set_by: "wisps.count × wisps.strands_per_wisp × strands.points (× --segment-pieces)",
        },
        MemoryPart {
            what: "light map",
            product: format!(
                "{} light(s) × {} render points × {pieces} fill piece(s) per segment in a {}³ map",
                lights,
                grouped(points),
                geom.n
            ),
            bytes: geom
                .estimated_bytes(points, pieces)
                .saturating_add(crate::map::OccluderGrid::estimated_bytes())
                .saturating_mul(lights),
            set_by: "wisps.count × wisps.strands_per_wisp × strands.points (× --segment-pieces), --map-res and the lights",
        },
        MemoryPart {
            what: "contact shadows",
            product: match config.contact.window_m(style.strands.fibers_per_strand) {
                Some(_) => format!(
                    "{} light(s) × {} render points, segments cut into parts of {:.2} mm",
                    lights,
                    grouped(points),
                    geom.column_m() * crate::map::CONTACT_BIN_COLUMNS * 1e3
                ),
                None => "off (fibre bundles, or --contact-mm 0)".to_string(),
            },
            bytes: match config.contact.window_m(style.strands.fibers_per_strand) {
                Some(_) => crate::map::contact::ContactShadows::estimated_bytes(
                    points,
                    sample_len_m as f32,
                    geom.column_m() * crate::map::CONTACT_BIN_COLUMNS,
                )
                .saturating_mul(lights),
                None => 0,
            },
            set_by: "one fibre per render strand: render points, --map-res and --contact-mm",
        },
        MemoryPart {
            what: "surface shadow texture",
            product: if config.draw_solids {
                format!(
                    "{} light(s) × at most {} map columns² × {} texels each, and a ribbon per render point",
                    lights,
                    geom.columns_per_axis(),
                    crate::map::surface::TEXELS_PER_COLUMN
                )
            } else {
                "off (no solids drawn)".to_string()
            },
            bytes: if config.draw_solids {
                crate::map::surface::SurfaceShadow::estimated_bytes(
                    geom.columns_per_axis() as u64,
                    points,
                    crate::map::surface::SurfaceShadow::ribbon_texel_bound(
                        geom.column_m(),
                        0.5 * style.strand_spacing_m(),
                        sample_len_m as f32,
                    ),
                )
                .saturating_mul(lights)
            } else {
                0
            },
            set_by: "the solids drawn, --map-res and render points",
        },
        MemoryPart {
            what: "framebuffer",
            product: format!("{}×{} pixels", config.width, config.height),
            bytes: Framebuffer::estimated_bytes(config.width, config.height),
            set_by: "--width × --height",
        },
        MemoryPart {
            what: "hair line raster",
            product: format!("{} segments on {} rows", grouped(segments), config.height),
            bytes: LineScratch::estimated_bytes(
                segments,
                config.width,
                config.height,
                sample_len_m * px_per_m,
                style.strands.fibers_per_strand.round() >= 2.0,
            ),
            set_by: "render strands × strands.points (× --segment-pieces), and --height",
        },
        MemoryPart {
            what: "fibre tables",
            product: "one fibre's scattering and dual-scattering tables".into(),
            // Measured peak heap of `Fiber::new` (tests/hostile_budget.rs harness): 2.6 MB
            // Marschner, 2.0 MB Chiang, at the default table resolution; 4 MB holds either.
            bytes: 4_000_000,
            set_by: "fiber.model (the table sizes are fixed)",
        },
        MemoryPart {
            what: "motion",
            product: format!("clip \"{}\" keyframes", motion.clip_name()),
            bytes: motion.held_bytes(),
            set_by: "the glTF clip",
        },
    ];
    if config.lighting.mode == crate::fiber::ShadingMode::Volume {
        // The hair spans at most its length either side of the head, and the head.
        let extent_m = 2.0 * style.max_length_m() + style.head_size_m();
        memory.push(MemoryPart {
            what: "light paths (--shading volume)",
            product: format!(
                "{lights} light(s) × {} render points, bins at most {} MB",
                grouped(points),
                config.volume.max_bins_bytes / 1_000_000
            ),
            bytes: crate::light_paths::LightPaths::estimated_bytes(
                points,
                sample_len_m as f32,
                extent_m,
                &config.volume,
            )
            .saturating_mul(lights),
            set_by: "render points, --volume-cell-mm and --volume-bins",
        });
    }
    if let Some(ch) = motion.character() {
        // The posed mesh is held by the motion's part; drawing it needs the raster's samples
        // and binned triangles, and the occluder grid its vertices in the light frame.
        let triangles = ch.triangles.len() as u64;
        memory.push(MemoryPart {
            what: "character raster",
            product: format!(
                "{}×{} pixels × 4 samples, {} triangles, {} vertices",
                config.width,
                config.height,
                grouped(triangles),
                grouped(ch.vertex_count() as u64)
            ),
            // The posed vertices, and their copy kept for the map's reuse check.
            bytes: MeshScratch::estimated_bytes(config.width, config.height, triangles)
                + b(2 * ch.vertex_count() * size_of::<Vec3>()),
            set_by: "--width × --height, and the glTF's meshes",
        });
    }
    if plan.export_png {
        // Three frame buffers in flight between the renderer and the writer, and the
        // encoder's copy of the one being written, counted at the widest format's 16 B a
        // pixel (linear RGBA f32 for EXR; 8-bit PNG needs 3, 16-bit PNG 8).
        memory.push(MemoryPart {
            what: "frame export",
            product: format!("4 × {}×{} pixels × 16 B", config.width, config.height),
            bytes: 4 * 16 * pixels,
            set_by: "--width × --height",
        });
    }

    if plan.cache != CacheUse::None {
        // One record's bytes and, reading, its decoded positions; writing, the file buffer.
        let record = crate::cache::format::record_bytes(particles);
        let (second, what_else) = match plan.cache {
            CacheUse::Read => (particles * b(size_of::<Vec3>()), "its positions"),
            _ => (b(8 * 1024), "an 8 KiB file buffer"),
        };
        memory.push(MemoryPart {
            what: "simulation cache",
            product: format!(
                "one record of {} guide particles × {} B, and {what_else}",
                grouped(particles),
                crate::cache::format::POSITION_BYTES
            ),
            bytes: record + second,
            set_by: "wisps.count × guides.links",
        });
    }

    let step_s = style.dynamics.step_s.max(1e-5) as f64;
    let before_first_s = if plan.cache == CacheUse::Read {
        0.0
    } else {
        (config.settle_s.max(0.0) + plan.warm_up_s.max(0.0)).min(1e15)
    };
    let frame_s = plan.frame_interval_s.clamp(0.0, 1e15);
    // The engine advances in 0.2 s slices before the first frame, interpolating each time.
    let slices = (before_first_s / 0.2).ceil();
    let (sim_product, sim_cpu_s) = if plan.cache == CacheUse::Read {
        (
            format!("{} guide particles read from the cache", grouped(particles)),
            0.0,
        )
    } else if config.simulate {
        let steps = ((before_first_s + frame_s) / step_s).ceil();
        (
            format!(
                "{} guide particles × {} steps of {:.4} s",
                grouped(particles),
                grouped(steps as u64),
                step_s
            ),
            particles as f64 * steps * cost_ns::PARTICLE_STEP * 1e-9,
        )
    } else {
        (
            format!(
                "{} guide particles × {} rigid updates",
                grouped(particles),
                slices + 1.0
            ),
            particles as f64 * (slices + 1.0) * cost_ns::POINT_INTERP * 1e-9,
        )
    };
    let work = vec![
        WorkPart {
            what: "settle and warm-up simulation",
            product: sim_product,
            cpu_s: sim_cpu_s,
            set_by: "wisps.count × guides.links, dynamics.step_s, --start-s",
        },
        WorkPart {
            what: "warm-up interpolation",
            product: format!(
                "{} render points × {slices} slices of 0.2 s",
                grouped(points)
            ),
            cpu_s: points as f64 * slices * cost_ns::POINT_INTERP * 1e-9,
            set_by: "render strands × strands.points (× --segment-pieces), --start-s",
        },
        WorkPart {
            what: "first frame",
            product: format!(
                "{} render points and {}×{} pixels",
                grouped(points),
                config.width,
                config.height
            ),
            cpu_s: (points as f64 * cost_ns::POINT + pixels as f64 * cost_ns::PIXEL) * 1e-9,
            set_by: "render strands × strands.points (× --segment-pieces), --width × --height",
        },
    ];
    Estimate { memory, work }
}

#[cfg(test)]
mod tests;
