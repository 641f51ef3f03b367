//! The placement floor: the exact reference against itself with each bundle's fibres turned by
//! other angles. No estimate that knows the render strands but not where their fibres lie can
//! read closer to one placement than another placement does.

use crate::accuracy::MapMeasurement;
use crate::accuracy::comparison::Comparison;
use crate::accuracy::reference::{exact_reference_placed, key_light};
use crate::engine::Engine;

/// The reference against itself: at the vertices `measured` sampled, the exact reference
/// with each bundle's fibres turned by other angles (`ExactInput::placement_seed` = each of
/// `seeds`, outside the measurement's own ensemble) compared with the measurement's reference,
/// as if it were a map. Against one placement (`placements` = 1) this is the floor below which
/// no estimate that knows the render strands but not where their fibres lie can go: at a
/// vertex the camera sees lit, a few fibres of its own bundle and its neighbours' decide its
/// light, and their places are the reference's construction. Against an ensemble it is how
/// far one real head of hair lies from the ensemble's mean. With one fibre per strand there is
/// nothing to place, and the comparison is exact (0). Costs one reference per seed.
pub fn placement_floor(
    engine: &Engine,
    measured: &MapMeasurement,
    seeds: &[u64],
) -> Vec<Comparison> {
    let light = key_light(engine);
    seeds
        .iter()
        .map(|&seed| {
            let placed =
                exact_reference_placed(&engine.style, engine.strands(), &engine.fiber, light, seed)
                    .light_at_vertices(&measured.vertices, &measured.footprint);
            Comparison::new(&measured.truth, &placed)
        })
        .collect()
}
