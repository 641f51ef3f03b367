//! glTF 2.0 animation samplers (spec §3.11 "Animations" and Appendix C "Interpolation"):
//! LINEAR, STEP and CUBICSPLINE over vec3 (translation, scale) and quaternion (rotation)
//! outputs.
//!
//! A [`Track`] holds its key times and values as `Vec4` (xyz + 0, or quaternion xyzw), so one
//! code path serves both kinds; a lookup is a binary search on the key times (the clip has a
//! few hundred keys at most, so caching the last segment would save nothing measurable).
//! Times before the first key or after the last one clamp to the end value.

use glam::{Quat, Vec3, Vec4};

/// How values between keys are computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// Linear interpolation; quaternions by spherical linear interpolation on the shortest arc.
    Linear,
    /// The value of the previous key holds until the next key.
    Step,
    /// Cubic Hermite spline with per-key in- and out-tangents (glTF Appendix C).
    CubicSpline,
}

/// Why a track could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TrackError {
    /// No keys.
    #[error("a track needs at least one key")]
    Empty,
    /// Values do not match the key count (CUBICSPLINE needs 3 values per key).
    #[error("{values} values for {keys} keys ({interpolation:?} needs {per_key} per key)")]
    CountMismatch {
        /// Number of keys.
        keys: usize,
        /// Number of values.
        values: usize,
        /// Values needed per key.
        per_key: usize,
        /// The interpolation.
        interpolation: Interpolation,
    },
    /// A key time is not finite or not after the previous one.
    #[error("key time {index} ({time_s} s) is not finite or not after the previous key")]
    BadTime {
        /// Key index.
        index: usize,
        /// The time in seconds.
        time_s: f32,
    },
    /// A value is NaN or infinite.
    #[error("value {index} is not finite")]
    BadValue {
        /// Value index.
        index: usize,
    },
}

/// One animated property: key times (seconds, strictly increasing) and values.
#[derive(Clone, Debug, PartialEq)]
pub struct Track {
    times_s: Vec<f32>,
    /// One per key (LINEAR, STEP) or (in-tangent, value, out-tangent) per key (CUBICSPLINE).
    values: Vec<Vec4>,
    interpolation: Interpolation,
}

impl Track {
    /// Builds a track; validates counts, times (finite, strictly increasing) and values.
    pub fn new(
        times_s: Vec<f32>,
        values: Vec<Vec4>,
        interpolation: Interpolation,
    ) -> Result<Track, TrackError> {
        if times_s.is_empty() {
            return Err(TrackError::Empty);
        }
        let per_key = if interpolation == Interpolation::CubicSpline {
            3
        } else {
            1
        };
        if values.len() != times_s.len() * per_key {
            return Err(TrackError::CountMismatch {
                keys: times_s.len(),
                values: values.len(),
                per_key,
                interpolation,
            });
        }
        for (index, &time_s) in times_s.iter().enumerate() {
            if !time_s.is_finite() || (index > 0 && time_s <= times_s[index - 1]) {
                return Err(TrackError::BadTime { index, time_s });
            }
        }
        if let Some(index) = values.iter().position(|v| !v.is_finite()) {
            return Err(TrackError::BadValue { index });
        }
        Ok(Track {
            times_s,
            values,
            interpolation,
        })
    }

    /// First and last key times in seconds.
    pub fn time_range_s(&self) -> (f32, f32) {
        // `new` guarantees at least one key.
        let first = self.times_s.first().copied().unwrap_or(0.0);
        let last = self.times_s.last().copied().unwrap_or(0.0);
        (first, last)
    }

    /// Applies a linear map to every stored value, tangents included: a map that is linear
    /// in the values (a rotation of translation keys, a quaternion premultiplied by a fixed
    /// one) commutes with every interpolation mode, so the track then samples as the mapped
    /// original. Values that come out non-finite are left as they were.
    pub(crate) fn map_values(&mut self, f: impl Fn(Vec4) -> Vec4) {
        for v in &mut self.values {
            let mapped = f(*v);
            if mapped.is_finite() {
                *v = mapped;
            }
        }
    }

    /// The interpolation mode.
    pub fn interpolation(&self) -> Interpolation {
        self.interpolation
    }

    /// Value (key index `k`) of a key, skipping CUBICSPLINE tangents.
    fn value(&self, k: usize) -> Vec4 {
        match self.interpolation {
            Interpolation::CubicSpline => self.values[3 * k + 1],
            _ => self.values[k],
        }
    }

