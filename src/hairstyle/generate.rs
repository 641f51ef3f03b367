//! Rest-pose generation: wisp roots on the scalp, guides draped around the head under gravity,
//! and the render-strand layout inside each wisp.
//!
//! Roots: a Fibonacci lattice on the unit sphere, kept where the polar angle from +Y is inside
//! the scalp region (the limit blends from `front_polar_deg` at the face to `max_polar_deg` at
//! the back), then projected radially onto the head ellipsoid. The lattice gives even spacing
//! without a relaxation pass and is deterministic.
//!
//! Guides: the first link leaves the scalp at a slant of 25° toward the comb, and the next ones
//! turn toward gravity (and, for roots near the face, toward the back, as combed hair); every new particle is
//! pushed out of the head ellipsoid inflated by a small layer offset, so the rest pose drapes
//! over the head instead of passing through it. The simulation then settles it.
//!
//! Render strands: barycentric weights drawn uniformly inside the triangle of the wisp's 3 guide
//! roots (Bertails 2005 §4.1: strands interpolated from the guides of their wisp).

use super::model::{GuideSet, StrandLayout};
use super::spec::Hairstyle;
pub use crate::rng::SplitMix64;
use glam::Vec3;

/// Point on the ellipsoid with semi-axes `r` in direction `d` (unit), and its outward unit normal.
fn ellipsoid_point(r: Vec3, d: Vec3) -> (Vec3, Vec3) {
    let s = 1.0 / (d / r).length();
    let p = d * s;
    (p, (p / (r * r)).normalize())
}

/// Pushes `p` out of the ellipsoid with semi-axes `r` (approximately: along the scaled radial
/// direction), so that its normalised radius is at least 1.
fn push_outside(p: Vec3, r: Vec3) -> Vec3 {
    let q = p / r;
    let len = q.length();
    if (1e-9..1.0).contains(&len) {
        p / len
    } else {
        p
    }
}

/// Polar angle limit (radians) of roots at azimuth `phi` (0 = face, +Z).
fn polar_limit(style: &Hairstyle, phi: f32) -> f32 {
    let front = style.scalp.front_polar_deg.to_radians();
    let back = style.scalp.max_polar_deg.to_radians();
    let t = 0.5 * (1.0 - phi.cos()); // 0 at the face, 1 at the back
    front + (back - front) * t.powf(0.7)
}

/// Unit directions of the wisp centres: `count` points of a Fibonacci lattice inside the scalp.
fn root_directions(style: &Hairstyle) -> Vec<Vec3> {
    let count = style.wisps.count as usize;
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    let inside = |n: usize, i: usize| -> Option<Vec3> {
        let y = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
        let rad = (1.0 - y * y).max(0.0).sqrt();
        let a = golden * i as f32;
        let d = Vec3::new(rad * a.sin(), y, rad * a.cos());
        let polar = y.clamp(-1.0, 1.0).acos();
        let phi = d.x.atan2(d.z);
        (polar <= polar_limit(style, phi)).then_some(d)
    };
    // Grow the lattice until the region holds enough points. Validation keeps the polar limits
    // at 5° or more (a cap of at least 0.19% of the sphere), so this ends within a few rounds;
    // the size bound only keeps an unvalidated spec from looping for ever.
    let mut n = count.max(4) * 2;
    loop {
        let dirs: Vec<Vec3> = (0..n).filter_map(|i| inside(n, i)).collect();
        if dirs.is_empty() && n > 1 << 31 {
            return vec![Vec3::Y; count];
        }
        if dirs.len() >= count || n > 1 << 31 {
            // Keep an even subset: take evenly spaced indices.
            let m = dirs.len();
            return (0..count).map(|k| dirs[k * m / count]).collect();
        }
        n = n * 3 / 2 + 8;
    }
}

/// Builds guides in their rest pose (head frame) and the render-strand layout.
pub fn generate(style: &Hairstyle) -> (GuideSet, StrandLayout) {
    let mut rng = SplitMix64::new(style.seed);
    let dirs = root_directions(style);
    let (guides, wisp_guides) = rest_guides(style, &dirs, &mut rng);
    let layout = strand_layout(style, wisp_guides, &mut rng);
    (guides, layout)
}

/// The roots of the guides [`generate`] makes, in its order (3 per wisp), without draping the
/// guides: what a check of where hair grows needs, at a cost that does not grow with
/// `guides.links`.
pub fn guide_roots(style: &Hairstyle) -> Vec<Vec3> {
    let mut rng = SplitMix64::new(style.seed);
    let radii = Vec3::from(style.head.radii_m);
    root_directions(style)
        .into_iter()
        .flat_map(|d| wisp_starts(style, radii, d, &mut rng).map(|s| s.root))
        .collect()
}

