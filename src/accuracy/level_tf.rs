//! A quality level's light map against the exact reference of the whole hair: the key light's
//! forward transmittance T_f at vertices spread over the full groom, from the exact rays
//! ([`ensemble_light`]) and from the level's map read at the same world points.
//!
//! A level may draw other render strands than the full groom (`preview` keeps half of each
//! wisp's strands with twice the fibres), so the reference is always the full hair's, and a
//! level's map is judged by the light it gives where the real hair is. The caller draws both
//! from the same guides at the same time (`Engine::set_guide_state`), so the hair differs only
//! by what the level draws of it. Where the level has a sampled vertex at the same place
//! (same index, same point), the map is read there as the shader reads it without a camera,
//! with its contact shadows if it has them (as `measure_map` reads it); elsewhere at the point
//! alone ([`LightMap::light_at`]).
//!
//! [`LightMap::light_at`]: crate::map::LightMap::light_at

use crate::accuracy::comparison::Comparison;
use crate::accuracy::exact::Footprint;
use crate::accuracy::map_vs_reference::sampled_vertices;
use crate::accuracy::reference::{default_rays, ensemble_light, key_light, placements_used};
use crate::engine::Engine;
use crate::fiber::LightAtPoint;
use glam::Vec3;
use rayon::prelude::*;

/// The exact reference's light at vertices of the full hair, to compare levels' maps with.
#[derive(Clone, Debug)]
pub struct LevelTfReference {
    vertices: Vec<usize>,
    positions: Vec<Vec3>,
    truth: Vec<LightAtPoint>,
    placements: u32,
}

impl LevelTfReference {
    /// The reference at `vertices` vertices spread evenly over `full`'s hair (where it has
    /// fibres), under its key light, averaged over `placements` placements of each bundle's
    /// fibres (one for one-fibre strands: [`placements_used`]), with the rays of
    /// [`default_rays`] on the fibres. `full` is the engine drawing every strand, after its hair was
    /// placed for the time compared.
    pub fn new(full: &Engine, vertices: usize, placements: u32) -> Self {
        let verts = sampled_vertices(full, vertices);
        let placements = placements_used(&full.style, placements);
        let strands = full.strands();
        let truth = ensemble_light(
            &full.style,
            strands,
            &full.fiber,
            key_light(full),
            &verts,
            &Footprint::Fibers {
                rays: default_rays(placements),
            },
            placements,
        );
        LevelTfReference {
            positions: verts.iter().map(|&v| strands.positions[v]).collect(),
            vertices: verts,
            truth,
            placements,
        }
    }

    /// Vertices compared.
    pub fn vertices(&self) -> usize {
        self.vertices.len()
    }

    /// Placements the reference averages.
    pub fn placements(&self) -> u32 {
        self.placements
    }

    /// `level`'s key-light map read at the reference's points (the module doc), against the
    /// reference: the MAE of T_f and its biases.
    pub fn compare(&self, level: &Engine) -> Comparison {
        let map = level.map();
        let drawn = &level.strands().positions;
        let away = map.frame().x;
        let estimate: Vec<LightAtPoint> = self
            .vertices
            .par_iter()
            .zip(&self.positions)
            .map(|(&v, &p)| {
                if drawn.get(v) == Some(&p) {
                    map.light_at_vertex_seen(v, p, away, Vec3::X, 0.0)
                } else {
                    map.light_at(p)
                }
            })
            .collect();
        Comparison::new(&self.truth, &estimate)
    }
}
