//! Where light paths start (`light_paths` module doc, step 2): a directional light's over the
//! columns across it that hair reaches, a point light's into the directions, within the cone
//! of the grid's bounding sphere, that hair subtends. A path anywhere else would cross no
//! fibre and leave no record; sending none there keeps every estimate's expectation and puts
//! all the paths where they count.

use super::cells::Cells;
use crate::light::Light;
use crate::rng::SplitMix64;
use glam::{Vec2, Vec3};

/// Where a path starts: a point, its unit direction and its power (W, RGB).
pub(super) type Emit = (Vec3, Vec3, Vec3);

/// How a light sends paths into the grid: each path's start from its random numbers, with
/// power so that all of them carry the light's whole flux through the hair.
pub(super) struct Emitter {
    origin: Vec3,
    axis: Vec3,
    /// Each path's power, W (RGB).
    power: Vec3,
    kind: Kind,
}

enum Kind {
    /// From the columns across the light that hair reaches (`footprint`), a grid's
    /// diagonal in front of its centre.
    Plane {
        a: Vec3,
        b: Vec3,
        footprint: Footprint,
        back: f32,
    },
    /// From the point, into the directions of the cone around the grid's bounding sphere (the
    /// whole sphere for a light inside it) that a cell holding fibre subtends (`footprint`).
    Cone {
        frame: (Vec3, Vec3),
        /// 1 − cos of the cone's half-angle, kept apart from the cosine: for a light
        /// 20 m from a grid of 1 cm radius it is 1.3e-7, two steps of an f32 near 1.
        one_minus_cos_max: f32,
        footprint: ConeFootprint,
    },
}

impl Emitter {
    /// `light`'s paths into the grid of `cells`, `paths` of them. `None` when the light cannot
    /// reach the hair.
    pub(super) fn new(cells: &Cells, light: &Light, paths: u32) -> Option<Emitter> {
        let size = cells.dims.as_vec3() * cells.cell_m;
        let centre = cells.origin + 0.5 * size;
        let n = paths.max(1) as f32;
        let emitter = match *light {
            Light::Directional { travel, irradiance } => {
                Self::plane(cells, centre, travel.get(), irradiance, n)?
            }
            Light::Point {
                position_m,
                intensity,
            } => Self::cone(cells, centre, position_m, intensity, n)?,
        };
        (emitter.power.is_finite() && emitter.axis.is_finite()).then_some(emitter)
    }

    /// A directional light travelling along unit `d` with `irradiance`: `n` paths over the
    /// columns across it that hair reaches, each with E·A/n for the columns' area A, from a
    /// grid's diagonal in front of the grid's `centre`.
    fn plane(cells: &Cells, centre: Vec3, d: Vec3, irradiance: Vec3, n: f32) -> Option<Emitter> {
        let (a, b) = d.any_orthonormal_pair();
        let footprint = Footprint::new(cells, centre, a, b)?;
        let back = (cells.dims.as_vec3() * cells.cell_m).length();
        Some(Emitter {
            origin: centre,
            axis: d,
            power: irradiance * (footprint.area_m2() / n),
            kind: Kind::Plane {
                a,
                b,
                footprint,
                back,
            },
        })
    }

