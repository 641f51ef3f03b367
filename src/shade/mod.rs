//! Shading: the colour of every render-strand vertex and of the head's skin.
//!
//! Per vertex: a filtered map lookup (Bertails 2005 §3.3) gives what the light went through
//! to get there (direct fraction, T_f, σ̄f²); the fibre shader turns that into outgoing
//! radiance toward the camera (Zinke 2008 Figure 5, or the comparison modes). A constant
//! ambient term stands for the sky (Bertails' Φ_Ambient), coloured by one pass through the
//! fibre so that it reads as the hair's own colour.
//!
//! Work is split over vertices in fixed-size chunks; each vertex is independent, so the
//! result does not depend on the thread count.

mod bend;

use crate::color::{RADIANCE_MAX, saturate_radiance};
use crate::fiber::{Fiber, LightAtPoint, ShadingMode};
use crate::light::Light;
use crate::map::Shadows;
#[cfg(doc)]
use crate::map::{LightMap, Shadow};
use bend::{BendTest, Directions};
use glam::Vec3;
use rayon::prelude::*;

/// Lighting of a frame: the lights (each with its own map, in this order), an ambient term and
/// the fibre shader.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lighting<'a> {
    /// The lights, validated ([`Light`]).
    pub lights: &'a [Light],
    /// Ambient (sky) radiance, linear RGB.
    pub ambient: Vec3,
    /// Fibre shader.
    pub mode: ShadingMode,
}

/// Colour of light after one pass through a fibre at normal incidence: the chord is two radii,
/// so exp(−2σa) with σa per unit radius. Used to tint the ambient term only.
pub fn fiber_tint(fiber: &Fiber) -> Vec3 {
    (-2.0 * Vec3::from(fiber.params().sigma_a)).exp()
}

/// The render strands' vertices as the shader reads them.
#[derive(Clone, Copy, Debug)]
pub struct VertexGeometry<'a> {
    /// Vertex positions, metres; strand after strand.
    pub positions: &'a [Vec3],
    /// Unit tangents (central differences), one per position.
    pub tangents: &'a [Vec3],
    /// Points per render strand: vertex i's neighbours along its strand are i ± 1, except at
    /// the strand's ends (i mod this = 0 or this − 1).
    pub points_per_strand: usize,
    /// Each segment of the groom cut into this many pieces (`interp::subdivide`; 0 or 1:
    /// none): the added points lie on straight segments, so only every piece-th point can be
    /// a corner, and its neighbours' turns are read that many points away.
    pub segment_pieces: usize,
}

/// The colours [`shade_vertices`] makes, and its reusable buffers: the vertices in map order
/// and their colours in that order. Allocation-free once warmed up.
#[derive(Clone, Debug, Default)]
pub struct VertexColors {
    /// Per vertex, its linear RGB colour (black where not shaded).
    colors: Vec<Vec3>,
    /// The vertices' keys (map columns).
    keys: Vec<u32>,
    /// The vertex indices in key order (ties by index).
    order: Vec<u32>,
    /// Per key (map column, and one for points off the map): its count, then its cursor.
    counts: Vec<u32>,
    /// The colours in key order.
    shaded: Vec<Vec3>,
}

impl VertexColors {
    /// The colours of the last [`shade_vertices`], indexed like its vertices.
    pub fn colors(&self) -> &[Vec3] {
        &self.colors
    }

    /// Mutable colours (the light paths add their light to the shaded vertices).
    pub fn colors_mut(&mut self) -> &mut [Vec3] {
        &mut self.colors
    }

    /// Puts the indices of the first `n` vertices that `wanted` keeps in `order`, by the map
    /// column `key(i)` they read (`columns` buckets, and one for points off the map), ties by
    /// index: a counting sort, O(vertices + columns).
    fn order_by_column(
        &mut self,
        n: usize,
        columns: usize,
        key: impl Fn(usize) -> u32 + Sync,
        wanted: impl Fn(usize) -> bool + Sync,
    ) {
        let keys = &mut self.keys;
        keys.clear();
        keys.par_extend(
            (0..n)
                .into_par_iter()
                .map(|i| if wanted(i) { key(i) } else { u32::MAX }),
        );
        let bucket = |key: u32| (key as usize).min(columns);
        let counts = &mut self.counts;
        counts.clear();
        counts.resize(columns + 1, 0);
        for (i, &key) in keys.iter().enumerate() {
            if wanted(i) {
                counts[bucket(key)] += 1;
            }
        }
        let mut at = 0u32;
        for c in counts.iter_mut() {
            (*c, at) = (at, at + *c);
        }
        let order = &mut self.order;
        order.clear();
        order.resize(at as usize, 0);
        for (i, &key) in keys.iter().enumerate() {
            if !wanted(i) {
                continue;
            }
            let slot = &mut counts[bucket(key)];
            order[*slot as usize] = i as u32;
            *slot += 1;
        }
    }

