//! The multiply scattered light of `ShadingMode::Volume` (`crate::volume`), added to the
//! vertices' single scattering: one volume of light paths per directional light, gathered at
//! each shaded vertex.

use super::Engine;
use crate::light::Light;
use crate::volume::{PhotonVolume, pick_of};
use rayon::prelude::*;

impl Engine {
    /// Adds each directional light's multiply scattered light to the vertices shaded (all, or
    /// with `only_seen` those the raster keeps); point lights add none.
    pub(super) fn add_volume_light(&mut self, only_seen: bool) {
        let eye = self.camera.eye();
        let strands = &self.strands;
        let seen = &self.seen;
        let fibers = self.style.strands.fibers_per_strand;
        for light in &self.config.lighting.lights {
            let Light::Directional { travel, irradiance } = *light else {
                continue;
            };
            let Some(volume) = PhotonVolume::build(
                &self.fiber,
                &strands.positions,
                &strands.tangents,
                &strands.lengths_m,
                fibers,
                travel.get(),
                irradiance,
                &self.config.volume,
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
