//! The interpolation pass: the render strands of every wisp from its three guides (Bertails
//! 2005 §3.1 and §4.1: barycentric blends of the guides, Catmull-Rom smoothing, curls; an
//! imported groom's strands keep their own offsets), kept out of the head and body
//! (`crate::interp`). Its strands are what the map fills, the shader lights and the raster
//! draws.

use super::setup::{colliders_of, write_colliders};
use super::sizes::RunSizes;
use crate::budget::{MemoryPart, WorkPart, cost_ns, grouped};
use crate::hairstyle::{CurlSpec, GuideSet, StrandLayout};
use crate::interp::{StrandGeometry, interpolate_among};
use crate::motion::Pose;
use crate::sim::Colliders;
use glam::Vec3;

/// How the render strands are made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InterpolationConfig {
    /// Each segment of the groom's render strands is cut into this many straight pieces (1:
    /// as the groom says; default 1): the drawn geometry is the same, but the map, the contact
    /// shadows and the shader read the hair this many times as often along it
    /// ([`crate::interp::subdivide_in_place`]), at about as many times their cost.
    pub segment_pieces: u32,
    /// The share of each wisp's render strands made, in (0, 1] (default 1): the kept strands
    /// stand for the fibres of all ([`crate::hairstyle::thin_strands`]), a level of detail
    /// for hair whose strands are narrower than a pixel. Applied when the engine is built.
    pub strand_fraction: f32,
}

impl Default for InterpolationConfig {
    fn default() -> Self {
        Self {
            segment_pieces: 1,
            strand_fraction: 1.0,
        }
    }
}

/// The hair a frame's render strands are made from: the guide set and strand layout, the
/// curls, and the guide particles' positions now.
#[derive(Clone, Copy)]
pub struct GuideHair<'a> {
    pub guides: &'a GuideSet,
    pub layout: &'a StrandLayout,
    pub curl: &'a CurlSpec,
    pub positions: &'a [Vec3],
}

/// The render strands of the last frame and the colliders they were kept out of.
pub struct InterpolationPass {
    pub config: InterpolationConfig,
    strands: StrandGeometry,
    /// The head and body colliders of the frame's pose (reused).
    colliders: Colliders,
}

impl InterpolationPass {
    pub fn new(config: InterpolationConfig, pose: &Pose, head_radii_m: Vec3) -> Self {
        Self {
            config,
            strands: StrandGeometry::default(),
            colliders: colliders_of(pose, head_radii_m),
        }
    }

    /// The render strands of `hair`, kept out of the colliders of `pose`.
    pub fn run(&mut self, hair: GuideHair, pose: &Pose, head_radii_m: Vec3) {
        write_colliders(pose, head_radii_m, &mut self.colliders);
        interpolate_among(
            hair.guides,
            hair.layout,
            hair.curl,
            hair.positions,
            Some(&self.colliders),
            self.config.segment_pieces as usize,
            &mut self.strands,
        );
    }

    /// The render strands of the last frame.
    pub fn strands(&self) -> &StrandGeometry {
        &self.strands
    }

    /// The colliders of the last frame's pose (head ellipsoid, body spheres and capsules).
    pub fn colliders(&self) -> &Colliders {
        &self.colliders
    }

    /// The render strands' points: position, tangent, length and fibre share.
    pub fn estimate(sizes: &RunSizes) -> Vec<MemoryPart> {
        vec![MemoryPart {
            what: "render strands",
            product: format!(
                "{} render points × {} B (position, tangent, length, fibre share)",
                grouped(sizes.points),
                POINT_BYTES
            ),
            bytes: sizes.points * POINT_BYTES as u64,
            set_by: "wisps.count × wisps.strands_per_wisp × strands.points (× --segment-pieces)",
        }]
    }

    /// The interpolation at the end of the settle and warm-up (`Engine::run_up_to`), none when
    /// nothing is simulated before the first frame.
    pub fn work_before_first_frame(sizes: &RunSizes) -> WorkPart {
        let times = sizes.warm_up_slices.min(1.0);
        WorkPart {
            what: "warm-up interpolation",
            product: format!("{} render points × {times}", grouped(sizes.points)),
            cpu_s: sizes.points as f64 * times * cost_ns::POINT_INTERP * 1e-9,
            set_by: "render strands × strands.points (× --segment-pieces)",
        }
    }
}

/// Bytes per render point: position and tangent, length and fibre share.
const POINT_BYTES: usize = 2 * size_of::<Vec3>() + 2 * size_of::<f32>();
