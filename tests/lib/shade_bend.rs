//! Bent strands (`shade::bend`): the raster colours a segment linearly between its vertices.
//! Along a polyline of straight runs joined by corners, with equal segments, the drawn
//! integral of the colour must be the sum of each straight segment shaded along its own
//! direction: a corner's colour is the mean of its two segments', a vertex inside a run is
//! shaded along the run (its central tangent is the run's direction), so every segment's mean
//! is a sum of quarters and halves of its own and its neighbours' colours that adds up, over
//! the strand, to one of each.

use glam::{Quat, Vec3};
use proptest::prelude::*;
use wisp::fiber::{Fiber, FiberModel, FiberParams, ShadingMode};
use wisp::light::Light;
use wisp::shade::{Lighting, VertexColors, VertexGeometry, shade_vertices, shade_vertices_with};

const SEGMENT_M: f32 = 0.005;

/// A strand from the origin whose direction turns by `turns[k]` (degrees, about an axis that
/// itself rotates by `twist` degrees a step) at each inner vertex.
fn polyline(turns: &[f32], twist: f32) -> Vec<Vec3> {
    let mut d = Vec3::NEG_Y;
    let mut axis = Vec3::Z;
    let mut p = vec![Vec3::ZERO];
    for (k, &deg) in std::iter::once(&0.0).chain(turns).enumerate() {
        if k > 0 {
            d = (Quat::from_axis_angle(axis, deg.to_radians()) * d).normalize();
            axis = Quat::from_axis_angle(d, twist.to_radians()) * axis;
            axis = (axis - d * axis.dot(d)).normalize();
        }
        p.push(p[k] + d * SEGMENT_M);
    }
    p
}

/// Turns of straight runs joined by corners: each (corner in degrees, segments after it),
/// after a first run of two segments.
fn runs(corners: &[(f32, usize)]) -> Vec<f32> {
    let mut turns = vec![0.0];
    for &(deg, after) in corners {
        turns.push(deg);
        turns.extend(std::iter::repeat_n(0.0, after - 1));
    }
    turns
}

/// Central-difference tangents, one-sided at the ends (as `interp`).
fn tangents(p: &[Vec3]) -> Vec<Vec3> {
    (0..p.len())
        .map(|i| (p[(i + 1).min(p.len() - 1)] - p[i.saturating_sub(1)]).normalize())
        .collect()
}

/// One directional light of unit irradiance and a shader, with no ambient.
struct LightSet {
    lights: Vec<Light>,
    mode: ShadingMode,
}

impl LightSet {
    fn get(&self) -> Lighting<'_> {
        Lighting {
            lights: &self.lights,
            ambient: Vec3::ZERO,
            mode: self.mode,
        }
    }
}

fn lighting(mode: ShadingMode, toward_light: Vec3) -> LightSet {
    LightSet {
        lights: vec![Light::directional(-toward_light, Vec3::ONE).expect("a valid light")],
        mode,
    }
}

/// Σ over segments of the mean of its two vertex colours: the raster's integral along the
/// strand, in units of one segment.
fn drawn(colors: &[Vec3]) -> Vec3 {
    colors.windows(2).map(|w| 0.5 * (w[0] + w[1])).sum()
}

struct Case {
    fiber: Fiber,
    lighting: LightSet,
    eye: Vec3,
    points: Vec<Vec3>,
}

impl Case {
    fn shade(&self) -> Vec<Vec3> {
        let mut colors = VertexColors::default();
        shade_vertices(
            &self.fiber,
            wisp::map::Shadows::hair_only(&[]),
            &self.lighting.get(),
            self.eye,
            VertexGeometry {
                positions: &self.points,
                tangents: &tangents(&self.points),
                points_per_strand: self.points.len(),
                segment_pieces: 1,
            },
            None,
            &mut colors,
        );
        colors.colors().to_vec()
    }

