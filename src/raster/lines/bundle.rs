//! Lines that stand for a bundle of thin parallel lines: their coverage profile across the
//! line.
//!
//! Why: a render strand of F fibres drawn as one opaque band F fibre diameters wide has the
//! right coverage but, wherever it is a few pixels wide (close-ups, the crown seen from the
//! front), it reads as a flat paper ribbon with square ends. Its fibres really spread over the
//! bundle's disc (the exact reference places them there, `map::exact::placement`), so a line
//! with a [`Bundle`] is drawn as its fibres: its coverage across the line at signed distance
//! `d` (pixels) from the axis is the summed box overlap of the pixel with each fibre's
//! projected strip,
//!
//!   cov(d) = Σₖ |[d − ½, d + ½] ∩ [R·xₖ − r, R·xₖ + r]|  (pixels),
//!
//! R the bundle's projected radius, r a fibre's, xₖ ∈ [−1, 1] fibre k's offset across the line
//! (its point of the unit disc projected on one axis). Its integral over d is the fibres'
//! summed width 2Fr, the same as the band's, so the coverage of the hair is unchanged; only
//! where within the bundle it lies differs (a pixel's coverage is capped at 1: fibres that
//! overlap on screen cover their union). Where the bundle is under 3 px in radius the fibres
//! would average back to the band, so the band is drawn (`fibers.rs` blends the two from 3
//! to 6 px, mitres the joints of the fibres' segments, and narrows the bundle toward a
//! tapered tip; `cover.rs` reads the profile per pixel).
//!
//! How: in units of R the profile depends only on the offsets and on ρ = r/R, both fixed for a
//! draw call, so the cumulative width A(u) = Σₖ clamp(u − xₖ + ρ, 0, 2ρ) is tabulated once per
//! call for [`PATTERNS`] turns of the disc (lines pick one by a hash of their index, so
//! neighbouring strands do not show the same stripes), and a pixel reads
//! cov(d) = R·(A((d + ½)/R) − A((d − ½)/R)): two table reads, linear between samples.

use glam::Vec2;

/// Turns of the bundle's disc tabulated; a line uses turn `hash(line) % PATTERNS`.
pub const PATTERNS: usize = 16;
/// Samples of A(u) per pattern over u ∈ [−1 − ρ, 1 + ρ].
const SAMPLES: usize = 512;

/// What a line stands for: thin lines (fibres) spread over a disc around its axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bundle<'a> {
    /// Radius of the disc the fibres fill, world metres.
    pub radius_m: f32,
    /// Radius of one fibre, world metres.
    pub fiber_radius_m: f32,
    /// Each fibre's place in the unit disc (at least two; one fibre is a plain line).
    pub points: &'a [Vec2],
}

/// The tabulated cumulative widths of one draw call (see the module doc).
#[derive(Clone, Debug, Default)]
pub(super) struct Profiles {
    /// `PATTERNS × SAMPLES` values of A(u), pattern after pattern.
    table: Vec<f32>,
    /// ρ = r / R.
    pub(super) rho: f32,
    /// A(+∞) = 2ρ·F: the fibres' summed width in units of R.
    pub(super) total: f32,
    /// u of the first sample, and samples per unit of u.
    u0: f32,
    per_u: f32,
    /// What the table was made from (ρ and the points), so a call with the same bundle as
    /// the last one reuses it.
    made_from: (f32, Vec<Vec2>),
}

impl Profiles {
    /// Tabulates `bundle`'s profiles; `false` (and nothing to draw as a bundle) when it is not
    /// one: fewer than two fibres, non-finite or non-positive radii, or fibres as wide as the
    /// bundle.
    pub(super) fn prepare(&mut self, bundle: &Bundle) -> bool {
        let rho = bundle.fiber_radius_m / bundle.radius_m;
        if bundle.points.len() < 2
            || !(rho > 0.0 && rho < 0.5)
            || bundle.points.iter().any(|p| !p.is_finite())
        {
            self.table.clear();
            return false;
        }
        if !self.table.is_empty() && self.made_from.0 == rho && self.made_from.1 == bundle.points {
            return true;
        }
        self.made_from.0 = rho;
        self.made_from.1.clear();
        self.made_from.1.extend_from_slice(bundle.points);
        self.rho = rho;
        self.total = 2.0 * rho * bundle.points.len() as f32;
        self.u0 = -1.0 - rho;
        let span = 2.0 * (1.0 + rho);
        self.per_u = (SAMPLES - 1) as f32 / span;
        self.table.clear();
        self.table.reserve(PATTERNS * SAMPLES);
        for p in 0..PATTERNS {
            let (sn, cs) = (p as f32 * std::f32::consts::TAU / PATTERNS as f32).sin_cos();
            for i in 0..SAMPLES {
                let u = self.u0 + i as f32 / self.per_u;
                let a: f32 = bundle
                    .points
                    .iter()
                    .map(|v| {
                        let x = (cs * v.x - sn * v.y).clamp(-1.0, 1.0);
                        (u - x + rho).clamp(0.0, 2.0 * rho)
                    })
                    .sum();
                self.table.push(a);
            }
        }
        true
    }

    /// Index of the first sample of the pattern for line `line`.
    #[inline]
    pub(super) fn pattern_of(line: usize) -> u32 {
        let h = (line as u32).wrapping_mul(0x9E37_79B9);
        ((h >> 28) as usize % PATTERNS * SAMPLES) as u32
    }

    /// The fibres' summed width, in units of R, left of `u` in the pattern starting at
    /// `base` (from [`Profiles::pattern_of`]).
    #[inline(always)]
    pub(super) fn cumulative(&self, base: u32, u: f32) -> f32 {
        let t = (u - self.u0) * self.per_u;
        if !(t > 0.0) {
            return 0.0;
        }
        if t >= (SAMPLES - 1) as f32 {
            return self.total;
        }
        let i = t as usize;
        let f = t - i as f32;
        let k = base as usize + i;
        match (self.table.get(k), self.table.get(k + 1)) {
            (Some(&a), Some(&b)) => a + (b - a) * f,
            _ => 0.0,
        }
    }
}

#[cfg(test)]
mod tests;