    /// A point light at `position_m` with `intensity`: `n` paths into the directions of the
    /// cone of the grid's bounding sphere (about the grid's `centre`) that hair subtends, each
    /// with I·Ω/n for their solid angle Ω.
    fn cone(
        cells: &Cells,
        centre: Vec3,
        position_m: Vec3,
        intensity: Vec3,
        n: f32,
    ) -> Option<Emitter> {
        let to = centre - position_m;
        let (dist, radius) = (
            to.length(),
            0.5 * (cells.dims.as_vec3() * cells.cell_m).length(),
        );
        if !(dist.is_finite() && radius > 0.0) {
            return None;
        }
        // A light among the hair (inside the grid's bounding sphere) sends into the whole
        // sphere of directions: 1 − cos θmax = 2. The axis and 1 − cos θmax are chosen by two
        // selects, not as one tuple: with the tuple, the release build (rustc 1.95,
        // `-C target-cpu=x86-64-v2`) once returned the axis with its y lane zeroed (the x86
        // backend reloaded a spilled `axis.xy` with `movss`). Keep the two selects;
        // `tests.rs` checks the axis in every lane (it fails on the tuple form where seen).
        let inside = !(dist > radius);
        let axis = if inside { Vec3::Z } else { to / dist };
        // 1 − √(1 − s²) = s² / (1 + √(1 − s²)), without the cancellation.
        let s2 = (radius / dist).powi(2);
        let one_minus_cos_max = if inside {
            2.0
        } else {
            s2 / (1.0 + (1.0 - s2).max(0.0).sqrt())
        };
        let frame = axis.any_orthonormal_pair();
        let cone = Cone {
            light_m: position_m,
            axis,
            frame,
            one_minus_cos_max,
        };
        let footprint = ConeFootprint::new(cells, &cone, radius)?;
        let solid_angle = std::f32::consts::TAU * one_minus_cos_max * footprint.share_of_cone();
        Some(Emitter {
            origin: position_m,
            axis,
            power: intensity * (solid_angle / n),
            kind: Kind::Cone {
                frame,
                one_minus_cos_max,
                footprint,
            },
        })
    }

    /// A path's start: from the random numbers of `rng`.
    pub(super) fn emit(&self, rng: &mut SplitMix64) -> Emit {
        let (origin, axis, power) = (self.origin, self.axis, self.power);
        match &self.kind {
            Kind::Plane {
                a,
                b,
                footprint,
                back,
            } => {
                let q = footprint.sample(rng);
                let on_plane = origin + *a * q.x + *b * q.y;
                (on_plane - axis * *back, axis, power)
            }
            Kind::Cone {
                frame,
                one_minus_cos_max,
                footprint,
            } => {
                let Vec2 { x, y } = footprint.sample(rng);
                // cos θ = 1 − x(1 − cos θmax), uniform over the cone; sin θ from 1 − cos θ alone.
                let one_minus_cos = x * one_minus_cos_max;
                let cos = 1.0 - one_minus_cos;
                let sin = (one_minus_cos * (2.0 - one_minus_cos)).max(0.0).sqrt();
                let phi = std::f32::consts::TAU * y;
                let d = axis * cos + (frame.0 * phi.cos() + frame.1 * phi.sin()) * sin;
                (origin, d, power)
            }
        }
    }
}

/// A grid of `width` × `height` squares, some marked: where paths are sent. Both footprints
/// below draw from one of these.
struct Marked {
    width: u32,
    height: u32,
    /// The marked squares, `x + y · width`, ascending.
    squares: Vec<u32>,
}

impl Marked {
    /// The squares whose flag (row-major, `width` a row) is set; `None` when none is.
    fn from_flags(flags: &[bool], width: u32) -> Option<Marked> {
        let squares: Vec<u32> = (0..flags.len() as u32)
            .filter(|&k| flags[k as usize])
            .collect();
        (!squares.is_empty()).then_some(Marked {
            width,
            height: flags.len() as u32 / width.max(1),
            squares,
        })
    }

    /// Whether square (x, y) is marked.
    #[cfg(test)]
    fn holds(&self, x: u32, y: u32) -> bool {
        x < self.width && self.squares.binary_search(&(x + y * self.width)).is_ok()
    }

    /// The marked squares' share of the grid.
    fn share(&self) -> f32 {
        self.squares.len() as f32 / (self.width as f32 * self.height as f32)
    }

