//! Fragment emission: a band's segments become fragments, one per pixel a segment covers in
//! front of the opaque depth and not behind nearer hair that already hides the pixel.
//!
//! What: [`emit_fragments`] walks a band's segments near to far (the reverse of their sort
//! keys, which run far to near by mid-point 1/depth, ties in input order), each over its rows
//! and, in a row, over the pixel centres its strip can reach: around the axis's crossing of
//! the row, within its reach across and along (`segment.rs` precomputes both). A fragment
//! ([`Frag`]) holds the pixel, the 1/depth at the pixel centre, its covered sub-samples and
//! their opacity (`cover.rs`), and its segment and place along it: its colour is looked up
//! when the fragments are grouped by pixel (`pixel_runs.rs`), so emission needs no colour and
//! can run before the hair is shaded (`seen.rs`).
//!
//! How: depth is 1/depth interpolated linearly along the segment in screen space (exact for
//! perspective) at the pixel centre, compared without a division as `(1/z)·z_buffer > 1`.
//! The pixel loop is branch-free: every visited centre writes a fragment into the next slot,
//! kept only where it is covered and in front (a hair crosses 1 to 3 centres a row, so a
//! branch per centre mispredicts often). Each kept fragment then updates the pixel's hiding
//! state (`hiding.rs`); a row, and a whole segment, whose pixels are all hidden nearer than
//! the segment is skipped without its loop.

use std::sync::atomic::{AtomicBool, Ordering};

use super::cover;
use super::cull::MARGIN;
use super::fast_float::{ceil_index, fmax, fmin};
use super::fibers::Fibers;
use super::hiding::Hiding;
use super::params::Params;
use super::samples::sample_reach;
use super::segment::{NO_FIBERS, Seg};

/// One segment's coverage of one pixel: 24 bytes. It holds where on its segment the pixel
/// centre lies instead of a colour, so fragments can be emitted before the hair is shaded and
/// take their colour when composited (their segment's `SegColors`).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Frag {
    /// Pixel index within the band.
    pub(super) pixel: u32,
    /// Bits of 1/depth at the pixel centre (positive, so they order like the value).
    pub(super) iz_bits: u32,
    /// Opacity over the sub-samples it covers, in (0, 1].
    pub(super) alpha: f32,
    /// The pixel's sub-samples it covers, one bit each (sample `4g + l` is lane l of
    /// `SAMPLE_X[g]`).
    pub(super) mask: u16,
    /// Its segment's place among the segments with fragments in its [`Emitted`] (whose
    /// `ids` give the segment's index in the draw call, [`Seg::k`]) and the pixel centre's
    /// place along the (clipped) segment, in [0, 1].
    pub(super) seg: u32,
    pub(super) t: f32,
}

/// A band's fragments as they are emitted, and the segments they come from.
///
/// Why a fragment names its segment by its place in `ids` rather than by the draw call's
/// index: each fragment's colours are looked up, and the draw call's table is 27 MB for the
/// dense preset. Read by the draw call's index, one random read per fragment missed the
/// caches (56% of compositing on dense); the band's own table (`band_colors`, one read per
/// segment) stays in L2.
#[derive(Debug, Default)]
pub(super) struct Emitted {
    pub(super) frags: Vec<Frag>,
    /// The draw call's index ([`Seg::k`]) of each segment that emitted a fragment, in
    /// emission order: a fragment's [`Frag::seg`] indexes it.
    pub(super) ids: Vec<u32>,
}

impl Emitted {
    pub(super) fn clear(&mut self) {
        self.frags.clear();
        self.ids.clear();
    }
}

/// One band's opaque depth, what fragments are emitted against: rows `row0 ..` of the
/// framebuffer, whole rows of [`Params::width`].
#[derive(Clone, Copy)]
pub(super) struct Rows<'a> {
    pub(super) row0: usize,
    pub(super) depth: &'a [f32],
}

/// A band's segments as emission reads them: `segs` gathered in emission order, their sort
/// `keys` far to near (the low 32 bits a position in `segs`), and the draw call's table of
/// [`Fibers`] (by [`Seg::fibers`]; empty without bundles).
#[derive(Clone, Copy)]
pub(super) struct BandSegs<'a> {
    pub(super) segs: &'a [Seg],
    pub(super) keys: &'a [u64],
    pub(super) fibers: &'a [Fibers],
}

/// Where a segment's fragments go: the band's opaque depth they are tested against, the
/// hiding state they update and the list they are appended to.
struct Target<'a, 'b> {
    rows: Rows<'a>,
    hiding: &'b mut Hiding,
    frags: &'b mut Vec<Frag>,
}

