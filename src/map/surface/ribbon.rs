//! A sample's piece of strand as the texture draws it: a ribbon across the light, the texels
//! it overlaps row by row and its deposit into a band of texel rows (the module doc of
//! `surface` for the whole).
//!
//! A ribbon from a along unit d for `len` texels, `half_w` either side, overlaps texel (x, y)
//! (centre c, offsets s = (c − a)·d along and t = (c − a)·d⊥ across) by the box-filter product
//!
//!   w = |(s − ½, s + ½) ∩ (0, len)| · |(t − ½, t + ½) ∩ (−half_w, half_w)|,
//!
//! and a texel of overlap w receives loss · w / Σw over the texel's area, so the ribbon
//! deposits exactly its piece's loss.

use glam::{Vec2, Vec3};

/// A sample's piece of strand drawn as a ribbon across the light, in texel coordinates: from
/// `a` along unit `dir` for `len` (≥ 1) texels, `half_w` either side, its depth along the
/// light (map metres) running from `depth.0` to `depth.1`, its crossings' losses Σ n(1 − ā_f)
/// times their cross-section (`loss`, m²; over a texel's area it is an optical depth; once
/// gathered, what a unit of overlap deposits per texel area) and its ribbon's summed box
/// overlap (the sum [`Piece::gather`] returns), so a texel of overlap w gets loss · w / sum
/// over its area: the whole ribbon deposits the piece's own.
#[derive(Clone, Copy, Debug)]
pub(super) struct Piece {
    pub(super) a: Vec2,
    pub(super) dir: Vec2,
    pub(super) len: f32,
    pub(super) half_w: f32,
    pub(super) depth: (f32, f32),
    pub(super) loss: Vec3,
    /// Where its gathered texels ([`Piece::gather`]) lie in its run's buffer
    /// (`waves.rs`).
    pub(super) texels: [u32; 2],
    /// Texel box the ribbon touches: rows `x0..x1`, columns `y0..y1`.
    pub(super) x0: u32,
    pub(super) x1: u32,
    pub(super) y0: u32,
    pub(super) y1: u32,
}

impl Piece {
    /// The ribbon from `a` to `b` (texel coordinates), or `None` when it touches no texel of a
    /// `dims` texture.
    pub(super) fn new(
        a: Vec2,
        b: Vec2,
        depth: (f32, f32),
        half_w: f32,
        dims: [usize; 2],
    ) -> Option<Piece> {
        let d = b - a;
        let len = d.length();
        // A piece seen end-on still covers its width along some direction: at least one texel.
        let (dir, len, a) = if len >= 1.0 {
            (d / len, len, a)
        } else {
            let dir = if len > 0.0 { d / len } else { Vec2::X };
            (dir, 1.0, 0.5 * (a + b) - dir * 0.5)
        };
        let reach = half_w + 1.0;
        let end = a + dir * len;
        let (lo, hi) = (
            a.min(end) - Vec2::splat(reach),
            a.max(end) + Vec2::splat(reach),
        );
        let x0 = lo.x.floor().max(0.0) as usize;
        let y0 = lo.y.floor().max(0.0) as usize;
        let x1 = (hi.x.ceil().max(0.0) as usize).min(dims[0]);
        let y1 = (hi.y.ceil().max(0.0) as usize).min(dims[1]);
        if x0 >= x1 || y0 >= y1 {
            return None;
        }
        Some(Piece {
            a,
            dir,
            len,
            half_w,
            depth,
            loss: Vec3::ZERO,
            texels: [0, 0],
            x0: x0 as u32,
            x1: x1 as u32,
            y0: y0 as u32,
            y1: y1 as u32,
        })
    }

