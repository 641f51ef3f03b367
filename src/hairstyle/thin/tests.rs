use super::*;
use crate::hairstyle::generate;

#[test]
fn a_third_keeps_the_first_strands_of_each_wisp_and_every_fibre() {
    let style = Hairstyle::default_smooth();
    let (_, layout) = generate(&style);
    let (thin_style, thin) = thin_strands(style.clone(), layout.clone(), 1.0 / 3.0);
    // 25 strands a wisp: ceil(25 / 3) = 9 kept.
    assert_eq!(thin_style.wisps.strands_per_wisp, 9);
    assert_eq!(thin.count(), 134 * 9);
    // The kept strands are the first 9 of each wisp, in order: the same weights, phases and
    // lengths as the full layout's.
    for w in 0..134 {
        for k in 0..9 {
            let (full, kept) = (w * 25 + k, w * 9 + k);
            assert_eq!(thin.strand_wisp[kept], w as u32);
            assert_eq!(thin.strand_weights[kept], layout.strand_weights[full]);
            assert_eq!(thin.strand_phase[kept], layout.strand_phase[full]);
            assert_eq!(thin.strand_length[kept], layout.strand_length[full]);
        }
    }
    // Fibres in all: 3,350 strands × 30 = 1,206 × 83.33.
    let before = layout.count() as f64 * style.strands.fibers_per_strand as f64;
    let after = thin.count() as f64 * thin_style.strands.fibers_per_strand as f64;
    assert!((after / before - 1.0).abs() < 1e-6, "{before} -> {after}");
}

#[test]
fn the_whole_and_degenerate_fractions_are_safe() {
    let style = Hairstyle::default_curly();
    let (_, layout) = generate(&style);
    let (same_style, same) = thin_strands(style.clone(), layout.clone(), 1.0);
    assert_eq!(same_style, style);
    assert_eq!(same.strand_weights, layout.strand_weights);
    // Non-finite or out of range: clamped, never an empty wisp or a NaN fibre count.
    for f in [f32::NAN, 2.0, 0.0, -1.0, 1e-9] {
        let (s, l) = thin_strands(style.clone(), layout.clone(), f);
        assert!(l.count() >= layout.wisp_guides.len(), "{f}: {}", l.count());
        assert!(s.strands.fibers_per_strand.is_finite() && s.strands.fibers_per_strand > 0.0);
    }
}

#[test]
fn an_imported_layout_keeps_each_kept_strands_own_offsets() {
    let style = Hairstyle::default_smooth();
    let (_, mut layout) = generate(&style);
    let ppg = layout.points_per_strand;
    // An offset per strand that names it: strand i's points all carry (i, 0, 0).
    layout.rest_offset = (0..layout.count())
        .flat_map(|i| std::iter::repeat_n(glam::Vec3::new(i as f32, 0.0, 0.0), ppg))
        .collect();
    let (_, thin) = thin_strands(style.clone(), layout.clone(), 0.5);
    assert_eq!(thin.rest_offset.len(), thin.count() * ppg);
    // 25 a wisp, 13 kept: the kept strand k of wisp w is full strand 25 w + k.
    for (kept, chunk) in thin.rest_offset.chunks(ppg).enumerate() {
        let full = (kept / 13) * 25 + kept % 13;
        assert!(chunk.iter().all(|p| p.x == full as f32), "kept {kept}");
    }
}

#[test]
fn the_estimate_and_the_thinning_keep_the_same_count() {
    // `kept_strands` is the one rule: the engine's memory estimate (`RunSizes`) counts with it
    // and `thin_strands` keeps it of every wisp, for awkward fractions too.
    let style = Hairstyle::default_smooth();
    let (_, layout) = generate(&style);
    for f in [0.1f32, 1.0 / 3.0, 0.5, 0.77, 1e-9, f32::NAN] {
        let kept = kept_strands(style.wisps.strands_per_wisp, f);
        let (s, l) = thin_strands(style.clone(), layout.clone(), f);
        assert_eq!(l.count(), 134 * kept as usize, "{f}");
        assert_eq!(s.wisps.strands_per_wisp, kept, "{f}");
    }
    assert_eq!(
        kept_strands(30, 0.1),
        3,
        "0.1 of 30 is 3, not 4 from 0.1's rounding"
    );
    assert_eq!(kept_strands(0, 0.5), 0);
}
