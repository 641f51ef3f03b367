//! A grid-free reference for the map: the same light transport (Poisson crossings, Zinke's
//! per-crossing ā_f and β̄_f²), but with each render-strand sample's fibres spread as an
//! isotropic 3D Gaussian of width `h` instead of being binned into cells.
//!
//! A render strand stands for F fibres spread over roughly the spacing between render
//! strands, so `h` = that spacing is the density the map's cells approximate. Integrating the
//! Gaussian along the light ray up to a point gives a lateral 2D Gaussian times a 1D normal
//! CDF, so the expected crossings before point v are exactly
//!
//! n(v) = Σ_s c_s · exp(−d_s²/2h²)/(2πh²) · Φ((x_v − x_s)/h),   c_s = F·ℓ_s·2r·sin ψ_s,
//!
//! with d_s the lateral distance between the light rays through v and the sample. Then as in
//! the map: direct = exp(−n), T_f = exp(−Σ c·w·(1 − ā_f)), σ̄f² = Σ c·w·β̄_f².
//!
//! No grid means no discretisation error, so the difference between the map and this reference
//! is the map's own error (cell size, box fill, trilinear read) for the same physics. Cost is
//! O(vertices × samples within 4h laterally); it is a measuring instrument, not a renderer.

use super::{LightFrame, MapBuildInput};
use crate::fiber::LightAtPoint;
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// Normal CDF Φ(t) from erf (Abramowitz & Stegun 7.1.26, |error| < 1.5e-7).
fn normal_cdf(t: f32) -> f32 {
    let x = t.abs() * std::f32::consts::FRAC_1_SQRT_2;
    let k = 1.0 / (1.0 + 0.327_591_1 * x);
    let poly = k
        * (0.254_829_6
            + k * (-0.284_496_74 + k * (1.421_413_7 + k * (-1.453_152_1 + k * 1.061_405_4))));
    let erf = 1.0 - poly * (-x * x).exp();
    if t >= 0.0 {
        0.5 * (1.0 + erf)
    } else {
        0.5 * (1.0 - erf)
    }
}

/// One sample's contribution, in the light frame.
#[derive(Clone, Copy)]
struct Source {
    x: f32,
    yz: Vec2,
    crossings: f32,
    loss: Vec3,
    beta2: Vec3,
}

/// The light reaching each point of `points` (world) in the Gaussian-density reference of
/// width `h_m` built from `input`'s samples.
pub fn reference_light(input: &MapBuildInput, h_m: f32, points: &[Vec3]) -> Vec<LightAtPoint> {
    let frame = LightFrame::new(input.light_dir);
    let r = input.fiber.params().radius_m;
    let to_light = -frame.x;
    let count = input
        .positions
        .len()
        .min(input.tangents.len())
        .min(input.lengths_m.len());
    let sources: Vec<Source> = (0..count)
        .filter(|&s| input.positions[s].is_finite() && input.tangents[s].is_finite())
        .map(|s| {
            let (p, u) = (frame.to_map(input.positions[s]), input.tangents[s]);
            let cos_psi = u.dot(frame.x).clamp(-1.0, 1.0);
            let c = input.fibers_per_strand
                * input.lengths_m[s]
                * 2.0
                * r
                * (1.0 - cos_psi * cos_psi).max(0.0).sqrt();
            let fs = input
                .fiber
                .forward_scatter(u.dot(to_light).clamp(-1.0, 1.0));
            Source {
                x: p.x,
                yz: Vec2::new(p.y, p.z),
                crossings: c,
                loss: c * (Vec3::ONE - fs.a_f.clamp(Vec3::ZERO, Vec3::ONE)),
                beta2: c * fs.beta_f2,
            }
        })
        .collect();
    // Lateral hash grid of bucket size 4h: the Gaussian beyond 4h weighs < 3.4e-4 of its peak.
    let bucket = 4.0 * h_m;
    let (lo, hi) = sources.iter().fold(
        (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN)),
        |(a, b), s| (a.min(s.yz), b.max(s.yz)),
    );
    if sources.is_empty() {
        return vec![LightAtPoint::UNSHADOWED; points.len()];
    }
    let dims = ((hi - lo) / bucket).floor().as_uvec2() + 1;
    let index = |yz: Vec2| -> Option<(u32, u32)> {
        let c = ((yz - lo) / bucket).floor();
        (c.x >= 0.0 && c.y >= 0.0 && (c.x as u32) < dims.x && (c.y as u32) < dims.y)
            .then_some((c.x as u32, c.y as u32))
    };
    let mut starts = vec![0u32; (dims.x * dims.y + 1) as usize];
    for s in &sources {
        let (a, b) = index(s.yz).expect("sources lie inside their own bounds");
        starts[(a * dims.y + b) as usize + 1] += 1;
    }
    for i in 1..starts.len() {
        starts[i] += starts[i - 1];
    }
    let mut cursor = starts.clone();
    let mut sorted = vec![sources[0]; sources.len()];
    for s in &sources {
        let (a, b) = index(s.yz).expect("inside");
        let c = &mut cursor[(a * dims.y + b) as usize];
        sorted[*c as usize] = *s;
        *c += 1;
    }
    let inv_2h2 = 1.0 / (2.0 * h_m * h_m);
    let norm = 1.0 / (std::f32::consts::TAU * h_m * h_m);
    points
        .par_iter()
        .map(|p| {
            let m = frame.to_map(*p);
            let yz = Vec2::new(m.y, m.z);
            let c = ((yz - lo) / bucket).floor();
            let (mut n, mut loss, mut var) = (0.0f32, Vec3::ZERO, Vec3::ZERO);
            for da in -1i64..=1 {
                for db in -1i64..=1 {
                    let (a, b) = (c.x as i64 + da, c.y as i64 + db);
                    if a < 0 || b < 0 || a >= dims.x as i64 || b >= dims.y as i64 {
                        continue;
                    }
                    let k = (a as u32 * dims.y + b as u32) as usize;
                    for s in &sorted[starts[k] as usize..starts[k + 1] as usize] {
                        let d2 = (s.yz - yz).length_squared();
                        if d2 > 16.0 * h_m * h_m {
                            continue;
                        }
                        let w = norm * (-d2 * inv_2h2).exp() * normal_cdf((m.x - s.x) / h_m);
                        n += s.crossings * w;
                        loss += s.loss * w;
                        var += s.beta2 * w;
                    }
                }
            }
            LightAtPoint {
                direct_fraction: (-n).exp(),
                tf: (-loss).exp(),
                sigma_f2: var,
                crossings_behind: LightAtPoint::DENSE,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::normal_cdf;

    #[test]
    fn normal_cdf_matches_known_values() {
        // Φ(0) = 0.5, Φ(1) = 0.841345, Φ(-2) = 0.022750, Φ(3) = 0.998650 (standard tables).
        for (t, v) in [
            (0.0, 0.5),
            (1.0, 0.841_345),
            (-2.0, 0.022_750),
            (3.0, 0.998_650),
        ] {
            assert!(
                (normal_cdf(t) - v).abs() < 2e-6,
                "Φ({t}) = {}",
                normal_cdf(t)
            );
        }
    }
}