    /// A point uniform over the marked squares, in squares from the grid's corner.
    fn sample(&self, rng: &mut SplitMix64) -> Vec2 {
        let count = self.squares.len();
        let k = self.squares[((rng.open_unit_f64() * count as f64) as usize).min(count - 1)];
        let square = Vec2::new((k % self.width) as f32, (k / self.width) as f32);
        square + Vec2::new(rng.unit(), rng.unit())
    }
}

/// The columns across a directional light, a cell wide, that some cell holding fibre
/// reaches: a path anywhere else crosses no fibre and leaves no record, so none is sent
/// there, and the paths' power is the columns' area over their number. Exact, not an
/// approximation: a cell is marked over the whole square its cube's projection fits in.
struct Footprint {
    /// Plane coordinates (along `a`, `b` of [`Emitter`], metres from the grid's centre) of
    /// column (0, 0)'s corner.
    lo: Vec2,
    tile_m: f32,
    columns: Marked,
}

impl Footprint {
    fn new(cells: &Cells, centre: Vec3, a: Vec3, b: Vec3) -> Option<Footprint> {
        let size = cells.dims.as_vec3() * cells.cell_m;
        let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
        for k in 0..8 {
            let corner = cells.origin
                + size * Vec3::new((k & 1) as f32, ((k >> 1) & 1) as f32, ((k >> 2) & 1) as f32);
            let q = Vec2::new((corner - centre).dot(a), (corner - centre).dot(b));
            lo = lo.min(q);
            hi = hi.max(q);
        }
        let tile_m = cells.cell_m;
        let columns = ((hi - lo) / tile_m).ceil().max(Vec2::ONE);
        if !(columns.x * columns.y <= u32::MAX as f32) {
            return None;
        }
        let (columns_x, columns_y) = (columns.x as u32, columns.y as u32);
        let mut marked = vec![false; (columns_x * columns_y) as usize];
        // A cube of edge e projects within e/2 · (|v.x| + |v.y| + |v.z|) of its centre's
        // projection along unit v; widened by a thousandth of a column for rounding.
        let half = 0.5 * cells.cell_m;
        let reach = Vec2::new(half * a.abs().element_sum(), half * b.abs().element_sum())
            + Vec2::splat(1e-3 * tile_m);
        for i in cells.filled() {
            let c = cells.origin + (cells.coords(i).as_vec3() + 0.5) * cells.cell_m - centre;
            let q = Vec2::new(c.dot(a), c.dot(b)) - lo;
            // Clamped to the grid (a centre on its far edge would floor past it).
            let last = columns - Vec2::ONE;
            let from = ((q - reach) / tile_m).floor().max(Vec2::ZERO).min(last);
            let to = ((q + reach) / tile_m).floor().max(from).min(last);
            for y in from.y as u32..=to.y as u32 {
                let row = (y * columns_x) as usize;
                marked[row + from.x as usize..=row + to.x as usize].fill(true);
            }
        }
        Some(Footprint {
            lo,
            tile_m,
            columns: Marked::from_flags(&marked, columns_x)?,
        })
    }

    fn area_m2(&self) -> f32 {
        self.columns.squares.len() as f32 * self.tile_m * self.tile_m
    }

    /// A point uniform over the marked columns (plane coordinates, metres).
    fn sample(&self, rng: &mut SplitMix64) -> Vec2 {
        self.lo + self.columns.sample(rng) * self.tile_m
    }
}

/// A point light's cone of directions toward the grid: direction (x, y) ∈ [0, 1)² has
/// 1 − cos θ = x (1 − cos θmax) from `axis` (so x is uniform in solid angle) and azimuth
/// 2πy from `frame.0` toward `frame.1`.
struct Cone {
    light_m: Vec3,
    axis: Vec3,
    frame: (Vec3, Vec3),
    one_minus_cos_max: f32,
}

