//! Points spread evenly over the unit disc (a Vogel spiral): where the fibres of a render
//! strand's bundle lie across it. The raster draws a bundle's fibres there, and the exact
//! reference places its fibres and its rays' footprints the same way.
//!
//! Point i of n sits at radius ρ = √((i + ½)/n) and angle i·g, g = π(3 − √5) the golden angle:
//! the √ keeps the area density uniform (each point holds an area π/n), and the golden angle
//! keeps successive points from lining up in spokes, whatever n.

use glam::Vec2;

/// Golden angle, radians.
const GOLDEN_ANGLE: f32 = 2.399_963_2;

/// Point `i` of `count` of a Vogel spiral filling the unit disc evenly.
#[inline]
pub fn vogel(i: u32, count: u32) -> Vec2 {
    let rho = ((i as f32 + 0.5) / count as f32).sqrt();
    let (s, c) = (i as f32 * GOLDEN_ANGLE).sin_cos();
    Vec2::new(c, s) * rho
}

/// Where the fibres of a bundle of `count` lie in its unit disc (fibre f at `vogel(f, count)`,
/// before the per-strand turn): the raster draws a bundle's fibres there too.
pub fn bundle_disc_points(count: u32) -> Vec<Vec2> {
    (0..count).map(|f| vogel(f, count)).collect()
}

#[cfg(test)]
mod tests;