/// Where the 3 guides of the wisp centred on the scalp at direction `d` start: roots spread on
/// the wisp's disc (radius `wisps.radius_m`, a random turn), a random length within the
/// jitter, a random layer and wave phase per wisp. Draws 4 numbers from `rng`.
fn wisp_starts(style: &Hairstyle, radii: Vec3, d: Vec3, rng: &mut SplitMix64) -> [GuideStart; 3] {
    let (centre, normal) = ellipsoid_point(radii, d);
    // Tangent frame at the wisp centre.
    let side = Vec3::Y.cross(normal).try_normalize().unwrap_or(Vec3::X);
    let fwd = normal.cross(side);
    let length =
        style.guides.length_m * (1.0 + style.guides.length_jitter * (2.0 * rng.unit() - 1.0));
    let layer = 0.002 + 0.006 * rng.unit(); // metres above the scalp where hair lies
    let wave_phase = std::f32::consts::TAU * rng.unit();
    let spin = std::f32::consts::TAU * rng.unit();
    std::array::from_fn(|k| {
        let a = spin + k as f32 * std::f32::consts::TAU / 3.0;
        let offset = style.wisps.radius_m * (a.cos() * side + a.sin() * fwd);
        let (root, n) = ellipsoid_point(radii, (centre + offset).normalize());
        GuideStart {
            root,
            normal: n,
            side_dir: side,
            link_m: length / style.guides.links as f32,
            layer_m: layer,
            wave_phase,
        }
    })
}

/// The 3 guides of each wisp ([`wisp_starts`]) at the directions `dirs`, each draped by
/// [`push_guide`]. Returns the guides and each wisp's guide indices.
fn rest_guides(
    style: &Hairstyle,
    dirs: &[Vec3],
    rng: &mut SplitMix64,
) -> (GuideSet, Vec<[u32; 3]>) {
    let radii = Vec3::from(style.head.radii_m);
    let ppg = style.guides.links as usize + 1;
    let wisps = dirs.len();
    let mut rest = Vec::with_capacity(wisps * 3 * ppg);
    let mut link_length_m = Vec::with_capacity(wisps * 3);
    let mut root_normal = Vec::with_capacity(wisps * 3);
    let mut wisp_guides = Vec::with_capacity(wisps);
    for &d in dirs {
        let g0 = link_length_m.len() as u32;
        for start in wisp_starts(style, radii, d, rng) {
            push_guide(style, radii, &start, &mut rest);
            link_length_m.push(start.link_m);
            root_normal.push(start.normal);
        }
        wisp_guides.push([g0, g0 + 1, g0 + 2]);
    }
    let guides = GuideSet {
        points_per_guide: ppg,
        rest,
        link_length_m,
        root_normal,
        carrier: Vec::new(),
    };
    (guides, wisp_guides)
}

/// The render strands of every wisp: `strands_per_wisp` each, with barycentric weights drawn
/// uniformly in the guides' triangle, a random curl phase and a length fraction in
/// `[1 − length_variation, 1]`.
fn strand_layout(
    style: &Hairstyle,
    wisp_guides: Vec<[u32; 3]>,
    rng: &mut SplitMix64,
) -> StrandLayout {
    let wisps = wisp_guides.len();
    let spw = style.wisps.strands_per_wisp as usize;
    let mut strand_wisp = Vec::with_capacity(wisps * spw);
    let mut strand_weights = Vec::with_capacity(wisps * spw);
    let mut strand_phase = Vec::with_capacity(wisps * spw);
    let mut strand_length = Vec::with_capacity(wisps * spw);
    // Strand lengths come from their own stream, so the other placements do not change with
    // `length_variation`.
    let mut lengths = SplitMix64::new(style.seed ^ 0x005E_ED1E_570F_5742);
    for w in 0..wisps {
        for _ in 0..spw {
            // Uniform point in a triangle: (1 - √r1, √r1 (1 - r2), √r1 r2).
            let s1 = rng.unit().sqrt();
            let r2 = rng.unit();
            strand_wisp.push(w as u32);
            strand_weights.push([1.0 - s1, s1 * (1.0 - r2), s1 * r2]);
            strand_phase.push(std::f32::consts::TAU * rng.unit());
            strand_length.push(1.0 - style.strands.length_variation * lengths.unit());
        }
    }
    let points = style.strands.points as usize;
    StrandLayout {
        rest_offset: tip_fan(style, strand_wisp.len(), points),
        wisp_guides,
        strand_wisp,
        strand_weights,
        strand_phase,
        strand_length,
        tip_taper: style.strands.tip_taper,
        points_per_strand: points,
    }
}

/// Largest sideways reach of a render strand's tip from where its wisp's blend puts it, as a
/// fraction of the wisp radius.
const TIP_FAN_OF_WISP_RADIUS: f32 = 0.6;

