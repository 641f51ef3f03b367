//! The skin texture pass: the hair's shadow on skin and clothes, per light, in a texture finer
//! than the map's columns (`map::surface`): each sample's ribbon of fibres deposits its optical
//! depth where it lies in front of the first solid. Without solids drawn there is no skin to
//! shade and no texture.

use super::hair_map::HairMapInput;
use super::sizes::RunSizes;
use crate::budget::MemoryPart;
use crate::map::surface::{DEFAULT_TEXELS_PER_COLUMN, SurfaceShadow};
use crate::map::{LightMap, OccluderGrid};

/// How finely the hair's shadow on the solids is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkinTextureConfig {
    /// Texels per map column across the light, along each axis (default 2): finer texels
    /// draw narrower streaks, at a cost that grows with the texels each ribbon covers.
    pub texels_per_column: f32,
}

impl Default for SkinTextureConfig {
    fn default() -> Self {
        Self {
            texels_per_column: DEFAULT_TEXELS_PER_COLUMN,
        }
    }
}

/// Per light, the hair's shadow texture on the solids (`None` where the map holds no hair).
#[derive(Default)]
pub struct SkinTexturePass {
    pub config: SkinTextureConfig,
    textures: Vec<Option<SurfaceShadow>>,
}

impl SkinTexturePass {
    pub fn new(config: SkinTextureConfig) -> Self {
        Self {
            config,
            textures: Vec::new(),
        }
    }

    /// Builds each light's texture from `hair` in front of `grids`, in `maps`' frames, when
    /// solids are drawn and the maps or the grids changed, for render strands whose fibres
    /// spread over `bundle_radius_m`.
    pub fn run(
        &mut self,
        (maps, grids): (&[LightMap], &[OccluderGrid]),
        hair: &HairMapInput,
        bundle_radius_m: f32,
        draw_solids: bool,
        changed: bool,
    ) {
        if !draw_solids || !changed {
            return;
        }
        self.textures.resize_with(maps.len(), || None);
        for (((texture, map), grid), light) in self
            .textures
            .iter_mut()
            .zip(maps)
            .zip(grids)
            .zip(hair.lights)
        {
            SurfaceShadow::build_for(
                texture,
                map,
                grid,
                &hair.for_light(light),
                bundle_radius_m,
                self.config.texels_per_column,
            );
        }
    }

    /// Per light, the hair's shadow texture (empty without solids).
    pub fn textures(&self) -> &[Option<SurfaceShadow>] {
        &self.textures
    }

    /// The textures at most, when solids are drawn.
    pub fn estimate(
        config: &SkinTextureConfig,
        sizes: &RunSizes,
        draw_solids: bool,
    ) -> Vec<MemoryPart> {
        let (geom, density) = (sizes.geom, config.texels_per_column);
        vec![MemoryPart {
            what: "surface shadow texture",
            product: if draw_solids {
                format!(
                    "{} light(s) × at most {} map columns² × {} texels each, and a ribbon per render point",
                    sizes.lights,
                    geom.columns_per_axis(),
                    density
                )
            } else {
                "off (no solids drawn)".to_string()
            },
            bytes: if draw_solids {
                SurfaceShadow::estimated_bytes(
                    geom.columns_per_axis() as u64,
                    density,
                    sizes.points,
                    SurfaceShadow::ribbon_texel_bound(
                        geom.column_m(),
                        density,
                        0.5 * sizes.strand_spacing_m,
                        sizes.sample_len_m as f32,
                    ),
                )
                .saturating_mul(sizes.lights)
            } else {
                0
            },
            set_by: "the solids drawn, --map-res and render points",
        }]
    }
}
