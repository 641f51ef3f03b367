//! Tests of the surface texture: ribbons, their sums and deposits, their row spans, and the
//! tiles that drop ribbons behind the solids.

use super::limits::LimitTiles;
use super::ribbon::deposit;
use super::*;

/// Ribbons of several lengths, widths, angles and sub-texel offsets, in a texture of
/// 3 bands × 40 columns.
fn ribbons() -> Vec<Piece> {
    let dims = [3 * BAND_ROWS, 40];
    let mut out = Vec::new();
    for (k, angle_deg) in [0.0f32, 7.0, 33.0, 45.0, 80.0, 90.0, 137.0]
        .iter()
        .enumerate()
    {
        for len in [0.3f32, 1.0, 4.5, 9.0] {
            for half_w in [0.2f32, 1.15, 3.0] {
                let dir = Vec2::from_angle(angle_deg.to_radians());
                let a = Vec2::new(BAND_ROWS as f32 * 0.5 + 0.37, 20.0 + 0.21 * k as f32)
                    - dir * (0.5 * len);
                let mut p = Piece::new(a, a + dir * len, (0.1, 0.3), half_w, dims).unwrap();
                p.loss = Vec3::new(0.3, 0.5, 0.9);
                out.push(p);
            }
        }
    }
    out
}

#[test]
fn a_ribbon_gathers_its_overlapping_texels_in_front_and_the_sum_of_all() {
    // Gathering visits each texel once: its sum must be the plain sum over the row spans, and
    // over the whole box, to the bit, and it must keep exactly the texels of positive overlap at most as deep as the limit
    // (found here by a brute-force walk over the ribbon's whole box).
    let dims = [3 * BAND_ROWS, 40];
    let blocks: Vec<f32> = (0..16 * 14).map(|i| [0.15, 0.25, 0.7][i % 3]).collect();
    let limit = block_limits(dims, &blocks);
    let mut gathered = Vec::new();
    let mut kept = 0;
    for piece in ribbons() {
        gathered.clear();
        let sum = piece.gather(dims[1], &limit, &mut gathered);
        assert_eq!(sum.to_bits(), piece.overlap_sum().to_bits(), "{piece:?}");
        let mut expected = Vec::new();
        let mut box_sum = 0.0f32;
        for x in piece.x0 as usize..piece.x1 as usize {
            for y in piece.y0 as usize..piece.y1 as usize {
                let (w, along) = piece.at(x, y);
                box_sum += w;
                let k = x * dims[1] + y;
                if w > 0.0 && piece.depth_at(along) <= limit[k] {
                    expected.push((k as u32, w));
                }
            }
        }
        assert_eq!(gathered, expected, "{piece:?}");
        // The texels a span visits beyond the overlap add +0: the sum over the whole box, in
        // the same order, is the same bits, whatever the spans.
        assert_eq!(sum.to_bits(), box_sum.to_bits(), "{piece:?}");
        kept += gathered.len();
    }
    assert!(kept > 100, "only {kept} texels kept");
}

/// A `dims` limit field of 3 × 3-texel blocks (not aligned with the tiles) from `blocks`,
/// a value above 0.6 standing for no solid (an infinite limit).
fn block_limits(dims: [usize; 2], blocks: &[f32]) -> Vec<f32> {
    let block_cols = dims[1].div_ceil(3);
    let mut limit = Vec::with_capacity(dims[0] * dims[1]);
    for x in 0..dims[0] {
        for y in 0..dims[1] {
            let v = blocks[(x / 3) * block_cols + y / 3];
            limit.push(if v > 0.6 { f32::INFINITY } else { v });
        }
    }
    limit
}

/// What `piece` deposits band by band into a `dims` texture with `limit`, over texels of
/// area 1 / `inv_texel_area`.
fn deposited(piece: &Piece, dims: [usize; 2], limit: &[f32], inv_texel_area: f32) -> Vec<Vec3> {
    let mut texels = Vec::new();
    let sum = piece.gather(dims[1], limit, &mut texels);
    let per = piece.loss * (inv_texel_area / sum);
    let mut out = Vec::new();
    for b in 0..dims[0].div_ceil(BAND_ROWS) {
        let band = b * BAND_ROWS..((b + 1) * BAND_ROWS).min(dims[0]);
        let mut rows = vec![Vec3::ZERO; band.len() * dims[1]];
        if sum > 0.0 {
            deposit(per, &texels, band, dims[1], &mut rows);
        }
        out.extend(rows);
    }
    out
}

proptest::proptest! {
    /// A piece the limit tiles call behind every solid deposits nothing, whatever its
    /// angle, length, width, depths and the field of limits (solids at any depth, holes
    /// with none): dropping it changes no texel.
    #[test]
    fn a_piece_the_tiles_call_behind_deposits_nothing(
        angle in 0f32..std::f32::consts::TAU,
        len in 0.3f32..12.0,
        half_w in 0.1f32..3.0,
        (ax, ay) in (2f32..46.0, 2f32..38.0),
        (d0, d1) in (0.3f32..0.8, 0.3f32..0.8),
        blocks in proptest::collection::vec(0.4f32..0.62, 16 * 14),
    ) {
        let dims = [48, 40];
        let limit = block_limits(dims, &blocks);
        let mut tiles = LimitTiles::default();
        tiles.build(&limit, dims);
        let a = Vec2::new(ax, ay);
        let Some(mut piece) =
            Piece::new(a, a + Vec2::from_angle(angle) * len, (d0, d1), half_w, dims)
        else {
            return Ok(());
        };
        piece.loss = Vec3::new(0.3, 0.5, 0.9);
        if tiles.behind_all(&piece) {
            let rows = deposited(&piece, dims, &limit, 1.0);
            proptest::prop_assert!(rows.iter().all(|v| *v == Vec3::ZERO), "{piece:?}");
        }
    }
}