    /// Unshadowed colours of `points` with `tangents`, strands of `points_per_strand`.
    fn unshadowed(
        &self,
        points: &[Vec3],
        tangents: &[Vec3],
        points_per_strand: usize,
    ) -> Vec<Vec3> {
        let mut c = Vec::new();
        shade_vertices_with(
            &self.fiber,
            &self.lighting.get(),
            self.eye,
            VertexGeometry {
                positions: points,
                tangents,
                points_per_strand,
                segment_pieces: 1,
            },
            |_, _, _| wisp::fiber::LightAtPoint::UNSHADOWED,
            &mut c,
        );
        c
    }

    /// Every segment shaded as a straight strand of its own two points.
    fn segments_alone(&self) -> Vec3 {
        self.points
            .windows(2)
            .map(|w| {
                let d = (w[1] - w[0]).normalize();
                drawn(&self.unshadowed(w, &[d, d], 2))
            })
            .sum()
    }

    /// The same vertices shaded once each at their tangent (before bent strands): each point
    /// as a strand of its own.
    fn at_tangents(&self) -> Vec3 {
        drawn(&self.unshadowed(&self.points, &tangents(&self.points), 1))
    }
}

fn fiber(model: FiberModel) -> Fiber {
    Fiber::new(&FiberParams {
        model,
        sigma_a: [0.4, 0.7, 1.3],
        ..Default::default()
    })
}

fn rel_diff(a: Vec3, b: Vec3) -> f32 {
    (a - b).abs().max_element() / a.abs().max(b.abs()).max_element().max(1e-12)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn a_strand_with_corners_draws_the_sum_of_its_segments(
        corners in prop::collection::vec((9.0f32..150.0, 2usize..5), 1..6),
        twist in -60.0f32..60.0,
        light_az in 0.0f32..std::f32::consts::TAU,
        light_el in -1.2f32..1.2,
        chiang in any::<bool>(),
        dual in any::<bool>(),
    ) {
        let model = if chiang { FiberModel::Chiang } else { FiberModel::Marschner };
        let mode = if dual { ShadingMode::DualScattering } else { ShadingMode::SingleScattering };
        let toward_light = Vec3::new(
            light_el.cos() * light_az.cos(),
            light_el.sin(),
            light_el.cos() * light_az.sin(),
        );
        // The eye far away (1 km), so every vertex sees it in the same direction to 1e-7.
        let case = Case {
            fiber: fiber(model),
            lighting: lighting(mode, toward_light),
            eye: Vec3::new(0.0, 0.0, 1000.0),
            points: polyline(&runs(&corners), twist),
        };
        let colors = case.shade();
        prop_assert!(colors.iter().all(|c| c.is_finite() && c.min_element() >= 0.0));
        let (got, want) = (drawn(&colors), case.segments_alone());
        prop_assert!(
            rel_diff(got, want) < 2e-4,
            "drawn {got} against the segments' own {want}"
        );
    }
}

/// The test above can fail: on a strand that turns 70° and then 30° (the dense scene's roots)
/// in a side light, shading each vertex once at its tangent draws a different integral (9.5%
/// from the segments' own), and the corners' shading does not.
#[test]
fn one_evaluation_per_vertex_misses_the_segments_own_highlights() {
    let case = Case {
        fiber: fiber(FiberModel::Chiang),
        lighting: lighting(
            ShadingMode::SingleScattering,
            Vec3::new(1.0, 0.2, 0.6).normalize(),
        ),
        eye: Vec3::new(0.0, 0.0, 1000.0),
        points: polyline(&[0.0, 70.0, 30.0, 0.0, 0.0, 0.0], 0.0),
    };
    let want = case.segments_alone();
    let bent = rel_diff(drawn(&case.shade()), want);
    let once = rel_diff(case.at_tangents(), want);
    assert!(bent < 2e-4, "bent-strand shading {bent}");
    assert!(once > 0.02, "one evaluation per vertex {once}");
}