/// Each render strand's departure from its wisp's blend over its tip taper (the layout's
/// `rest_offset`, `points` per strand): 0 before the taper, growing as the square of the way
/// through it to a reach drawn in [0, `TIP_FAN_OF_WISP_RADIUS`] × the wisp radius, sideways in
/// a direction of its own. The blends of a wisp's strands run parallel to the tips, so without
/// it the strands of a wisp end side by side like the bristles of a brush cut straight; real
/// tips part where their fibres thin out. None (empty) without a taper. Drawn from a stream of
/// its own, so every other placement is the same with or without it.
fn tip_fan(style: &Hairstyle, strands: usize, points: usize) -> Vec<Vec3> {
    let taper = style.strands.tip_taper;
    if taper.is_nan() || taper <= 0.0 || points < 2 {
        return Vec::new();
    }
    let mut rng = SplitMix64::new(style.seed ^ 0x7195_FA2E_D0C7_3B11);
    let mut out = Vec::with_capacity(strands * points);
    for _ in 0..strands {
        let reach = TIP_FAN_OF_WISP_RADIUS * style.wisps.radius_m * rng.unit();
        let (sin, cos) = (std::f32::consts::TAU * rng.unit()).sin_cos();
        for i in 0..points {
            let u = i as f32 / (points - 1) as f32;
            let through = ((u - (1.0 - taper)) / taper).clamp(0.0, 1.0);
            let r = reach * through * through;
            out.push(Vec3::new(r * cos, r * sin, 0.0));
        }
    }
    out
}

/// Where a guide starts and how it lies: its root on the scalp and the unit scalp normal
/// there, the wisp's side direction (the wave's plane), its link length, the layer above the
/// scalp its particles keep (metres) and its wave's phase (radians).
struct GuideStart {
    root: Vec3,
    normal: Vec3,
    side_dir: Vec3,
    link_m: f32,
    layer_m: f32,
    wave_phase: f32,
}

/// Elevation of a guide's first link above the scalp's tangent plane, degrees: hair leaves
/// its follicle at a slant and lies down within a few millimetres. A first link along the
/// normal (a whole link, 2.3 cm for the smooth preset) stood every root up like a brush
/// bristle at the crown, with its shadowed side showing as a dark stub along the parting.
const ROOT_ELEVATION_DEG: f32 = 25.0;

/// The first link's direction: `ROOT_ELEVATION_DEG` above the scalp (unit `normal`), toward
/// where the hair is combed (`hang`, projected onto the tangent plane); the normal where the
/// comb has no tangential part.
fn root_direction(normal: Vec3, hang: Vec3) -> Vec3 {
    let Some(along) = (hang - normal * hang.dot(normal)).try_normalize() else {
        return normal;
    };
    let (sin, cos) = ROOT_ELEVATION_DEG.to_radians().sin_cos();
    (normal * sin + along * cos).normalize_or(normal)
}

/// Appends the particles of one guide, root first, each link of length `start.link_m`
/// metres.
fn push_guide(style: &Hairstyle, radii: Vec3, start: &GuideStart, out: &mut Vec<Vec3>) {
    let GuideStart {
        root,
        normal,
        side_dir,
        link_m: l,
        layer_m: layer,
        wave_phase,
    } = *start;
    let links = style.guides.links as usize;
    let inflated = radii + Vec3::splat(layer);
    let mut p = root;
    let mut dir = normal;
    let mut first = normal;
    out.push(p);
    let amp = style.guides.wave_amplitude_m;
    let mut prev_wave = 0.0;
    for i in 1..=links {
        let s = i as f32 * l; // arc length at the new particle
        // Combing: while a strand is over the front half of the head it is brushed back (−Z)
        // and a little outward; behind the head only gravity remains. The push out of the
        // head below turns this into hair lying along the scalp, over the crown.
        let front = ((p.z / radii.z + 0.25) / 0.75).clamp(0.0, 1.0);
        let side = (p.x / radii.x).clamp(-1.0, 1.0);
        let comb = Vec3::new(0.8 * side, 0.0, -2.5) * front;
        let hang = (Vec3::NEG_Y + comb).normalize();
        if i == 1 {
            first = root_direction(normal, hang);
        }
        // The first link leaves at a slant toward the comb (`root_direction`); the next ones
        // turn from there to the comb over the first 4 cm.
        let t = (s / 0.04).min(1.0);
        let want = (first * (1.0 - t) + hang * t).normalize_or(hang);
        dir = if i == 1 {
            first
        } else {
            (dir + 2.0 * want).normalize_or(want)
        };
        let mut next = p + dir * l;
        if amp > 0.0 {
            let ramp = (s / 0.05).min(1.0);
            let wave = amp
                * ramp
                * (std::f32::consts::TAU * s / style.guides.wave_period_m + wave_phase).sin();
            next += side_dir * (wave - prev_wave);
            prev_wave = wave;
        }
        // Push out of the head, then restore the link length (keeps links rigid in the rest
        // pose too); a few rounds converge because the previous particle is outside.
        for _ in 0..4 {
            next = push_outside(next, inflated);
            next = p + (next - p).normalize_or(dir) * l;
        }
        dir = (next - p) / l;
        out.push(next);
        p = next;
    }
}

#[cfg(test)]
mod tests;