    /// Segment containing `t_s`: key `k` and the fraction `u` in [0, 1] toward key `k + 1`,
    /// or `None` when `t_s` is outside the keys (the clamped key is returned instead).
    fn locate(&self, t_s: f32) -> Result<(usize, f32, f32), usize> {
        let n = self.times_s.len();
        let (first, last) = self.time_range_s();
        if n == 1 || t_s.is_nan() || t_s <= first {
            return Err(0);
        }
        if t_s >= last {
            return Err(n - 1);
        }
        // First key strictly after t; 1 ≤ i ≤ n − 1 here because first < t < last.
        let i = self.times_s.partition_point(|&x| x <= t_s);
        let k = i - 1;
        let dt_s = self.times_s[i] - self.times_s[k];
        Ok((k, (t_s - self.times_s[k]) / dt_s, dt_s))
    }

    /// Raw (un-normalised) interpolated Vec4 at `t_s`. `quat` selects the shortest arc for
    /// LINEAR.
    fn sample_raw(&self, t_s: f32, quat: bool) -> Vec4 {
        let (k, u, dt_s) = match self.locate(t_s) {
            Ok(seg) => seg,
            Err(k) => return self.value(k),
        };
        match self.interpolation {
            Interpolation::Step => self.value(k),
            Interpolation::Linear => {
                let (a, b) = (self.values[k], self.values[k + 1]);
                if quat {
                    Vec4::from(slerp_shortest(Quat::from_vec4(a), Quat::from_vec4(b), u))
                } else {
                    a.lerp(b, u)
                }
            }
            Interpolation::CubicSpline => {
                let v0 = self.values[3 * k + 1];
                let out0 = self.values[3 * k + 2];
                let in1 = self.values[3 * (k + 1)];
                let v1 = self.values[3 * (k + 1) + 1];
                hermite(v0, out0 * dt_s, v1, in1 * dt_s, u)
            }
        }
    }

    /// The vec3 value (translation in metres, or scale) at `t_s`.
    /// Heap bytes held (key times and values).
    pub fn held_bytes(&self) -> u64 {
        (self.times_s.len() * size_of::<f32>() + self.values.len() * size_of::<Vec4>()) as u64
    }

    /// Key times in seconds (strictly increasing).
    pub fn times_s(&self) -> &[f32] {
        &self.times_s
    }

    pub fn sample_vec3(&self, t_s: f32) -> Vec3 {
        self.sample_raw(t_s, false).truncate()
    }

    /// The unit quaternion at `t_s` (normalised; identity if the data degenerates to zero).
    pub fn sample_quat(&self, t_s: f32) -> Quat {
        let v = self.sample_raw(t_s, true);
        let len = v.length();
        if len > 1e-12 && len.is_finite() {
            Quat::from_vec4(v / len)
        } else {
            Quat::IDENTITY
        }
    }
}

/// Cubic Hermite spline (glTF Appendix C): value `p0` with scaled out-tangent `m0` at u = 0,
/// value `p1` with scaled in-tangent `m1` at u = 1. Tangents must already be multiplied by
/// the key interval (seconds), as the spec requires.
pub fn hermite(p0: Vec4, m0: Vec4, p1: Vec4, m1: Vec4, u: f32) -> Vec4 {
    let u2 = u * u;
    let u3 = u2 * u;
    p0 * (2.0 * u3 - 3.0 * u2 + 1.0)
        + m0 * (u3 - 2.0 * u2 + u)
        + p1 * (-2.0 * u3 + 3.0 * u2)
        + m1 * (u3 - u2)
}

/// Spherical linear interpolation along the shorter arc: `b` is negated when `a·b < 0` (q and
/// −q are the same rotation). Nearly parallel inputs fall back to normalised lerp, where slerp's
/// 1/sin(angle) would lose precision.
pub fn slerp_shortest(a: Quat, b: Quat, u: f32) -> Quat {
    let mut b4 = Vec4::from(b);
    let a4 = Vec4::from(a);
    let mut cos = a4.dot(b4);
    if cos < 0.0 {
        b4 = -b4;
        cos = -cos;
    }
    let v = if cos > 0.9995 {
        a4.lerp(b4, u)
    } else {
        let angle = cos.min(1.0).acos();
        let sin = angle.sin();
        a4 * (((1.0 - u) * angle).sin() / sin) + b4 * ((u * angle).sin() / sin)
    };
    Quat::from_vec4(v.normalize_or(Vec4::W))
}

#[cfg(test)]
mod tests;