    /// The colours shaded in `order`, put back in vertex order (`n` vertices, the others
    /// black).
    fn scatter_back(&mut self, n: usize) {
        self.colors.clear();
        self.colors.resize(n, Vec3::ZERO);
        for (c, &i) in self.shaded.iter().zip(self.order.iter()) {
            self.colors[i as usize] = *c;
        }
    }
}

/// Shades every vertex, or with `seen` only those it flags (the rest are black: the engine
/// leaves out the hair the raster would not draw, `raster::seen_points`): `out.colors()[i]` is
/// the linear RGB radiance of vertex `i` seen from `eye`, summed over the lights (light `k`'s
/// shadows are `shadows.light(k)`). The light a vertex receives is the map's past the solids,
/// given that the camera sees it ([`Shadow::light_at_vertex_seen`]: with the light near the
/// camera the view and light rays cross the same fibres, so a fibre that is seen is lit more
/// often than the average), with the fibres just in front of it taken exactly when the map
/// has contact shadows (one fibre per strand). Non-finite results (which the fibre model must
/// never produce) are replaced by black, so nothing invalid can reach a pixel.
///
/// Vertices are shaded in the order of the first map's columns
/// ([`LightMap::lookup_order_key`], ties by index), so that neighbouring lookups read
/// neighbouring memory, and the colours are then put back in vertex order. Each vertex's
/// colour does not depend on the order: only the time does (measured on smooth, one thread:
/// the lookups of every vertex 50 ms in strand order, 36 ms in map order with the sort).
pub fn shade_vertices(
    fiber: &Fiber,
    shadows: Shadows,
    lighting: &Lighting,
    eye: Vec3,
    strands: VertexGeometry,
    seen: Option<&[bool]>,
    out: &mut VertexColors,
) {
    let Some(first) = shadows.first_map() else {
        shade_vertices_with(
            fiber,
            lighting,
            eye,
            strands,
            |_, _, _| LightAtPoint::UNSHADOWED,
            &mut out.colors,
        );
        return;
    };
    let VertexGeometry {
        positions,
        tangents,
        points_per_strand,
        segment_pieces,
    } = strands;
    let r = fiber.params().radius_m;
    let bend = BendTest::for_beta_r_deg(fiber.params().beta_r_deg);
    let dirs =
        |i: usize| bend.directions(positions, tangents[i], points_per_strand, segment_pieces, i);
    let n = positions.len().min(tangents.len());
    let columns = first.geometry().columns_per_axis() as usize;
    out.order_by_column(
        n,
        columns.saturating_mul(columns),
        |i| first.lookup_order_key(positions[i]),
        |i| seen.is_none_or(|s| s.get(i).copied().unwrap_or(false)),
    );
    let (order, shaded) = (&out.order, &mut out.shaded);
    shaded.clear();
    shaded.resize(order.len(), Vec3::ZERO);
    let ambient = hair_ambient(fiber, lighting);
    // About eight jobs a thread: the seen points are few (20 K on the dance at 1280 × 720,
    // which CHUNK cut into 5 jobs for 2 threads); each vertex is shaded alone, so the split
    // changes no bit.
    let chunk = (order.len() / (rayon::current_num_threads() * 8)).clamp(MIN_CHUNK, CHUNK);
    shaded
        .par_chunks_mut(chunk)
        .zip(order.par_chunks(chunk))
        // One job per chunk: chunks cost unevenly (a lookup takes its opposition taps only
        // where the view and light rays share fibres; `raster::lines` on rayon's splitting).
        .with_max_len(1)
        .for_each(|(out, indices)| {
            for (c, &i) in out.iter_mut().zip(indices) {
                let i = i as usize;
                *c = shade_one(
                    fiber,
                    lighting,
                    ambient,
                    eye,
                    positions[i],
                    dirs(i),
                    |k, p| match shadows.light(k) {
                        Some(s) => s.light_at_vertex_seen(i, p, eye - p, tangents[i], r),
                        None => LightAtPoint::UNSHADOWED,
                    },
                );
            }
        });
    out.scatter_back(positions.len());
}

/// The ambient radiance added to every hair vertex: the sky tinted by the fibre, none when the
/// picture shows the shadows alone (`ShadingMode::Visibility`).
fn hair_ambient(fiber: &Fiber, lighting: &Lighting) -> Vec3 {
    if lighting.mode == ShadingMode::Visibility {
        Vec3::ZERO
    } else {
        lighting.ambient * fiber_tint(fiber)
    }
}

/// Vertices per parallel work item (the seen points' shading: at most).
const CHUNK: usize = 4096;
/// Vertices per parallel work item of the seen points' shading, at least (it aims at about
/// eight items a thread).
const MIN_CHUNK: usize = 256;