/// Appends to `out` one fragment per pixel of the band (`rows`) whose sub-samples a segment
/// of `band` covers and whose centre it passes nearer than the opaque depth and not behind
/// nearer hair that already hides the pixel (`hiding`, reset here): segments in reverse key
/// order (near to far), pixels in row order within a segment; and the index ([`Seg::k`]) of
/// each segment that keeps one to `out.ids`.
///
/// With `seen = Some((flags, at_most))`, `flags[k]` is also set for each segment ([`Seg::k`])
/// that keeps a fragment, and `out.frags` holds at most `at_most` fragments plus one
/// segment's: past that it is emptied and the pass goes on for the flags alone. Returns
/// whether `out.frags` holds every kept fragment (always without `seen`).
pub(super) fn emit_fragments(
    p: &Params,
    band: BandSegs,
    rows: Rows,
    hiding: &mut Hiding,
    out: &mut Emitted,
    seen: Option<(&[AtomicBool], usize)>,
) -> bool {
    let Emitted { frags, ids } = out;
    hiding.reset(rows.depth.len(), p.width);
    let mut to = Target {
        rows,
        hiding,
        frags,
    };
    let mut whole = true;
    for &key in band.keys.iter().rev() {
        let Some(s) = band.segs.get((key & 0xFFFF_FFFF) as usize) else {
            continue;
        };
        if to.hiding.hides(s) {
            continue;
        }
        let before = to.frags.len();
        emit_one(p, s, ids.len() as u32, band.fibers, &mut to);
        let kept = to.frags.len() > before;
        if kept {
            ids.push(s.k);
        }
        if let Some((flags, at_most)) = seen {
            if kept && let Some(flag) = flags.get(s.k as usize) {
                flag.store(true, Ordering::Relaxed);
            }
            if to.frags.len() > at_most {
                to.frags.clear();
                whole = false;
            }
        }
    }
    whole
}

/// [`emit_fragments`] for segment `s`, the band's `id`th with fragments: its coverage model
/// chosen once (a bundle's fibres with mitred joints, or a plain band), so each pixel loop
/// is compiled for one.
#[inline(always)]
fn emit_one(p: &Params, s: &Seg, id: u32, fibers: &[Fibers], to: &mut Target) {
    let fib = match (p.bundle, s.fibers) {
        (Some(prof), k) if k != NO_FIBERS => fibers.get(k as usize).map(|f| (prof, *f)),
        _ => None,
    };
    match fib {
        Some((prof, f)) => {
            let cover = cover::fibers(prof, f, s);
            emit_segment(p, s, id, (f.ext0, f.ext1), cover, to);
        }
        None => {
            let cover = cover::plain(s);
            let ext = sample_reach(s.ux, s.uy);
            emit_segment(p, s, id, (ext, ext), cover, to);
        }
    }
}

/// [`emit_fragments`] for one segment: `cover(d, qx, ry, along)` gives a pixel's covered
/// sub-samples and their opacity (`cover.rs`); `ext` is how far past its ends a pixel centre
/// may be covered along the axis. Walks the segment's rows in the band, skipping those whose
/// visited pixels nearer hair hides in front of all of it.
#[inline(always)]
fn emit_segment<C: Fn(f32, f32, f32, f32) -> (u16, f32)>(
    p: &Params,
    s: &Seg,
    id: u32,
    (ext0, ext1): (f32, f32),
    cover: C,
    to: &mut Target,
) {
    let w = p.width;
    let rows = to.rows.depth.len() / w;
    let (row0, row_end) = (to.rows.row0, to.rows.row0 + rows);
    let last_col = (w - 1) as f32;
    // Along-axis extent in which a pixel centre can have coverage.
    let s_lo = if s.cap0 { -0.5f32.max(ext0) } else { -ext0 };
    let s_hi = s.len + if s.cap1 { 0.5f32.max(ext1) } else { ext1 };
    let (j0, j1) = (
        (s.row_lo as usize).max(row0),
        (s.row_hi as usize + 1).min(row_end),
    );
    let iz_near = s.iz0.max(s.iz1) * (1.0 + MARGIN);
    for j in j0..j1 {
        let ry = j as f32 + 0.5 - s.y0;
        let Some((i0, i1)) = row_columns(s, ry, (s_lo, s_hi), last_col) else {
            continue;
        };
        let row = (j - row0) * w;
        let (Some(depth), Some(cull)) = (
            to.rows.depth.get(row + i0..=row + i1),
            to.hiding.cull_row(row + i0..=row + i1),
        ) else {
            continue;
        };
        // Every centre of the row behind the hair that hides it: nothing to keep here (the
        // segment's nearest 1/depth with `cull.rs`'s margin over the interpolation).
        if cull.iter().all(|&c| c > iz_near) {
            continue;
        }
        let start = to.frags.len();
        let pixels = RowPixels {
            ry,
            i0,
            first: row + i0,
            depth,
            cull,
        };
        emit_row(s, id, &cover, pixels, to.frags);
        for f in to.frags.get(start..).unwrap_or_default() {
            to.hiding
                .add(f.pixel as usize, f32::from_bits(f.iz_bits), f.alpha, f.mask);
        }
    }
}