impl Cone {
    /// (x, y) of the direction from the light to `p` (x may exceed 1 outside the cone), and
    /// its polar angle.
    fn coordinates(&self, p: Vec3) -> (Vec2, f32) {
        let v = p - self.light_m;
        let theta = self.axis.cross(v).length().atan2(self.axis.dot(v));
        let half_sin = (0.5 * theta).sin();
        let x = 2.0 * half_sin * half_sin / self.one_minus_cos_max;
        let phi = v.dot(self.frame.1).atan2(v.dot(self.frame.0));
        let y = (phi / std::f32::consts::TAU).rem_euclid(1.0);
        (Vec2::new(x, y), theta)
    }
}

/// The directions of a point light's cone, in bins of equal solid angle, that a cell holding
/// fibre subtends: as [`Footprint`] for a directional light, a path sent anywhere else would
/// cross no fibre. Exact: a cell is marked over the box in (x, y) of the cap its bounding
/// sphere subtends.
struct ConeFootprint {
    /// Bins in x and in y, `bins.width` each way.
    bins: Marked,
}

impl ConeFootprint {
    fn new(cells: &Cells, cone: &Cone, grid_radius_m: f32) -> Option<ConeFootprint> {
        // About a cell per bin across the grid's bounding sphere.
        let bins = ((2.0 * grid_radius_m / cells.cell_m).ceil() as u32).clamp(8, 512);
        let mut marked = vec![false; (bins * bins) as usize];
        // A cube's bounding sphere, widened by a thousandth for rounding.
        let cell_radius = 0.5 * 3f32.sqrt() * cells.cell_m * 1.001;
        let (n, slack) = (bins as f32, 1e-3);
        for i in cells.filled() {
            let c = cells.origin + (cells.coords(i).as_vec3() + 0.5) * cells.cell_m;
            let dist = (c - cone.light_m).length();
            let (q, theta_c) = cone.coordinates(c);
            if !(dist > cell_radius && q.is_finite()) {
                // The light is inside the cell's sphere: every direction may meet it.
                marked.fill(true);
                break;
            }
            let alpha = (cell_radius / dist).asin();
            // x grows with θ up to π (the far pole), where a cap that crosses it ends.
            let x_of = |theta: f32| {
                let h = (0.5 * theta.clamp(0.0, std::f32::consts::PI)).sin();
                2.0 * h * h / cone.one_minus_cos_max
            };
            let x0 = (x_of(theta_c - alpha) * n - slack)
                .floor()
                .max(0.0)
                .min(n - 1.0);
            let x1 = (x_of(theta_c + alpha) * n + slack)
                .floor()
                .max(x0)
                .min(n - 1.0);
            let (x0, x1) = (x0 as usize, x1 as usize);
            // The cap's azimuths: all of them when it holds the axis or the far pole (then
            // sin θc ≤ sin α), else within asin(sin α / sin θc) of its centre's.
            let spread = if theta_c > alpha {
                (alpha.sin() / theta_c.sin()).min(1.0).asin()
            } else {
                std::f32::consts::PI
            };
            let (y0, y1) = if spread >= 0.5 * std::f32::consts::PI {
                (0, bins as i64 - 1)
            } else {
                let half = spread / std::f32::consts::TAU * n + slack;
                (
                    (q.y * n - half).floor() as i64,
                    (q.y * n + half).floor() as i64,
                )
            };
            for y in y0..=y1 {
                let row = y.rem_euclid(bins as i64) as usize * bins as usize;
                marked[row + x0..=row + x1].fill(true);
            }
        }
        Some(ConeFootprint {
            bins: Marked::from_flags(&marked, bins)?,
        })
    }

    /// The marked bins' share of the cone's solid angle.
    fn share_of_cone(&self) -> f32 {
        self.bins.share()
    }

    /// A direction's (x, y), uniform in solid angle over the marked bins.
    fn sample(&self, rng: &mut SplitMix64) -> Vec2 {
        (self.bins.sample(rng) / self.bins.width as f32).min(Vec2::ONE)
    }
}

#[cfg(test)]
mod tests;
