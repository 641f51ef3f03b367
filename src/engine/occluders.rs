//! The occluder pass: the opaque solids of the frame (the head ellipsoid unless the character's
//! mesh has a head, the body spheres, the character's posed mesh) as entry depths across each
//! light, in its map's frame (`map::OccluderGrid`). They shadow the hair behind them as the
//! hair shadows them. Without solids drawn there are none: no invisible head casts a shadow.

use super::reuse::Kept;
use super::setup::solids_of;
use super::sizes::RunSizes;
use crate::budget::{MemoryPart, grouped};
use crate::map::{LightMap, OccluderGrid, OccluderMesh, Solid};
use crate::motion::{Character, CharacterPose, Pose};
use glam::Vec3;

/// Albedo of the head ellipsoid's skin.
const SKIN: Vec3 = Vec3::new(0.55, 0.38, 0.30);
/// Albedo of the body spheres' clothes.
const CLOTH: Vec3 = Vec3::new(0.10, 0.14, 0.22);

/// How the solids' entry depths are sampled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OccluderConfig {
    /// Texel of the entry depths across the light, in map cells (default ¼): finer texels
    /// draw the solids' shadow edges sharper, at a cost that grows as 1/texel² over the
    /// solids' extent (at most `map::occluders::MAX_TEXELS`² texels).
    pub texel_cells: f32,
}

impl Default for OccluderConfig {
    fn default() -> Self {
        Self { texel_cells: 0.25 }
    }
}

/// What the solids of a frame are made of.
#[derive(Clone, Copy)]
pub struct SolidsInput<'a> {
    pub pose: &'a Pose,
    pub head_radii_m: Vec3,
    /// The character and its posed mesh, if the motion has one.
    pub character: Option<(&'a Character, &'a CharacterPose)>,
    /// Whether solids are drawn at all (`Scene::draw_solids`).
    pub draw_solids: bool,
}

/// The frame's solids and, per light, their entry depths.
pub struct OccluderPass {
    pub config: OccluderConfig,
    /// The character's mesh has a head, so the head ellipsoid is not a solid.
    character_has_head: bool,
    grids: Vec<OccluderGrid>,
    /// The head and body solids of the frame, and their albedos.
    solids: Vec<Solid>,
    albedo: Vec<Vec3>,
    kept_solids: Kept<Solid>,
    kept_mesh: Kept<Vec3>,
}

impl OccluderPass {
    /// No grids yet; `character` is the motion's character, if any.
    pub fn new(config: OccluderConfig, character: Option<&Character>) -> Self {
        Self {
            config,
            character_has_head: character.is_some_and(Character::has_head),
            grids: Vec::new(),
            solids: Vec::new(),
            albedo: Vec::new(),
            kept_solids: Kept::default(),
            kept_mesh: Kept::default(),
        }
    }

    /// The solids of `input`, and their grids in each of `maps`' frames, rebuilt when the maps
    /// or the solids changed. Returns whether the grids changed.
    pub fn run(&mut self, maps: &[LightMap], maps_changed: bool, input: &SolidsInput) -> bool {
        self.collect_solids(input);
        let character = input.character.filter(|_| input.draw_solids);
        let mesh_positions: &[Vec3] = character.map_or(&[], |(_, posed)| &posed.positions);
        let solids_same = self.kept_solids.unchanged_or_record(&[&self.solids]);
        let mesh_same = self.kept_mesh.unchanged_or_record(&[mesh_positions]);
        if !maps_changed && solids_same && mesh_same && self.grids.len() == maps.len() {
            return false;
        }
        let mesh = match character {
            Some((ch, posed)) => OccluderMesh {
                positions: &posed.positions,
                triangles: &ch.triangles,
            },
            None => OccluderMesh::EMPTY,
        };
        self.grids.resize_with(maps.len(), OccluderGrid::default);
        for (grid, map) in self.grids.iter_mut().zip(maps) {
            grid.build_for(map, self.config.texel_cells, &self.solids, mesh);
        }
        true
    }

    /// The head ellipsoid (unless the character's mesh has a head) and the body spheres of the
    /// pose, when solids are drawn.
    fn collect_solids(&mut self, input: &SolidsInput) {
        self.solids.clear();
        self.albedo.clear();
        if !input.draw_solids {
            return;
        }
        let has_head = input.character.is_some() && self.character_has_head;
        for (k, s) in solids_of(input.pose, input.head_radii_m)
            .enumerate()
            .skip(usize::from(has_head))
        {
            self.solids.push(s);
            self.albedo.push(if k == 0 { SKIN } else { CLOTH });
        }
    }

    /// Per light, the solids' entry depths in its map's frame.
    pub fn grids(&self) -> &[OccluderGrid] {
        &self.grids
    }

    /// The head and body solids of the frame, with their albedos.
    pub fn solids(&self) -> (&[Solid], &[Vec3]) {
        (&self.solids, &self.albedo)
    }

    /// The grids, and the character's posed vertices kept for reuse.
    pub fn estimate(sizes: &RunSizes) -> Vec<MemoryPart> {
        let mut parts = vec![MemoryPart {
            what: "occluders",
            product: format!("{} light(s) × one grid of entry depths", sizes.lights),
            bytes: OccluderGrid::estimated_bytes().saturating_mul(sizes.lights),
            set_by: "the lights",
        }];
        if sizes.character_vertices > 0 {
            parts.push(MemoryPart {
                what: "character mesh kept for reuse",
                product: format!("{} vertices", grouped(sizes.character_vertices)),
                bytes: Kept::<Vec3>::estimated_bytes(sizes.character_vertices),
                set_by: "the glTF's meshes",
            });
        }
        parts
    }
}
