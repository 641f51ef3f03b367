//! Whether a groom's roots lie on the character's drawn head.
//!
//! A [`super::Fit`] places the hairstyle's head frame on the head joint: scale and offset from
//! the head mesh's box ([`super::fit`]), or given (`--head-scale`, `--head-offset`). Roots
//! placed in that frame should then lie on the drawn head; when they do not (a groom made for
//! another head, in other units, or a fit given wrongly) the hair floats off the head or grows
//! from inside it, and the user must be told before minutes of simulation are spent.
//!
//! [`Motion::roots_on_head`] measures it on the clip's first pose (t = 0): each root's distance
//! to the nearest triangle of the head mesh (triangles whose three vertices belong to the
//! head, [`super::Character::is_head_vertex`]), in pose metres. A root is near the head when
//! that distance is at most [`ROOT_TOLERANCE`] × the head's mean radius; the groom is on the
//! head when its median root is.
//!
//! Why that tolerance: the generated hairstyles grow on the ellipsoid inscribed in the head
//! mesh's box, and a boxy head (RobotExpressive's) stands off that ellipsoid by up to
//! (1 − 1/√3) ≈ 0.42 of its radius toward a corner of the box, (1 − 1/√2) ≈ 0.29 toward an
//! edge. A groom whose median root is farther than half a radius from every head triangle is
//! not on this head.
//!
//! Cost: at most [`MAX_ROOTS`] roots (evenly strided) against every head triangle: linear in
//! the head's triangles, independent of the groom's size beyond that.

use glam::Vec3;

use super::playback::Motion;
use super::skin::CharacterPose;

/// A root is near the head within this fraction of the head's mean radius (module doc).
pub const ROOT_TOLERANCE: f32 = 0.5;
/// Most roots measured (evenly strided over the groom).
pub const MAX_ROOTS: usize = 4096;

/// How far a groom's roots lie from the drawn head, pose metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RootsOnHead {
    /// Roots measured.
    pub roots: usize,
    /// Roots within `tolerance_m` of a head triangle.
    pub near: usize,
    /// Median distance of a root to the nearest head triangle.
    pub median_m: f32,
    /// Largest such distance.
    pub worst_m: f32,
    /// [`ROOT_TOLERANCE`] × the head's mean radius.
    pub tolerance_m: f32,
}

impl RootsOnHead {
    /// The median root lies within the tolerance of the head mesh.
    pub fn on_head(&self) -> bool {
        self.median_m <= self.tolerance_m
    }
}

impl Motion {
    /// How far `roots` (hairstyle head frame, metres) lie from the head mesh at t = 0, for a
    /// head of mean radius `head_radius_m` (see the module doc). `None` without a character,
    /// without head triangles, or without roots.
    pub fn roots_on_head(&self, roots: &[Vec3], head_radius_m: f32) -> Option<RootsOnHead> {
        let ch = self.character()?;
        let tris: Vec<[u32; 3]> = ch
            .triangles
            .iter()
            .copied()
            .filter(|t| t.iter().all(|&v| ch.is_head_vertex(v as usize)))
            .collect();
        if tris.is_empty() || roots.is_empty() {
            return None;
        }
        let mut pose = CharacterPose::default();
        self.pose_character(0.0, &mut pose);
        let head = self.sample(0.0).head;
        let stride = roots.len().div_ceil(MAX_ROOTS);
        let mut dist: Vec<f32> = roots
            .iter()
            .step_by(stride)
            .map(|r| {
                let p = head.transform_point3(*r);
                tris.iter()
                    .map(|t| {
                        let [a, b, c] = t.map(|v| pose.positions[v as usize]);
                        (p - closest_on_triangle(p, a, b, c)).length_squared()
                    })
                    .fold(f32::INFINITY, f32::min)
                    .sqrt()
            })
            .collect();
        dist.sort_by(f32::total_cmp);
        let tolerance_m = ROOT_TOLERANCE * head_radius_m;
        Some(RootsOnHead {
            roots: dist.len(),
            near: dist.iter().filter(|d| **d <= tolerance_m).count(),
            median_m: dist[dist.len() / 2],
            worst_m: dist[dist.len() - 1],
            tolerance_m,
        })
    }
}

/// The point of triangle `abc` nearest `p`: inside the triangle's plane projection when that
/// falls inside it, else the nearest point of its three edges.
fn closest_on_triangle(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Vec3 {
    let n = (b - a).cross(c - a);
    let n2 = n.length_squared();
    if n2 > 0.0 {
        let q = p - n * ((p - a).dot(n) / n2);
        // Inside when q is on the inner side of all three edges.
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(u, v)| (v - u).cross(q - u).dot(n) >= 0.0);
        if inside {
            return q;
        }
    }
    [(a, b), (b, c), (c, a)]
        .iter()
        .map(|&(u, v)| on_segment(p, u, v))
        .min_by(|x, y| {
            (p - *x)
                .length_squared()
                .total_cmp(&(p - *y).length_squared())
        })
        .unwrap_or(a)
}

/// The point of segment `u`–`v` nearest `p`.
fn on_segment(p: Vec3, u: Vec3, v: Vec3) -> Vec3 {
    let d = v - u;
    let l2 = d.length_squared();
    if l2.is_nan() || l2 <= 0.0 {
        return u;
    }
    u + d * ((p - u).dot(d) / l2).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests;
