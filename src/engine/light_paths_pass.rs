//! The multiply scattered light of `ShadingMode::Volume` (`crate::light_paths`), added to the
//! vertices' single scattering: one volume of light paths per light, gathered at
//! each shaded vertex.

use super::Engine;
use crate::light_paths::{LightPaths, StrandPoints, pick_of};
use rayon::prelude::*;

impl Engine {
    /// Adds each light's multiply scattered light to the vertices shaded (all, or with
    /// `only_seen` those the raster keeps); nothing unless the shader is `ShadingMode::Volume`.
    pub(super) fn add_volume_light(&mut self, only_seen: bool) {
        if self.config.lighting.mode != crate::fiber::ShadingMode::Volume {
            return;
        }
        let eye = self.camera.eye();
        let strands = &self.strands;
        let seen = &self.seen;
        // The solids stop light where they are drawn (the head and body's colliders stand for
        // them, a character's capsules for its mesh).
        // `CollisionScene` holds them prepared (the head's inverse once, not per cell).
        let solids = self.config.draw_solids;
        let colliders = crate::sim::collide::CollisionScene::new(&self.frame_colliders);
        let points = StrandPoints {
            positions: &strands.positions,
            tangents: &strands.tangents,
            lengths_m: &strands.lengths_m,
            fibers_per_strand: self.style.strands.fibers_per_strand,
        };
        for light in &self.config.lighting.lights {
            let Some(volume) = LightPaths::build(
                &self.fiber,
                &points,
                light,
                &self.config.volume,
                solids.then_some(|p: glam::Vec3| colliders.penetration_m(p.into())),
            ) else {
                continue;
            };
            let fiber = &self.fiber;
            self.colors
                .par_iter_mut()
                .enumerate()
                .with_min_len(256)
                .for_each(|(i, c)| {
                    if only_seen && !seen.get(i).copied().unwrap_or(false) {
                        return;
                    }
                    let (Some(&p), Some(&u)) = (strands.positions.get(i), strands.tangents.get(i))
                    else {
                        return;
                    };
                    let wo = (eye - p).normalize_or_zero();
                    if wo == glam::Vec3::ZERO {
                        return;
                    }
                    *c += volume.indirect(fiber, p, u, wo, pick_of(i));
                });
        }
    }
}