/// The colour of one vertex at `p` along the fibre directions `dirs` (`bend`: one, or the two
/// segments of a bent vertex, averaged): every light's contribution (its statistics from
/// `light(k, p)`, once per light) plus ambient, saturated to [0, `RADIANCE_MAX`]
/// ([`saturate_radiance`]: a sum that overflowed is the brightest radiance, not black).
#[inline]
fn shade_one(
    fiber: &Fiber,
    lighting: &Lighting,
    ambient: Vec3,
    eye: Vec3,
    p: Vec3,
    dirs: Directions,
    mut light: impl FnMut(usize, Vec3) -> LightAtPoint,
) -> Vec3 {
    let mut v = Vec3::ZERO;
    // Toward the eye, once per vertex (zero only for a vertex at the eye, where each light's
    // ωi stands in).
    let to_eye = (eye - p).normalize_or_zero();
    for (li, l) in lighting.lights.iter().enumerate() {
        let (wi, irradiance) = l.toward_and_irradiance(p);
        let wo = if to_eye == Vec3::ZERO { wi } else { to_eye };
        let at = light(li, p);
        let f = match dirs {
            Directions::One(u) => fiber.shade(lighting.mode, u, wi, wo, &at),
            Directions::Two(a, b) => {
                0.5 * (fiber.shade(lighting.mode, a, wi, wo, &at)
                    + fiber.shade(lighting.mode, b, wi, wo, &at))
            }
        };
        // Each light's term within ±RADIANCE_MAX: an overflowed term of either sign (a
        // scattering can dip below 0) would meet one of the other sign as ∞ − ∞ = NaN.
        v += (irradiance * f).clamp(Vec3::splat(-RADIANCE_MAX), Vec3::splat(RADIANCE_MAX));
    }
    saturate_radiance(v + ambient)
}

/// [`shade_vertices`] with the light statistics of vertex `i` at `p` from light `k` given by
/// `light(k, i, p)` (the maps, or a reference for measuring a map's error), in vertex order,
/// corners along both their segments as there (`bend`). A list of separate points (a sample
/// of vertices) is `points_per_strand: 1`: each is shaded at its tangent.
pub fn shade_vertices_with<L>(
    fiber: &Fiber,
    lighting: &Lighting,
    eye: Vec3,
    strands: VertexGeometry,
    light: L,
    colors: &mut Vec<Vec3>,
) where
    L: Fn(usize, usize, Vec3) -> LightAtPoint + Sync,
{
    let VertexGeometry {
        positions,
        tangents,
        points_per_strand,
        segment_pieces,
    } = strands;
    let n = positions.len().min(tangents.len());
    let bend = BendTest::for_beta_r_deg(fiber.params().beta_r_deg);
    shade_in_order(
        fiber,
        lighting,
        eye,
        &positions[..n],
        |i| {
            bend.directions(
                &positions[..n],
                tangents[i],
                points_per_strand,
                segment_pieces,
                i,
            )
        },
        light,
        colors,
    );
}

/// Every vertex of `positions` in vertex order, along `dirs(i)`, with the light of
/// `light(k, i, p)`.
fn shade_in_order<D, L>(
    fiber: &Fiber,
    lighting: &Lighting,
    eye: Vec3,
    positions: &[Vec3],
    dirs: D,
    light: L,
    colors: &mut Vec<Vec3>,
) where
    D: Fn(usize) -> Directions + Sync,
    L: Fn(usize, usize, Vec3) -> LightAtPoint + Sync,
{
    colors.resize(positions.len(), Vec3::ZERO);
    let ambient = hair_ambient(fiber, lighting);
    colors
        .par_chunks_mut(CHUNK)
        .zip(positions.par_chunks(CHUNK))
        .enumerate()
        .for_each(|(chunk, (out, pos))| {
            for (k, (c, p)) in out.iter_mut().zip(pos).enumerate() {
                let i = chunk * CHUNK + k;
                *c = shade_one(fiber, lighting, ambient, eye, *p, dirs(i), |li, p| {
                    light(li, i, p)
                });
            }
        });
}

/// Skin: Lambertian with albedo `albedo`, lit through the hair and past the other solids (each
/// light's map gives T_f at the skin point, from its surface texture where it has one,
/// [`Shadow::light_at_surface`]: hair casts its shadow on the head, the head on the body),
/// plus ambient, saturated ([`saturate_radiance`]). The lookup point is moved off the surface
/// along its normal by [`LightMap::surface_offset_m`] ("normal offset" shadow mapping), so
/// that near the terminator, where the light grazes the surface, the solid does not shadow
/// itself through the finite resolution of the occluder grid.
#[inline]
pub fn shade_skin(
    shadows: Shadows,
    lighting: &Lighting,
    albedo: Vec3,
    p: Vec3,
    normal: Vec3,
) -> Vec3 {
    let mut lit = Vec3::ZERO;
    for (k, l) in lighting.lights.iter().enumerate() {
        let Some(shadow) = shadows.light(k) else {
            break;
        };
        let (wi, irradiance) = l.toward_and_irradiance(p);
        let cos = normal.dot(wi).max(0.0);
        if cos > 0.0 {
            let tf = shadow.light_at_surface(p + normal * shadow.surface_offset_m());
            lit += irradiance * tf * cos * std::f32::consts::FRAC_1_PI;
        }
    }
    saturate_radiance(albedo * (lit + lighting.ambient))
}
