//! The shading pass: the colour of every render-strand point the raster will draw, from each
//! light's shadows (`crate::shade`: a filtered map lookup into the fibre shader), and with the
//! light-path shader the multiply scattered light of paths traced through the hair
//! (`crate::light_paths`), gathered at the same points.

use super::sizes::RunSizes;
use crate::budget::{MemoryPart, grouped};
use crate::fiber::{Fiber, FiberParams, ShadingMode};
use crate::interp::StrandGeometry;
use crate::light_paths::{
    AngularResponse, Directions, LightPathParams, LightPaths, Solids, StrandPoints, pick_of,
};
use crate::map::Shadows;
use crate::scene::Scene;
use crate::shade::{Lighting, VertexColors, VertexGeometry, shade_vertices};
use crate::sim::Colliders;
use crate::sim::collide::CollisionScene;
use glam::{Affine3A, Vec3};
use rayon::prelude::*;
use std::sync::Arc;

/// How the hair is shaded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadingConfig {
    /// The fibre shader (default dual scattering).
    pub mode: ShadingMode,
    /// The light paths of [`ShadingMode::Volume`] (unused by the other shaders).
    pub light_paths: LightPathParams,
    /// The light paths are built once per this many seconds of motion, in slots aligned to
    /// the motion's clock, and read by the slot's later frames where the head was at the
    /// build (`paths_rate`); 0: every frame.
    pub paths_interval_s: f64,
}

impl Default for ShadingConfig {
    fn default() -> Self {
        Self {
            mode: ShadingMode::DualScattering,
            light_paths: LightPathParams::default(),
            paths_interval_s: 0.0,
        }
    }
}

/// What a frame's hair is shaded from, besides the shadows.
#[derive(Clone, Copy)]
pub struct ShadingInput<'a> {
    pub fiber: &'a Fiber,
    pub fibers_per_strand: f32,
    pub scene: &'a Scene,
    pub strands: &'a StrandGeometry,
    /// The eye, world metres.
    pub eye: Vec3,
    /// Per point, whether the raster will draw it (`None`: shade every point).
    pub seen: Option<&'a [bool]>,
}

/// What the light paths are built from: the hair, the solids and the lights at one time.
#[derive(Clone, Copy)]
pub struct PathsInput<'a> {
    pub fiber: &'a Fiber,
    pub fibers_per_strand: f32,
    pub scene: &'a Scene,
    pub strands: &'a StrandGeometry,
    /// The head and body colliders, which stop the light paths where solids are drawn.
    pub colliders: &'a Colliders,
}

/// The points' colours and the shader's reusable buffers.
#[derive(Default)]
pub struct ShadingPass {
    pub config: ShadingConfig,
    colors: VertexColors,
    /// The fibre's moment integrals for [`Directions::Strongest`], with the fibre they are
    /// of: made once per fibre (about 1.4 M BCSDF evaluations), not per frame.
    response: Option<(FiberParams, Arc<AngularResponse>)>,
    /// Each light's light paths as last built ([`ShadingPass::build_light_paths`]), in the
    /// order of the scene's lights (`None`: no hair, or the light cannot reach it).
    paths: Vec<Option<LightPaths>>,
    /// The render-strand points the light paths were built from, indexed as now: a frame
    /// lit by an earlier build gathers each point where it was then (`engine::paths_rate`).
    positions_then: Vec<Vec3>,
}

impl ShadingConfig {
    /// Whether the light paths are built on some frames only: the light-path shader with a
    /// rate (`paths_interval_s` > 0).
    pub fn paths_at_rate(&self) -> bool {
        self.mode == ShadingMode::Volume && self.paths_interval_s > 0.0
    }
}

impl ShadingPass {
    pub fn new(config: ShadingConfig) -> Self {
        Self {
            config,
            ..Self::default()
        }
    }

    /// Shades the points of `input` (all, or those it says the raster will draw; the rest
    /// black) through `shadows`, plus, with the light-path shader, each light's multiply
    /// scattered light from the paths last built, read through `paths_back` (world now →
    /// world at their build) when they were built for an earlier frame.
    pub fn run(&mut self, shadows: Shadows, input: &ShadingInput, paths_back: Option<Affine3A>) {
        let strands = input.strands;
        shade_vertices(
            input.fiber,
            shadows,
            &self.lighting(input.scene),
            input.eye,
            VertexGeometry {
                positions: &strands.positions,
                tangents: &strands.tangents,
                points_per_strand: strands.points_per_strand,
                segment_pieces: strands.segment_pieces,
            },
            input.seen,
            &mut self.colors,
        );
        if self.config.mode == ShadingMode::Volume {
            self.gather_light_paths(input, paths_back);
        }
    }