/// The columns, first and last, of the pixel centres segment `s` can cover in the row whose
/// centre lies `ry` below its first end: within its half span of the axis's crossing of the
/// row, and along the axis within `[s_lo, s_hi]` (± a hair of slack); `None` where none is
/// on the image (`last_col` its last column).
#[inline(always)]
fn row_columns(
    s: &Seg,
    ry: f32,
    (s_lo, s_hi): (f32, f32),
    last_col: f32,
) -> Option<(usize, usize)> {
    // Pixel centres x + 0.5 with |d(x)| ≤ reach: around the axis crossing of this row.
    let xc = s.x0 + ry * s.dxdy;
    let (mut xa, mut xb) = (xc - s.half_span, xc + s.half_span);
    // ... and with s(x) = ux·(x − x0) + uy·ry within [s_lo, s_hi].
    if s.inv_ux != 0.0 {
        let p0 = s.x0 + (s_lo - 0.01 - s.uy * ry) * s.inv_ux;
        let p1 = s.x0 + (s_hi + 0.01 - s.uy * ry) * s.inv_ux;
        xa = xa.max(p0.min(p1));
        xb = xb.min(p0.max(p1));
    }
    // Clamp in float before converting to indices (`max`/`min` also absorb ±inf).
    let (fa, fb) = ((xa - 0.5).max(0.0), (xb - 0.5).min(last_col));
    if !(fa <= fb) {
        return None;
    }
    // `fa` ≥ 0 and `fb` ≤ last column < 2³¹ here (framebuffer sizes are u32 and fit).
    Some((ceil_index(fa), fb as i32 as usize))
}

/// The pixels of one row a segment visits: the row's centre `ry` below the segment's first
/// end, the first column `i0` and its pixel index in the band, and the visited pixels'
/// opaque depths and cull depths (`hiding.rs`).
struct RowPixels<'a> {
    ry: f32,
    i0: usize,
    first: usize,
    depth: &'a [f32],
    cull: &'a [f32],
}

/// Appends a fragment for each pixel of `row` that segment `s` (the band's `id`th with
/// fragments) covers, nearer than the opaque surface and not behind the hair that hides the
/// pixel. Branch-free: every centre writes the next slot, kept only where it passes.
#[inline(always)]
fn emit_row<C: Fn(f32, f32, f32, f32) -> (u16, f32)>(
    s: &Seg,
    id: u32,
    cover: &C,
    row: RowPixels,
    frags: &mut Vec<Frag>,
) {
    let ry = row.ry;
    let mut rx = row.i0 as f32 + 0.5 - s.x0;
    let mut n = frags.len();
    frags.resize(n + row.depth.len(), Frag::default());
    for ((px, &z), &c) in (row.first..).zip(row.depth).zip(row.cull) {
        let qx = rx;
        rx += 1.0;
        let d = s.ux * ry - s.uy * qx;
        let along = s.ux * qx + s.uy * ry;
        let (mask, alpha) = cover(d, qx, ry, along);
        let t = fmin(fmax(along * s.inv_len, 0.0), 1.0);
        let iz = s.iz0 + (s.iz1 - s.iz0) * t;
        // Covered, nearer than the opaque surface (1/z_hair > 1/z_buffer, without a
        // division), and not behind the hair that hides the pixel.
        let keep = (alpha > 0.0) & (mask != 0) & (iz * z > 1.0) & (iz >= c);
        if let Some(slot) = frags.get_mut(n) {
            *slot = Frag {
                pixel: px as u32,
                // 1/z > 0 where kept (it beat the opaque depth), so its bits order like
                // its value.
                iz_bits: iz.to_bits(),
                // The box overlap can exceed 1 by float rounding (a few 1e-7 for wide
                // lines); α must stay in [0, 1].
                alpha: fmin(alpha, 1.0),
                mask,
                seg: id,
                t,
            };
        }
        n += usize::from(keep);
    }
    frags.truncate(n);
}

#[cfg(test)]
mod tests;
