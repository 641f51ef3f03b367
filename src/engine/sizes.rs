//! The counts a run's memory and work follow from, computed from the hairstyle, the motion,
//! the configuration and the run's plan before anything large exists: what each pass's
//! estimate multiplies its per-item sizes by.

use crate::budget::{CacheUse, RunPlan};
use crate::hairstyle::{Hairstyle, kept_strands};
use crate::map::MapGeometry;
use crate::motion::Motion;
use crate::scene::Scene;

/// The sizes of a run (see the module doc).
#[derive(Clone, Copy, Debug)]
pub struct RunSizes {
    pub wisps: u64,
    pub guides: u64,
    pub points_per_guide: u64,
    /// Guide particles: guides × points per guide.
    pub particles: u64,
    /// Render strands.
    pub strands: u64,
    /// Drawn points per render strand: the groom's, each segment cut into the configured
    /// pieces.
    pub points_per_strand: u64,
    /// Render points and segments.
    pub points: u64,
    pub segments: u64,
    /// Image size, pixels.
    pub width: u32,
    pub height: u32,
    pub pixels: u64,
    /// Lights (at least one map is built).
    pub lights: u64,
    /// The longest render sample: the strand's length over its segments, plus the chord a
    /// curl can add between two samples, metres.
    pub sample_len_m: f64,
    /// Pixels per metre of hair on screen: the camera frames about the hair's extent,
    /// lmax + hmax.
    pub px_per_m: f64,
    /// The map's geometry, and the fill pieces of the longest sample.
    pub geom: MapGeometry,
    pub pieces: u64,
    pub fibers_per_strand: f32,
    pub strand_spacing_m: f32,
    pub max_length_m: f32,
    pub head_size_m: f32,
    /// The character's vertices and triangles (0 without one).
    pub character_vertices: u64,
    pub character_triangles: u64,
    /// The guides are read from a cache: nothing is simulated.
    pub from_cache: bool,
    /// Simulated seconds before the first frame (settle and warm-up), between frames, and the
    /// simulation step.
    pub before_first_s: f64,
    pub frame_s: f64,
    pub step_s: f64,
    /// Slices of 0.2 s the engine advances in before the first frame.
    pub warm_up_slices: f64,
}

/// What of a run's configuration the sizes follow from: the scene, each segment's pieces, the
/// strands' level of detail, the simulation step, the map's geometry and the settle.
#[derive(Clone, Copy, Debug)]
pub struct SizedBy<'a> {
    pub scene: &'a Scene,
    pub segment_pieces: u32,
    /// The share of each wisp's render strands made (`InterpolationConfig::strand_fraction`).
    pub strand_fraction: f32,
    /// The simulation step, seconds.
    pub step_s: f32,
    pub geom: MapGeometry,
    pub settle_s: f64,
}

impl RunSizes {
    /// The sizes of running `style` (as fitted to `motion`'s character) on `motion` as `by`
    /// says, under `plan`.
    pub fn of(style: &Hairstyle, motion: &Motion, by: SizedBy, plan: &RunPlan) -> Self {
        let wisps = style.wisps.count as u64;
        let guides = 3 * wisps;
        let points_per_guide = style.guides.links as u64 + 1;
        let kept = kept_strands(style.wisps.strands_per_wisp, by.strand_fraction);
        let strands = wisps * kept as u64;
        let points_per_strand = crate::interp::subdivided_points(
            style.strands.points as usize,
            by.segment_pieces as usize,
        ) as u64;
        let (width, height) = (by.scene.width, by.scene.height);
        let sample_len_m = style.max_length_m() as f64
            / points_per_strand.saturating_sub(1).max(1) as f64
            + 2.0 * style.curl.radius_m as f64;
        let geom = by.geom;
        let from_cache = plan.cache == CacheUse::Read;
        let before_first_s = if from_cache {
            0.0
        } else {
            (by.settle_s.max(0.0) + plan.warm_up_s.max(0.0)).min(1e15)
        };
        let character = motion.character();
        Self {
            wisps,
            guides,
            points_per_guide,
            particles: guides * points_per_guide,
            strands,
            points_per_strand,
            points: strands * points_per_strand,
            segments: strands * points_per_strand.saturating_sub(1),
            width,
            height,
            pixels: width as u64 * height as u64,
            lights: by.scene.lights.len().max(1) as u64,
            sample_len_m,
            px_per_m: height as f64 / (style.max_length_m() + style.head_size_m()) as f64,
            geom,
            pieces: geom.pieces_for(sample_len_m as f32),
            fibers_per_strand: style.strands.fibers_per_strand,
            strand_spacing_m: style.strand_spacing_m(),
            max_length_m: style.max_length_m(),
            head_size_m: style.head_size_m(),
            character_vertices: character.map_or(0, |c| c.vertex_count() as u64),
            character_triangles: character.map_or(0, |c| c.triangles.len() as u64),
            from_cache,
            before_first_s,
            frame_s: plan.frame_interval_s.clamp(0.0, 1e15),
            step_s: by.step_s.max(1e-5) as f64,
            warm_up_slices: (before_first_s / 0.2).ceil(),
        }
    }
}