    /// Texel (x, y)'s box overlap with the ribbon, and where the texel's centre projects on
    /// the ribbon's axis (texels from `a`; [`Piece::depth_at`] turns it into a depth).
    #[inline]
    pub(super) fn at(&self, x: usize, y: usize) -> (f32, f32) {
        let overlap = |c: f32, lo: f32, hi: f32| ((c + 0.5).min(hi) - (c - 0.5).max(lo)).max(0.0);
        let q = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) - self.a;
        let s = q.dot(self.dir);
        let w =
            overlap(s, 0.0, self.len) * overlap(q.dot(self.dir.perp()), -self.half_w, self.half_w);
        (w, s)
    }

    /// The piece's depth along the light (map metres) at axis position `s` (from [`Piece::at`]),
    /// asked only where a texel overlaps: the division is skipped for the rest.
    #[inline]
    pub(super) fn depth_at(&self, s: f32) -> f32 {
        let t = (s / self.len).clamp(0.0, 1.0);
        self.depth.0 + (self.depth.1 - self.depth.0) * t
    }

    /// The two strips of [`Piece::row_span`], prepared once per piece.
    #[inline]
    pub(super) fn strips(&self) -> [Strip; 2] {
        let (dx, dy) = (self.dir.x, self.dir.y);
        [
            // Along: s = qx·dx + qy·dy in (−½, len + ½).
            Strip::new(dx, dy, -0.5, self.len + 0.5),
            // Across: d = −qx·dy + qy·dx in (−half_w − ½, half_w + ½).
            Strip::new(-dy, dx, -self.half_w - 0.5, self.half_w + 0.5),
        ]
    }

    /// The columns `y` of row `x` whose texel centre can overlap the ribbon (strictly within
    /// half a texel of it along and across, where [`Piece::at`] gives a positive overlap): the
    /// intersection of two open strips ([`Piece::strips`]), each an interval in y, widened by
    /// more than the rounding of either computation, so no texel with overlap is left out and
    /// at most one without it is visited at each end. (A texel visited without overlap adds
    /// +0 to the ribbon's sum and is not kept: the spans may change, the sums cannot.)
    #[inline]
    pub(super) fn row_span(&self, x: usize, strips: &[Strip; 2]) -> std::ops::Range<usize> {
        let qx = x as f32 + 0.5 - self.a.x;
        let mut lo = f32::NEG_INFINITY;
        let mut hi = f32::INFINITY;
        for st in strips {
            let c = qx * st.per_qx;
            if st.steep {
                let (u, v) = ((st.from - c) * st.inv_k, (st.to - c) * st.inv_k);
                let slack = st.slack + st.slack_per_c * c.abs();
                lo = lo.max(u.min(v) - slack);
                hi = hi.min(u.max(v) + slack);
            } else if !(c > st.from && c < st.to) {
                hi = f32::NEG_INFINITY;
            }
        }
        if lo.is_nan() || hi.is_nan() || lo > hi {
            return 0..0;
        }
        // Texel y's centre is at qy = y + ½ − a.y: the texels strictly inside are the integers
        // in (lo, hi) + a.y − ½.
        let to_y = |qy: f32| qy + self.a.y - 0.5;
        let y0 = ((to_y(lo).floor() + 1.0).max(self.y0 as f32)) as usize;
        let y1 = (to_y(hi).ceil().min(self.y1 as f32)).max(0.0) as usize;
        y0..y1.max(y0)
    }

    /// Sum of the overlaps over the texels the ribbon touches, rows then columns: the order
    /// [`Piece::gather`] adds them in (its reference in the tests).
    #[cfg(test)]
    pub(super) fn overlap_sum(&self) -> f32 {
        let mut sum = 0.0;
        let strips = self.strips();
        for x in self.x0 as usize..self.x1 as usize {
            for y in self.row_span(x, &strips) {
                sum += self.at(x, y).0;
            }
        }
        sum
    }

    /// Visits the ribbon's texels once, rows then columns, in a texture of `cols` columns:
    /// appends to `out` each texel (row-major index) with a positive overlap where the
    /// ribbon's depth is at most the texel's `limit`, with that overlap, and returns the sum
    /// of the overlaps over all its texels (what normalises its deposit).
    pub(super) fn gather(&self, cols: usize, limit: &[f32], out: &mut Vec<(u32, f32)>) -> f32 {
        let mut sum = 0.0;
        let strips = self.strips();
        for x in self.x0 as usize..self.x1 as usize {
            for y in self.row_span(x, &strips) {
                let (w, along) = self.at(x, y);
                sum += w;
                let k = x * cols + y;
                if w > 0.0 && self.depth_at(along) <= limit[k] {
                    out.push((k as u32, w));
                }
            }
        }
        sum
    }
}

/// One strip of a ribbon across a row of texels ([`Piece::row_span`]): the texel centres
/// with `qx·per_qx + qy·k` in (`from`, `to`), qx and qy the centre's offset from the ribbon's
/// start.
///
/// Why reciprocals: four divisions a row for the spans and two more for their slack cost 21%
/// of curly's texture. A product by `1/k` is within an ulp or two of the quotient, and the slack
/// (a hundredth of a texel, plus 1e-5 of the magnitudes over |k|) is 80 times that.
pub(super) struct Strip {
    per_qx: f32,
    /// Whether |k| > 1e-6: else the strip does not depend on y, and holds the row or not.
    steep: bool,
    inv_k: f32,
    from: f32,
    to: f32,
    /// The slack is `slack + slack_per_c · |qx·per_qx|`.
    slack: f32,
    slack_per_c: f32,
}

impl Strip {
    fn new(per_qx: f32, k: f32, from: f32, to: f32) -> Strip {
        let steep = k.abs() > 1e-6;
        let inv_k = if steep { 1.0 / k } else { 0.0 };
        // A hundredth of a texel, plus far more than the rounding of from − c (a few ulps of
        // the larger) magnified by the division.
        let per = 1e-5 * inv_k.abs();
        Strip {
            per_qx,
            steep,
            inv_k,
            from,
            to,
            slack: 1e-2 + per * (from.abs() + to.abs() + 1.0),
            slack_per_c: per,
        }
    }
}

/// Adds a ribbon's gathered `texels` (row-major index, overlap) that lie in `band` (rows) to
/// `rows` (the band's texels, `cols` per row): `per` × the overlap each, `per` being the
/// piece's loss ÷ its overlap sum, per texel area.
pub(super) fn deposit(
    per: Vec3,
    texels: &[(u32, f32)],
    band: std::ops::Range<usize>,
    cols: usize,
    rows: &mut [Vec3],
) {
    let (first, end) = ((band.start * cols) as u32, (band.end * cols) as u32);
    // The texels are in row-major order: those of earlier bands first.
    let from = texels.partition_point(|&(k, _)| k < first);
    for &(k, w) in texels[from..].iter().take_while(|&&(k, _)| k < end) {
        rows[(k - first) as usize] += per * w;
    }
}
