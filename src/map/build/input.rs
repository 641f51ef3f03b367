//! What the map is built from ([`MapBuildInput`]: render-strand samples, the fibre, the light)
//! and how its expected crossing counts become transmittance ([`CountModel`]).

use crate::fiber::Fiber;
use crate::map::MapLight;
use glam::Vec3;

/// How expected crossing counts become transmittance (see the module doc of `map`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CountModel {
    /// Average over Poisson-distributed crossings: T_f = exp(−n̄(1 − ā_f)), direct = exp(−n̄).
    #[default]
    Poisson,
    /// A ray meeting exactly the mean count: T_f = ā_f^n̄, direct = 0^n̄ read as exp(−n̄).
    MeanCount,
}

/// What the map is built from: render-strand samples (world) and the fibre they are made of.
pub struct MapBuildInput<'a> {
    /// Sample positions, metres (world).
    pub positions: &'a [Vec3],
    /// Unit tangents at the samples.
    pub tangents: &'a [Vec3],
    /// Hair length each sample stands for, metres, times its fibre share: the length of
    /// *fibre*, in units of the strand's F fibres (`StrandGeometry::lengths_m`).
    pub lengths_m: &'a [f32],
    /// Share of its strand's fibres present at each sample, in (0, 1]
    /// (`StrandGeometry::fibre_share`; missing entries count as 1). The piece of strand a
    /// sample stands for is `lengths_m / share` long: a tapered tip's fewer fibres still run
    /// along its whole piece, so its crossings are spread over that length, not packed into a
    /// shorter one.
    pub fiber_share: &'a [f32],
    /// Real fibres per render strand.
    pub fibers_per_strand: f32,
    /// The light's geometry: the direction it travels, or where a point light is.
    pub light: MapLight,
    /// The fibre (radius and forward-scattering statistics).
    pub fiber: &'a Fiber,
}

impl MapBuildInput<'_> {
    /// Length of strand sample `s` stands for, metres: `lengths_m[s] / fibre_share[s]` (the
    /// fibre length it fills, undone of the taper), or `lengths_m[s]` where the share is
    /// missing, not in (0, 1) or gives no finite length.
    #[inline]
    pub fn span_m(&self, s: usize) -> f32 {
        let len = self.lengths_m.get(s).copied().unwrap_or(0.0);
        match self.fiber_share.get(s) {
            Some(&share) if share > 0.0 && share < 1.0 && (len / share).is_finite() => len / share,
            _ => len,
        }
    }
}