    /// The scene's lights and ambient with this pass's shader.
    pub fn lighting<'a>(&self, scene: &'a Scene) -> Lighting<'a> {
        Lighting {
            lights: &scene.lights,
            ambient: scene.ambient,
            mode: self.config.mode,
        }
    }

    /// `fiber`'s moment integrals, made on first use and again when the fibre changes.
    fn response_of(&mut self, fiber: &Fiber) -> Arc<AngularResponse> {
        match &self.response {
            Some((params, r)) if params == fiber.params() => r.clone(),
            _ => {
                let r = Arc::new(AngularResponse::new(fiber));
                self.response = Some((fiber.params().clone(), r.clone()));
                r
            }
        }
    }

    /// Traces each light's paths through the hair of `input` and keeps them for the frames
    /// that gather them.
    pub fn build_light_paths(&mut self, input: &PathsInput) {
        let strands = input.strands;
        // The solids stop light where they are drawn (the head and body's colliders stand for
        // them, a character's capsules for its mesh), prepared once (the head's inverse).
        let colliders = CollisionScene::new(input.colliders);
        let bounds = input.colliders.solid_bounds_m();
        let solids = input.scene.draw_solids;
        let points = StrandPoints {
            positions: &strands.positions,
            tangents: &strands.tangents,
            lengths_m: &strands.lengths_m,
            fibers_per_strand: input.fibers_per_strand,
        };
        self.positions_then.clear();
        self.positions_then.extend_from_slice(&strands.positions);
        self.paths.clear();
        for light in &input.scene.lights {
            self.paths.push(LightPaths::build(
                input.fiber,
                &points,
                light,
                &self.config.light_paths,
                solids.then_some(Solids {
                    depth_m: |p: Vec3| colliders.penetration_m(p.into()),
                    within_m: &bounds,
                }),
            ));
        }
    }

    /// Adds each light's multiply scattered light, from the light paths last built, to the
    /// points shaded. With `back` (world now → world at an earlier build), each point is read
    /// where it was at the build, its tangent and view carried back with the head.
    fn gather_light_paths(&mut self, input: &ShadingInput, back: Option<Affine3A>) {
        let strands = input.strands;
        let response = matches!(self.config.light_paths.directions, Directions::Strongest(_))
            .then(|| self.response_of(input.fiber));
        let then = &self.positions_then;
        for paths in self.paths.iter().flatten() {
            self.colors
                .colors_mut()
                .par_iter_mut()
                .enumerate()
                .with_min_len(256)
                .for_each(|(i, c)| {
                    if input
                        .seen
                        .is_some_and(|s| !s.get(i).copied().unwrap_or(false))
                    {
                        return;
                    }
                    let (Some(&p), Some(&u)) = (strands.positions.get(i), strands.tangents.get(i))
                    else {
                        return;
                    };
                    let wo = (input.eye - p).normalize_or_zero();
                    if wo == Vec3::ZERO {
                        return;
                    }
                    let (p, u, wo) = match back {
                        Some(b) => (
                            then.get(i)
                                .copied()
                                .unwrap_or_else(|| b.transform_point3(p)),
                            b.transform_vector3(u),
                            b.transform_vector3(wo),
                        ),
                        None => (p, u, wo),
                    };
                    *c += paths.indirect(input.fiber, response.as_deref(), p, u, wo, pick_of(i));
                });
        }
    }

    /// The colours of the last run, indexed like the render strands' points (black where
    /// not shaded).
    pub fn colors(&self) -> &[Vec3] {
        self.colors.colors()
    }

    /// The colours and the shader's ordering buffers, and the light paths when they are on.
    pub fn estimate(config: &ShadingConfig, sizes: &RunSizes) -> Vec<MemoryPart> {
        let points = sizes.points;
        let mut parts = vec![MemoryPart {
            what: "shading",
            product: format!(
                "{} render points × {} B (colour; the shading's order and colour in that order)",
                grouped(points),
                POINT_BYTES
            ),
            bytes: points * POINT_BYTES as u64,
            set_by: "wisps.count × wisps.strands_per_wisp × strands.points (× --segment-pieces)",
        }];
        if config.mode == ShadingMode::Volume {
            // The hair spans at most its length either side of the head, and the head.
            let extent_m = 2.0 * sizes.max_length_m + sizes.head_size_m;
            parts.push(MemoryPart {
                what: "light paths (--shading volume)",
                product: format!(
                    "{} light(s) × {} render points, bins at most {} MB; the points at the build",
                    sizes.lights,
                    grouped(points),
                    config.light_paths.max_bins_bytes / 1_000_000
                ),
                bytes: LightPaths::estimated_bytes(
                    points,
                    sizes.sample_len_m as f32,
                    extent_m,
                    &config.light_paths,
                )
                .saturating_mul(sizes.lights)
                .saturating_add(points * size_of::<Vec3>() as u64),
                set_by: "render points, --volume-cell-mm and --volume-bins",
            });
        }
        parts
    }
}

/// Bytes per render point: its colour, and the shading's key, index and colour in map order.
const POINT_BYTES: usize = 2 * size_of::<Vec3>() + 2 * size_of::<u32>();
