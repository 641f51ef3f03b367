//! The guides' rest shape as the integrator reads it: rest positions and link directions in
//! the head frame, link lengths, the hair volume each particle stands for, the bending
//! damping's weights, and the self-collision grid's size.
//!
//! What each particle stands for: a guide carries the cross-section of every fibre of the
//! render strands it drives, A = N_fibres · π r² / guides (3 guides per wisp share a wisp's
//! strands), times the helix length factor √(1 + (2π R / P)²) of curled strands (a curl of
//! radius R and period P puts that much more fibre along each metre of guide). Each of a
//! guide's n particles stands for an equal share of its hair, V = A · L · (n − 1)/n for links
//! of length L: the volume the density grid splats (`density.rs`).
//!
//! The density grid's spacing h is the mean link length, so that one sample per particle
//! gives a density that is smooth along the strand (the B-spline's partition of unity), but at
//! least 1/60 of the hair's reach (root distance from the head centre plus guide length), so
//! that the whole reachable cube, 2·reach/h + 4 ≤ 124 nodes a side, fits the grid's node
//! budget and is reserved once.

use super::bend;
use super::state::{sanitized_link_m, usable_guides};
use crate::hairstyle::{GuideSet, Hairstyle};
use glam::Vec3A;

/// Constant per-particle data of the rest shape, head frame.
pub(super) struct Shape {
    pub(super) points_per_guide: usize,
    /// Rest positions, head frame (roots and the rigid first link are placed from these).
    pub(super) rest: Vec<Vec3A>,
    /// Unit rest direction of the link ending at each particle, head frame (index 0 of each
    /// guide holds the root normal).
    pub(super) rest_dir: Vec<Vec3A>,
    /// Link length per guide, metres.
    pub(super) link_m: Vec<f32>,
    /// Hair volume each particle of a guide stands for, m³ (`density.rs`).
    pub(super) particle_volume_m3: Vec<f32>,
    /// Weights of the exact bending damping over one step (`bend::damping_weights`).
    pub(super) damping_weights: Vec<f32>,
    /// Per guide, the bone that carries its root (`GuideSet::carrier`; empty: the head).
    pub(super) carrier: Vec<u32>,
}

/// Cross-section of real hair (m²) each guide stands for (module doc): every fibre of every
/// render strand, π r² per fibre, shared by the guides, times the curl's length factor.
pub fn hair_section_per_guide_m2(style: &Hairstyle, guides: &GuideSet) -> f32 {
    let fibers = style.wisps.count as f64
        * f64::from(style.wisps.strands_per_wisp)
        * f64::from(style.strands.fibers_per_strand);
    let r = f64::from(style.fiber.radius_m);
    let (cr, cp) = (
        f64::from(style.curl.radius_m),
        f64::from(style.curl.period_m),
    );
    let curl = if cr > 0.0 && cp > 0.0 {
        (1.0 + (std::f64::consts::TAU * cr / cp).powi(2)).sqrt()
    } else {
        1.0
    };
    let per_guide = fibers * std::f64::consts::PI * r * r * curl / guides.count().max(1) as f64;
    if per_guide.is_finite() {
        per_guide as f32
    } else {
        0.0
    }
}

impl Shape {
    /// The rest shape of the usable guides of `guides`, each standing for hair of
    /// cross-section `section_m2` (≥ 0), with the bending damping `bend_damp` per step.
    pub(super) fn new(guides: &GuideSet, section_m2: f32, bend_damp: f32) -> Shape {
        let ppg = guides.points_per_guide;
        let count = usable_guides(guides);
        let n = count * ppg;
        let rest: Vec<Vec3A> = guides.rest[..n].iter().map(|p| Vec3A::from(*p)).collect();
        let mut rest_dir = Vec::with_capacity(n);
        for g in 0..count {
            let normal = Vec3A::from(guides.root_normal[g]).normalize_or(Vec3A::Y);
            rest_dir.push(normal);
            for i in 1..ppg {
                let d = rest[g * ppg + i] - rest[g * ppg + i - 1];
                let prev = rest_dir[g * ppg + i - 1];
                rest_dir.push(d.normalize_or(prev));
            }
        }
        let link_m: Vec<f32> = guides.link_length_m[..count]
            .iter()
            .map(|l| sanitized_link_m(*l))
            .collect();
        // Each of the ppg particles stands for an equal share of the guide's hair.
        let share = if ppg > 0 {
            (ppg - 1) as f32 / ppg as f32
        } else {
            0.0
        };
        let particle_volume_m3 = link_m.iter().map(|l| section_m2 * l * share).collect();
        Shape {
            points_per_guide: ppg,
            rest,
            rest_dir,
            link_m,
            particle_volume_m3,
            damping_weights: bend::damping_weights(bend_damp, ppg),
            carrier: guides.carrier.iter().take(count).copied().collect(),
        }
    }

    /// How far from the head centre any particle can be, metres: root distance plus guide
    /// length, over the guides.
    pub(super) fn reach_m(&self) -> f32 {
        let ppg = self.points_per_guide;
        (0..self.link_m.len())
            .map(|g| {
                let root = self.rest[g * ppg].length();
                root + self.link_m[g] * (ppg.saturating_sub(1)) as f32
            })
            .fold(0.0f32, f32::max)
    }

    /// The density grid's node spacing for hair of reach `reach_m` (module doc), metres.
    pub(super) fn density_cell_m(&self, reach_m: f32) -> f32 {
        let count = self.link_m.len();
        let mean_link_m = if count > 0 {
            self.link_m.iter().map(|l| f64::from(*l)).sum::<f64>() / count as f64
        } else {
            0.02
        };
        (mean_link_m as f32).max(reach_m / 60.0).clamp(1e-3, 1.0)
    }
}
