//! A small deterministic random generator shared by the stages that draw numbers (strand
//! placement, light paths): results must not depend on a crate's version of its streams.
//!
//! SplitMix64 (Steele, Lea & Flood 2014): the state advances by the odd constant
//! γ = ⌊2⁶⁴/φ⌋ (φ the golden ratio), x_{n+1} = x_n + γ mod 2⁶⁴, and each number is a bijective
//! mix of the state, z ← (z ⊕ z≫30)·c₁, z ← (z ⊕ z≫27)·c₂, z ⊕ z≫31. Floats take the top bits:
//! [`SplitMix64::unit`] the top 24 (uniform in [0, 1), f32's mantissa), and
//! [`SplitMix64::open_unit_f64`] the top 53 plus a half, (k + ½)/2⁵³, which is never 0 nor 1
//! (a logarithm's argument). Independent streams for parallel blocks come from
//! [`SplitMix64::stream`].

/// SplitMix64's step: 2⁶⁴ over the golden ratio, odd.
const GOLDEN: u64 = 0x9E37_79B9_7F4A_7C15;

/// SplitMix64's output function (a bijection of the state).
fn mix(state: u64) -> u64 {
    let mut z = state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// SplitMix64 (Steele, Lea & Flood 2014): 64-bit state, one add and two multiply-xorshifts
/// per number.
pub struct SplitMix64(u64);

impl SplitMix64 {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// Independent stream number `index` of `seed`: its state is the seed's own output
    /// number `index`, a hashed word. Why not `new(seed ^ index · k)`: states that differ by a
    /// multiple of the step run the same numbers shifted, and with k the step itself blocks
    /// b and b + 4 of seed 3 draw the same sequence four numbers apart, so light paths traced
    /// from them fall into step and repeat (`tests::streams_do_not_repeat_each_other`).
    pub fn stream(seed: u64, index: u64) -> Self {
        let state = seed.wrapping_add(index.wrapping_add(1).wrapping_mul(GOLDEN));
        Self(mix(state))
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(GOLDEN);
        mix(self.0)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }
    /// Uniform in (0, 1), 53 bits: never 0 (a logarithm's argument) nor 1.
    pub fn open_unit_f64(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
}

#[cfg(test)]
mod tests;
