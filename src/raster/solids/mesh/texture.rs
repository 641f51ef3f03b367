//! A mesh's texture and its sampling: bilinear, with repeat wrapping, texel centres at
//! half-integers (glTF's default sampler).

use glam::{Vec2, Vec3};

/// A texture: linear RGB texels, rows top to bottom.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Texture {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<Vec3>,
}

impl Texture {
    /// Bilinear sample at `uv` with repeat wrapping; texel centres at half-integers (glTF's
    /// default sampler). A malformed texture or non-finite coordinates read white / texel 0.
    #[inline]
    pub fn sample(&self, uv: Vec2) -> Vec3 {
        let (w, h) = (self.width as i64, self.height as i64);
        if w == 0 || h == 0 || self.texels.len() as i64 != w * h {
            return Vec3::ONE;
        }
        let uv = if uv.is_finite() && uv.abs().max_element() < 1e6 {
            uv - uv.floor()
        } else {
            Vec2::ZERO
        };
        let (x, y) = (uv.x * w as f32 - 0.5, uv.y * h as f32 - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let at = |i: i64, j: i64| self.texels[(j.rem_euclid(h) * w + i.rem_euclid(w)) as usize];
        let (i, j) = (x0 as i64, y0 as i64);
        let top = at(i, j).lerp(at(i + 1, j), fx);
        let bottom = at(i, j + 1).lerp(at(i + 1, j + 1), fx);
        top.lerp(bottom, fy)
    }
}

#[cfg(test)]
mod tests;