#[test]
fn the_tiles_find_pieces_behind_a_wall_and_keep_those_in_front_or_over_a_hole() {
    // A wall at depth 0.5 over the whole texture but a hole of 8 × 8 texels: ribbons at
    // depth 0.6–0.7 away from the hole are dropped, the same ribbons at 0.3–0.4 or over
    // the hole are kept, and every kept one deposits something.
    let dims = [48, 40];
    let mut limit = vec![0.5f32; dims[0] * dims[1]];
    for x in 20..28 {
        for y in 16..24 {
            limit[x * dims[1] + y] = f32::INFINITY;
        }
    }
    let mut tiles = LimitTiles::default();
    tiles.build(&limit, dims);
    let ribbon = |a: Vec2, depth| {
        let mut p = Piece::new(a, a + Vec2::new(3.0, 1.0), depth, 1.0, dims).unwrap();
        p.loss = Vec3::ONE;
        p
    };
    let (far_from_hole, over_hole) = (Vec2::new(5.0, 5.0), Vec2::new(22.0, 18.0));
    assert!(tiles.behind_all(&ribbon(far_from_hole, (0.6, 0.7))));
    for p in [
        ribbon(far_from_hole, (0.3, 0.4)),
        ribbon(over_hole, (0.6, 0.7)),
        // Crossing the wall: its near end in front.
        ribbon(far_from_hole, (0.45, 0.7)),
    ] {
        assert!(!tiles.behind_all(&p), "{p:?}");
        let total: Vec3 = deposited(&p, dims, &limit, 1.0).iter().sum();
        assert!(total.min_element() > 0.0, "{p:?} deposits {total}");
    }
}

#[test]
fn a_ribbon_across_bands_deposits_its_whole_loss_band_by_band() {
    let dims = [3 * BAND_ROWS, 40];
    let limit = vec![f32::INFINITY; dims[0] * dims[1]];
    let mut across = 0;
    for mut piece in ribbons() {
        // Moved down by half a band, so the longer ribbons straddle a band's edge.
        piece.a.x += 0.5 * BAND_ROWS as f32;
        piece.x0 += BAND_ROWS as u32 / 2;
        piece.x1 += BAND_ROWS as u32 / 2;
        if piece.x0 as usize / BAND_ROWS == (piece.x1 as usize - 1) / BAND_ROWS {
            continue;
        }
        across += 1;
        let total: Vec3 = deposited(&piece, dims, &limit, 4.0).iter().sum();
        assert!(
            (total - piece.loss * 4.0).abs().max_element() < 1e-5,
            "{piece:?}: {total}"
        );
    }
    assert!(across >= 20, "only {across} ribbons across bands");
}

#[test]
fn a_row_span_holds_every_texel_with_overlap_and_little_else() {
    // Ribbons anywhere in a 1024² texture, at any angle (also within 1e-7 of an axis), of
    // any length and width: every texel of the box with a positive overlap must be in its
    // row's span (a texel left out would drop its share of the deposit), and the spans
    // visit at most two texels per row without overlap.
    let dims = [1024, 1024];
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 40) as f32 / (1u64 << 24) as f32
    };
    let (mut visited, mut overlapping, mut rows) = (0usize, 0usize, 0usize);
    for case in 0..4000 {
        let angle = match case % 4 {
            0 => next() * std::f32::consts::TAU,
            1 => (next() - 0.5) * 2e-6,
            2 => std::f32::consts::FRAC_PI_2 + (next() - 0.5) * 2e-6,
            _ => (next() * 8.0).round() * std::f32::consts::FRAC_PI_4,
        };
        let dir = Vec2::from_angle(angle);
        let a = Vec2::new(next(), next()) * 1000.0;
        let len = 0.2 + next() * 20.0;
        let half_w = 0.05 + next() * 4.0;
        let Some(p) = Piece::new(a, a + dir * len, (0.0, 1.0), half_w, dims) else {
            continue;
        };
        let strips = p.strips();
        for x in p.x0 as usize..p.x1 as usize {
            let span = p.row_span(x, &strips);
            rows += 1;
            visited += span.len();
            for y in p.y0 as usize..p.y1 as usize {
                if p.at(x, y).0 > 0.0 {
                    overlapping += 1;
                    assert!(span.contains(&y), "case {case}: texel ({x}, {y}) of {p:?}");
                }
            }
        }
    }
    assert!(
        visited <= overlapping + 2 * rows,
        "{visited} visits for {overlapping} overlapping texels in {rows} rows"
    );
}
