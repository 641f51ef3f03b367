//! Binning the contact shadows' fibre parts across the light: each part in every bin its
//! r-widened lateral box touches, listed in each bin by nearest depth first.

use super::{ContactShadows, MAX_BINS, Segment};
use crate::map::lateral_bins::list_by_depth;
use glam::Vec2;
use rayon::prelude::*;

impl ContactShadows {
    /// The bin rectangle of a lateral box widened by the fibre radius.
    #[inline]
    fn bin_rect(&self, lo: Vec2, hi: Vec2) -> Option<([usize; 2], [usize; 2])> {
        self.bin_rect_padded(lo, hi, self.radius_m)
    }

    /// The bin rectangle of a lateral box widened by `pad`.
    #[inline]
    pub(super) fn bin_rect_padded(
        &self,
        lo: Vec2,
        hi: Vec2,
        pad: f32,
    ) -> Option<([usize; 2], [usize; 2])> {
        let r = Vec2::splat(pad);
        let l = ((lo - r - self.origin) * self.inv_bin).floor();
        let h = ((hi + r - self.origin) * self.inv_bin).floor();
        if !(l.is_finite() && h.is_finite()) || h.x < 0.0 || h.y < 0.0 {
            return None;
        }
        let (dx, dy) = (self.dims[0] as f32, self.dims[1] as f32);
        if l.x >= dx || l.y >= dy {
            return None;
        }
        Some((
            [l.x.max(0.0) as usize, l.y.max(0.0) as usize],
            [h.x.min(dx - 1.0) as usize, h.y.min(dy - 1.0) as usize],
        ))
    }

    pub(super) fn seg_rect(&self, s: &Segment) -> Option<([usize; 2], [usize; 2])> {
        let (a, b) = (s.a, s.a + s.d);
        self.bin_rect(a.min(b), a.max(b))
    }

    /// The bin grid over the segments' widened projections; each segment cut into parts of at
    /// most a bin across and along the light (so a part lies in at most 2 × 2 bins, padded by
    /// r, and a window's scan skips whole parts), each bin sorted by nearest depth.
    pub(super) fn bin(&mut self, segments: Vec<Segment>, bin_m: f32) {
        let (mut lo, mut hi) = (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN));
        for s in &segments {
            lo = lo.min(s.a.min(s.a + s.d));
            hi = hi.max(s.a.max(s.a + s.d));
        }
        if segments.is_empty() {
            self.origin = Vec2::ZERO;
            self.inv_bin = 1.0;
            self.dims = [1, 1];
            self.bin_start = vec![0, 0];
            self.bin_items.clear();
            return;
        }
        let pad = Vec2::splat(self.radius_m + bin_m.max(1e-6));
        self.origin = lo - pad;
        let extent = hi + pad - self.origin;
        let bin = bin_m.max(1e-6).max(extent.max_element() / MAX_BINS);
        let dims = (extent / bin).ceil().max(Vec2::ONE);
        self.inv_bin = 1.0 / bin;
        self.dims = [dims.x as usize, dims.y as usize];
        // Parts tile their segment: each owns t ∈ [0, 1) of itself, as segments own theirs.
        self.segments = segments
            .par_iter()
            .flat_map_iter(|s| {
                let n = self.parts(s.d.length(), s.dx);
                let step = 1.0 / n as f32;
                (0..n).map(move |i| {
                    let t = i as f32 * step;
                    let d = s.d * step;
                    Segment {
                        a: s.a + s.d * t,
                        d,
                        inv_len: s.inv_len * n as f32,
                        x_a: s.x_a + s.dx * t,
                        dx: s.dx * step,
                        ..*s
                    }
                })
            })
            .collect();
        self.max_dx = self
            .segments
            .iter()
            .map(|s| s.dx.abs())
            .fold(0.0f32, f32::max);
        let rects: Vec<_> = self.segments.par_iter().map(|s| self.seg_rect(s)).collect();
        // Ties (equal nearest depth) by index: a total order, so the bins do not depend on
        // the thread count.
        let segs = &self.segments;
        let (start, items) = list_by_depth(
            self.dims,
            segs.len(),
            |i| rects[i],
            |i| segs[i as usize].x_min(),
        );
        self.bin_items = items;
        self.bin_start = start;
    }
}
