//! Seconds each stage of a frame took, as the engine measures them around its passes.

/// Seconds spent in each stage of one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageTimings {
    pub animation_s: f64,
    pub simulation_s: f64,
    pub interpolation_s: f64,
    /// The hair map, the occluders and the skin texture ([`MapPartTimings`]).
    pub map_s: f64,
    /// Finding the hair the raster will draw, and shading it.
    pub shading_s: f64,
    /// The solids, and compositing the hair.
    pub raster_s: f64,
}

impl StageTimings {
    pub const NAMES: [&'static str; 6] = [
        "animation",
        "simulation",
        "interpolation",
        "map",
        "shading",
        "raster",
    ];

    pub fn as_array(&self) -> [f64; 6] {
        [
            self.animation_s,
            self.simulation_s,
            self.interpolation_s,
            self.map_s,
            self.shading_s,
            self.raster_s,
        ]
    }

    fn from_array(a: [f64; 6]) -> Self {
        StageTimings {
            animation_s: a[0],
            simulation_s: a[1],
            interpolation_s: a[2],
            map_s: a[3],
            shading_s: a[4],
            raster_s: a[5],
        }
    }

    pub fn total_s(&self) -> f64 {
        self.as_array().iter().sum()
    }

    pub fn add(&mut self, o: &StageTimings) {
        let (a, b) = (self.as_array(), o.as_array());
        *self = Self::from_array(std::array::from_fn(|i| a[i] + b[i]));
    }

    pub fn scaled(&self, k: f64) -> StageTimings {
        Self::from_array(self.as_array().map(|v| v * k))
    }
}

/// Seconds spent in each part of the map stage of one frame (next to nothing for a part whose
/// inputs did not change, so it kept what it had).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MapPartTimings {
    /// The hair's light maps (fill, sorts, merge and sweep; contact shadows' bins when on).
    pub hair_s: f64,
    /// The head's and body's entry depths across each light.
    pub occluders_s: f64,
    /// The skin's shadow texture (`map::surface`), when solids are drawn.
    pub surface_s: f64,
}

impl MapPartTimings {
    pub const NAMES: [&'static str; 3] = ["hair map", "occluders", "skin texture"];

    pub fn as_array(&self) -> [f64; 3] {
        [self.hair_s, self.occluders_s, self.surface_s]
    }

    /// The three parts together.
    pub fn total_s(&self) -> f64 {
        self.hair_s + self.occluders_s + self.surface_s
    }
}
