//! A triangle on screen, ready to rasterise ([`ScreenTri`]), and its edge functions.

use glam::{Vec2, Vec3};

/// A triangle ready to rasterise: screen positions, 1/depth and the attributes at its corners.
#[derive(Clone, Copy, Debug)]
pub(super) struct ScreenTri {
    pub(super) p: [Vec2; 3],
    pub(super) inv_z: [f32; 3],
    pub(super) world: [Vec3; 3],
    pub(super) normal: [Vec3; 3],
    pub(super) uv: [Vec2; 3],
    pub(super) surface: u16,
    /// Front-facing (for double-sided surfaces seen from behind, normals are flipped).
    pub(super) front: bool,
    /// Twice the signed screen area (non-zero).
    pub(super) area2: f32,
}

/// A triangle's screen box: its corners' minimum and maximum.
#[inline]
pub(super) fn screen_box(t: &ScreenTri) -> (Vec2, Vec2) {
    (
        t.p[0].min(t.p[1]).min(t.p[2]),
        t.p[0].max(t.p[1]).max(t.p[2]),
    )
}

/// Screen-space edge functions of a triangle at `q`: e[i] is twice the signed area of the
/// sub-triangle opposite corner i, so e / area2 are the screen barycentrics.
#[inline]
pub(super) fn edges(t: &ScreenTri, q: Vec2) -> [f32; 3] {
    let [p0, p1, p2] = t.p;
    [
        (p1 - q).perp_dot(p2 - q),
        (p2 - q).perp_dot(p0 - q),
        (p0 - q).perp_dot(p1 - q),
    ]
}
